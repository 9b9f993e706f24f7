#include "clothref/fast/grid_springs.h"

#include <algorithm>
#include <cmath>

#include "clothref/formula/course_formulas.h"

namespace clothref::fast {

namespace {

static_assert(std::size(formula::kGridFamilyRest) == kGridFamilies);

int roundUp(int value, int multiple) { return (value + multiple - 1) / multiple * multiple; }

}  // namespace

template <typename T>
bool matchCourseGrid(int count, std::span<const std::uint32_t> start,
                     std::span<const std::uint32_t> end, std::span<const T> rest, int threads,
                     GridSpringWorkspace<T>& workspace) {
  const int n = static_cast<int>(std::lround(std::sqrt(double(count))));
  if (n < 2 || n * n != count || start.size() != end.size() || start.size() != rest.size())
    return false;
  GridSpringWorkspace<T> w;
  w.count = count;
  w.offset = {1, n, n + 1, n - 1, 2, 2 * n};
  w.padding = roundUp(std::max(2 * n, kMaxLanes), kMaxLanes);
  for (auto& mask : w.start_valid) mask.assign(std::size_t(count + 2 * w.padding), 0);
  std::array<bool, kGridFamilies> rest_seen{};
  std::size_t k = 0;
  bool matches = true;
  formula::forEachGridSpring(n, [&](int family, int s, int e) {
    if (!matches) return;
    if (k >= start.size() || int(start[k]) != s || int(end[k]) != e) {
      matches = false;
      return;
    }
    // one rest length per family, compared as bits (a NaN rest length keeps the general path)
    if (!rest_seen[family]) {
      w.rest[family] = rest[k];
      rest_seen[family] = true;
    } else if (!(rest[k] == w.rest[family]) ||
               std::signbit(rest[k]) != std::signbit(w.rest[family])) {
      matches = false;
      return;
    }
    w.start_valid[family][std::size_t(w.padding + s)] = ~MaskWord<T>(0);
    ++k;
  });
  if (!matches || k != start.size()) return false;
  for (auto* arrays : {&w.x, &w.v, &w.a})
    for (auto& array : *arrays) array.assign(std::size_t(count + 2 * w.padding), T(0));
  w.inverse_mass.assign(std::size_t(count + 2 * w.padding), T(0));
  w.velocity_w.assign(std::size_t(count + 2 * w.padding), T(0));
  w.acceleration_w.assign(std::size_t(count + 2 * w.padding), T(0));
  w.force.resize(std::size_t(std::max(threads, 1)));
  for (auto& per_thread : w.force)
    for (auto& per_family : per_thread)
      for (auto& array : per_family) array.assign(std::size_t(count + 2 * w.padding), T(0));
  workspace = std::move(w);
  return true;
}

namespace {

template <typename T>
void load(const GridLoad<T>& l, SimdPath path) {
  switch (path) {
    case SimdPath::Sse2:
      return loadGridStateSse2(l);
    case SimdPath::Avx2:
      return loadGridStateAvx2(l);
    case SimdPath::Avx512:
      return loadGridStateAvx512(l);
  }
}

template <typename T>
void sweep(const GridSweep<T>& s, SimdPath path) {
  switch (path) {
    case SimdPath::Sse2:
      return sweepGridSpringsSse2(s);
    case SimdPath::Avx2:
      return sweepGridSpringsAvx2(s);
    case SimdPath::Avx512:
      return sweepGridSpringsAvx512(s);
  }
}

// One evaluation split over threads: thread i owns particles [i * chunk, (i + 1) * chunk).
template <typename T>
struct ThreadedEvaluation {
  GridLoad<T> load;
  GridSweep<T> sweep;
  SimdPath path;
  int chunk;  // a multiple of kMaxLanes
  GridSpringWorkspace<T>* workspace;
};

template <typename T>
bool threadRange(const ThreadedEvaluation<T>& t, int index, int& begin, int& end) {
  begin = std::min(index * t.chunk, t.sweep.count);
  end = std::min(begin + t.chunk, t.sweep.count);
  return begin < end;
}

template <typename T>
void runThreadLoad(void* context, int index) {
  const auto& t = *static_cast<const ThreadedEvaluation<T>*>(context);
  GridLoad<T> l = t.load;
  if (threadRange(t, index, l.begin, l.end)) load(l, t.path);
}

template <typename T>
void runThreadSweep(void* context, int index) {
  const auto& t = *static_cast<const ThreadedEvaluation<T>*>(context);
  GridSweep<T> s = t.sweep;
  if (!threadRange(t, index, s.begin, s.end)) return;
  for (std::size_t f = 0; f < kGridFamilies; ++f)
    for (std::size_t k = 0; k < 3; ++k)
      s.force[f][k] = t.workspace->force[std::size_t(index)][f][k].data() + t.workspace->padding;
  sweep(s, t.path);
}

}  // namespace

template <typename T>
void evaluateGridCloth(GridSpringWorkspace<T>& w, const T* position, const T* velocity,
                       T* acceleration, const T* mass, const T* inverse_mass, const T* gravity,
                       T viscous_coef, T spring_coef, T damper_coef, SimdPath path,
                       ThreadPool* pool) {
  const std::size_t pad = std::size_t(w.padding);
  ThreadedEvaluation<T> t;
  GridLoad<T>& l = t.load;
  GridSweep<T>& s = t.sweep;
  l.position = position;
  l.velocity = velocity;
  l.mass = mass;
  l.inverse_mass = inverse_mass;
  for (int k = 0; k < 4; ++k) l.gravity[k] = gravity[k];
  l.viscous_coef = viscous_coef;
  for (std::size_t k = 0; k < 3; ++k) {
    l.x[k] = w.x[k].data() + pad;
    l.v[k] = w.v[k].data() + pad;
    l.a[k] = w.a[k].data() + pad;
    s.x[k] = l.x[k];
    s.v[k] = l.v[k];
    s.a[k] = l.a[k];
  }
  l.inverse_mass_copy = w.inverse_mass.data() + pad;
  l.velocity_w = w.velocity_w.data() + pad;
  l.a_w = w.acceleration_w.data() + pad;
  s.a_w = l.a_w;
  s.inverse_mass = l.inverse_mass_copy;
  for (std::size_t f = 0; f < kGridFamilies; ++f) {
    s.start_valid[f] = w.start_valid[f].data() + pad;
    s.offset[f] = w.offset[f];
    s.rest[f] = w.rest[f];
  }
  s.spring_coef = spring_coef;
  s.damper_coef = damper_coef;
  s.acceleration = acceleration;
  s.count = w.count;
  t.path = path;
  t.workspace = &w;
  const int threads = pool ? std::min(pool->size(), int(w.force.size())) : 1;
  t.chunk = roundUp((w.count + threads - 1) / threads, kMaxLanes);
  if (threads > 1) {
    // every particle's copy must be loaded before any sweep reads its neighbours
    pool->run(&runThreadLoad<T>, &t);
    pool->run(&runThreadSweep<T>, &t);
  } else {
    runThreadLoad<T>(&t, 0);
    runThreadSweep<T>(&t, 0);
  }
}

#define CLOTHREF_INSTANTIATE(T)                                                              \
  template bool matchCourseGrid(int, std::span<const std::uint32_t>,                         \
                                std::span<const std::uint32_t>, std::span<const T>, int,     \
                                GridSpringWorkspace<T>&);                                    \
  template void evaluateGridCloth(GridSpringWorkspace<T>&, const T*, const T*, T*, const T*, \
                                  const T*, const T*, T, T, T, SimdPath, ThreadPool*);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref::fast

#include "clothref/fast/sphere_cloth_contacts.h"

#include <cmath>
#include <limits>
#include <type_traits>

#include "clothref/fast/contact_filter.h"
#include "clothref/formula/course_formulas.h"

namespace clothref::fast {

namespace {

// The filter passes a particle when its squared distance is at most
// (radius * (1 + kRelativeMargin) + kAbsoluteMargin)^2. The exact test accepts a pair only when
// its rounded |n| <= r; the filter's and the exact test's rounded distances are both within a few
// units in the last place of the true one (far below 1e-5 relative; the float filter also leaves
// out w^2 >= 0, which only lowers its distance), and the absolute margin covers squares that
// underflow into subnormals.
constexpr double kRelativeMargin = 1e-5;
template <typename T>
constexpr double kAbsoluteMargin = std::is_same_v<T, float> ? 1e-15 : 1e-140;

// The filter's threshold in T, rounded up; NaN (pass everything) for a NaN or negative radius,
// where the exact test alone must decide.
template <typename T>
T reachSquared(T radius) {
  const double reach = double(radius) * (1 + kRelativeMargin) + kAbsoluteMargin<T>;
  if (!(reach >= 0)) return std::numeric_limits<T>::quiet_NaN();
  const double squared = reach * reach;
  T rounded = T(squared);
  if (double(rounded) < squared)
    rounded = std::nextafter(rounded, std::numeric_limits<T>::infinity());
  return rounded;
}

// The filter as a plain loop on the course layout (double, where no SIMD path is provided): the
// first particle j in [begin, end) whose squared distance, in the course's order, is not greater
// than reach_squared (NaN counts as not greater); `end` if none.
template <typename T>
int findCandidate(const T* center, T reach_squared, const T* positions, int begin, int end) {
  for (int j = begin; j < end; ++j) {
    const T* x = positions + 4 * j;
    T n[4];
    for (int k = 0; k < 4; ++k) n[k] = center[k] - x[k];
    const T squared = (n[0] * n[0] + n[2] * n[2]) + (n[1] * n[1] + n[3] * n[3]);
    if (!(squared > reach_squared)) return j;
  }
  return end;
}

void copyContactPositions(SimdPath path, const float* positions, int particles, float* x, float* y,
                          float* z) {
  switch (path) {
    case SimdPath::Sse2:
      return copyContactPositionsSse2(positions, particles, x, y, z);
    case SimdPath::Avx2:
      return copyContactPositionsAvx2(positions, particles, x, y, z);
    case SimdPath::Avx512:
      return copyContactPositionsAvx512(positions, particles, x, y, z);
  }
}

long scanContacts(SimdPath path, const ContactScan& scan) {
  switch (path) {
    case SimdPath::Sse2:
      break;
    case SimdPath::Avx2:
      return scanContactsAvx2(scan);
    case SimdPath::Avx512:
      return scanContactsAvx512(scan);
  }
  return scanContactsSse2(scan);
}

// What the scan's callback needs: sphere i's exact contacts with the filter's copy kept current.
struct FloatScan {
  const ContactBodies<float>* bodies;
  int sphere;
  float restitution, correction;
  ContactWorkspace* workspace;
};

bool resolveFlagged(void* context, int j) {
  const FloatScan& s = *static_cast<const FloatScan*>(context);
  if (!resolveSphereParticleContact(*s.bodies, s.sphere, j, s.restitution, s.correction))
    return false;
  // particle j moved: the copy follows, w folded in as copyContactPositions does
  const float* x = s.bodies->cloth_position + 4 * j;
  const float w = x[3] * 0.0f;
  s.workspace->x[std::size_t(j)] = x[0] + w;
  s.workspace->y[std::size_t(j)] = x[1] + w;
  s.workspace->z[std::size_t(j)] = x[2] + w;
  return true;
}

long collide(const ContactBodies<float>& bodies, float restitution, float correction, SimdPath path,
             ContactWorkspace& workspace) {
  if (bodies.spheres == 0) return 0;  // no pass would read the copy
  const std::size_t padded =
      std::size_t((bodies.particles + kContactBlock - 1) / kContactBlock * kContactBlock);
  if (workspace.x.size() < padded)
    for (auto* array : {&workspace.x, &workspace.y, &workspace.z}) array->assign(padded, 0.0f);
  copyContactPositions(path, bodies.cloth_position, bodies.particles, workspace.x.data(),
                       workspace.y.data(), workspace.z.data());
  long tested = 0;
  for (int i = 0; i < bodies.spheres; ++i) {
    FloatScan context{&bodies, i, restitution, correction, &workspace};
    const ContactScan scan{workspace.x.data(),
                           workspace.y.data(),
                           workspace.z.data(),
                           bodies.particles,
                           bodies.sphere_position + 4 * i,
                           reachSquared(bodies.radius[i]),
                           &resolveFlagged,
                           &context};
    tested += scanContacts(path, scan);
  }
  return tested;
}

long collide(const ContactBodies<double>& bodies, double restitution, double correction, SimdPath,
             ContactWorkspace&) {
  long tested = 0;
  for (int i = 0; i < bodies.spheres; ++i) {
    const double reach_squared = reachSquared(bodies.radius[i]);
    // the centre moves with every contact, so the filter restarts after each tested pair
    for (int j = 0;; ++j) {
      j = findCandidate(bodies.sphere_position + 4 * i, reach_squared, bodies.cloth_position, j,
                        bodies.particles);
      if (j >= bodies.particles) break;
      resolveSphereParticleContact(bodies, i, j, restitution, correction);
      ++tested;
    }
  }
  return tested;
}

}  // namespace

template <typename T>
bool resolveSphereParticleContact(const ContactBodies<T>& bodies, int i, int j, T restitution,
                                  T correction) {
  // the course's contact, written once (course_formulas.h): the oracle's bits by construction
  return formula::resolveContact(bodies.sphere_position + 4 * i, bodies.sphere_velocity + 4 * i,
                                 bodies.sphere_inverse_mass[i], bodies.cloth_position + 4 * j,
                                 bodies.cloth_velocity + 4 * j, bodies.cloth_inverse_mass[j],
                                 bodies.radius[i], restitution, correction);
}

template <typename T>
long collideSpheresWithCloth(const ContactBodies<T>& bodies, T restitution, T correction,
                             SimdPath path, ContactWorkspace& workspace) {
  return collide(bodies, restitution, correction, path, workspace);
}

#define CLOTHREF_INSTANTIATE(T)                                                  \
  template long collideSpheresWithCloth(const ContactBodies<T>&, T, T, SimdPath, \
                                        ContactWorkspace&);                      \
  template bool resolveSphereParticleContact(const ContactBodies<T>&, int, int, T, T);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref::fast

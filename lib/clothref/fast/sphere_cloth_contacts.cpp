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
// units in the last place of the true one (far below 1e-5 relative), and the absolute margin
// covers squares that underflow into subnormals.
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

// The filter as a plain loop (double, where no SIMD path is provided).
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

int findCandidate(SimdPath path, const float* center, float reach_squared, const float* positions,
                  int begin, int end) {
  switch (path) {
    case SimdPath::Sse2:
      break;
    case SimdPath::Avx2:
      return findContactCandidateAvx2(center, reach_squared, positions, begin, end);
    case SimdPath::Avx512:
      return findContactCandidateAvx512(center, reach_squared, positions, begin, end);
  }
  return findContactCandidateSse2(center, reach_squared, positions, begin, end);
}

int findCandidate(SimdPath, const double* center, double reach_squared, const double* positions,
                  int begin, int end) {
  return findCandidate<double>(center, reach_squared, positions, begin, end);
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
                             SimdPath path) {
  long tested = 0;
  for (int i = 0; i < bodies.spheres; ++i) {
    const T reach_squared = reachSquared(bodies.radius[i]);
    // the centre moves with every contact, so the filter restarts after each tested pair
    for (int j = 0;; ++j) {
      j = findCandidate(path, bodies.sphere_position + 4 * i, reach_squared, bodies.cloth_position,
                        j, bodies.particles);
      if (j >= bodies.particles) break;
      resolveSphereParticleContact(bodies, i, j, restitution, correction);
      ++tested;
    }
  }
  return tested;
}

#define CLOTHREF_INSTANTIATE(T)                                                   \
  template long collideSpheresWithCloth(const ContactBodies<T>&, T, T, SimdPath); \
  template bool resolveSphereParticleContact(const ContactBodies<T>&, int, int, T, T);
CLOTHREF_INSTANTIATE(float)
CLOTHREF_INSTANTIATE(double)
#undef CLOTHREF_INSTANTIATE

}  // namespace clothref::fast

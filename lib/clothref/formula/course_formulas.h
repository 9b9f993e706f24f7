// The course's formulas, each written once: the external force (gravity and drag) on one
// particle, the spring force of one spring, the contact of a
// sphere with a particle (or another sphere), and the spring topology of the course's grid. Plain
// inline templates on the course's 4-value columns (x, y, z, w; Eigen's Vector4 data()), the
// scalar type a parameter, the standard library only, so both sides include this header: the
// library (core's course-form stubs, fast's scalar contact path and grid matcher) and the course
// side (the grader's driver, built with a student's files).
//
// Each formula evaluates the course's Eigen expression operation for operation, in the order
// Eigen's 4-wide reductions use for a Vector4: a squared length or dot product is
// (lane 0 + lane 2) + (lane 1 + lane 3); normalize() divides by sqrt(squared length) and leaves a
// zero vector alone. No FMA (the project builds with -ffp-contract=off). Where a copy must remain
// (the SIMD lanes of fast/spring_kernels_impl.h and fast/contact_filter_impl.h, the student-shaped
// files of tools/grader/reference/), docs/design.md lists it with the test that proves it
// bit-equal.
#pragma once

#include <cmath>

namespace clothref::formula {

// Eigen's 4-wide reduction of a . b.
template <typename T>
inline T dot4(const T* a, const T* b) {
  return (a[0] * b[0] + a[2] * b[2]) + (a[1] * b[1] + a[3] * b[3]);
}

// The steps of the two formulas below that a caller may vary, one switch per step, each read on
// one line: CourseSpring and CourseContact hold the course's value of every switch at compile
// time, so the library's code is the course's line for line. A caller that varies a step passes
// its own struct with the same names (docs/design.md: the copies and who varies what).
struct CourseSpring {
  static constexpr bool spring_negated = false;       // the Hooke term k_s (|d| - rest), negated
  static constexpr bool damper_negated = false;       // the damper term, negated
  static constexpr bool no_damper = false;            // the damper term, left out
  static constexpr bool damper_unnormalised = false;  // the damper's projection on d, not on n
};
struct CourseContact {
  static constexpr bool normal_flipped = false;     // the normal, from a to b
  static constexpr bool touching_skipped = false;   // the contact test, penetration 0 excluded
  static constexpr bool separating_pushed = false;  // the approach test, left out
  static constexpr bool full_velocity = false;      // the impulse's velocity, v_rel not its normal
  static constexpr bool undivided = false;          // the impulse, not divided by 1/m_a + 1/m_b
  static constexpr bool moves_a = true;             // the correction of body a
  static constexpr bool moves_b = true;             // the correction of body b
};

// Shape::computeExternalForce for one particle, as an acceleration (m/s^2): gravity less the
// viscous drag, a = g - (v c) (1/m), per component in that order; a fixed particle (mass 0) gets
// none.
template <typename T>
inline void externalAcceleration(const T* velocity, T mass, T inverse_mass, const T* gravity,
                                 T viscous_coef, T acceleration[4]) {
  for (int k = 0; k < 4; ++k)
    acceleration[k] =
        mass == T(0) ? T(0) : gravity[k] - (velocity[k] * viscous_coef) * inverse_mass;
}

// Stub 2's per-spring force (Cloth::computeSpringForce): with d = x_s - x_e and n = d / |d|,
//   F = n (k_d ((v_s - v_e) . n) + k_s (|d| - rest))
// the force on the start particle is -F, on the end particle +F (newtons).
template <typename T, typename Variant = CourseSpring>
inline void springForce(const T* x_start, const T* x_end, const T* v_start, const T* v_end,
                        T rest_length, T spring_coef, T damper_coef, T force[4],
                        const Variant& variant = {}) {
  T d[4], n[4];
  for (int k = 0; k < 4; ++k) d[k] = n[k] = x_start[k] - x_end[k];
  const T squared = dot4(n, n);
  const T length = std::sqrt(squared);
  if (squared > T(0))  // Eigen's normalize leaves a zero vector alone
    for (int k = 0; k < 4; ++k) n[k] = n[k] / length;
  T relative[4];
  for (int k = 0; k < 4; ++k) relative[k] = v_start[k] - v_end[k];
  T damper = damper_coef * dot4(relative, variant.damper_unnormalised ? d : n);
  T spring = spring_coef * (length - rest_length);
  if (variant.spring_negated) spring = -spring;
  if (variant.damper_negated) damper = -damper;
  if (variant.no_damper) damper = T(0);
  const T scalar = damper + spring;
  for (int k = 0; k < 4; ++k) force[k] = n[k] * scalar;
}

// The contact of stubs 3 and 4 (Spheres::collide): body a (the sphere) and body b (a cloth
// particle or another sphere), normal n from b to a. When |x_a - x_b| <= contact_distance:
//   if a and b approach ((v_a - v_b) . n < 0), the impulse J = (-(1 + e) (n ((v_a - v_b) . n)))
//   / (1/m_b + 1/m_a) moves v_a by J/m_a and v_b by -J/m_b (the course forms the normal velocity
//   n (v_rel . n) first: -(1 + e) n s would round differently when e != 0);
//   then the positions move apart by (penetration n) correction each.
// Returns whether the bodies were in contact.
template <typename T, typename Variant = CourseContact>
inline bool resolveContact(T* x_a, T* v_a, T inverse_mass_a, T* x_b, T* v_b, T inverse_mass_b,
                           T contact_distance, T restitution, T correction,
                           const Variant& variant = {}) {
  T n[4];
  for (int k = 0; k < 4; ++k) n[k] = variant.normal_flipped ? -(x_a[k] - x_b[k]) : x_a[k] - x_b[k];
  const T squared = dot4(n, n);
  const T penetration = contact_distance - std::sqrt(squared);
  if (penetration < T(0) || (variant.touching_skipped && penetration <= T(0))) return false;
  if (squared > T(0)) {
    const T length = std::sqrt(squared);
    for (int k = 0; k < 4; ++k) n[k] = n[k] / length;
  }
  T relative[4];
  for (int k = 0; k < 4; ++k) relative[k] = v_a[k] - v_b[k];
  const T approach = dot4(relative, n);
  if (approach < T(0) || variant.separating_pushed) {
    const T factor = -(T(1) + restitution);
    const T denominator = inverse_mass_b + inverse_mass_a;
    for (int k = 0; k < 4; ++k) {
      const T normal = variant.full_velocity ? relative[k] : n[k] * approach;
      const T impulse = variant.undivided ? factor * normal : (factor * normal) / denominator;
      v_a[k] += impulse * inverse_mass_a;
      v_b[k] -= impulse * inverse_mass_b;
    }
  }
  for (int k = 0; k < 4; ++k) {
    const T shift = (penetration * n[k]) * correction;
    if (variant.moves_a) x_a[k] += shift;
    if (variant.moves_b) x_b[k] -= shift;
  }
  return true;
}

// Stub 1's topology (Cloth::initializeSpring) for an n x n grid, particle i * n + j in row i,
// column j: f(family, start, end) for every spring in the course's push order, six passes:
//   0 structural along a row (j, j + 1)      1 structural along a column (i, i + 1)
//   2 shear (i, j) - (i + 1, j + 1)          3 shear (i, j) - (i + 1, j - 1)
//   4 bend along a row (j, j + 2)            5 bend along a column (i, i + 2)
// A 2 x 2 grid has no bend springs. Families 0-1 use the rest length |x_0 - x_1|, 2-3
// |x_0 - x_(n+1)|, 4-5 |x_0 - x_2| (kGridFamilyRest).
enum class GridRest { Structural, Shear, Bend };
inline constexpr GridRest kGridFamilyRest[] = {GridRest::Structural, GridRest::Structural,
                                               GridRest::Shear,      GridRest::Shear,
                                               GridRest::Bend,       GridRest::Bend};

template <typename F>
inline void forEachGridSpring(int n, F&& f) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - 1; ++j) f(0, i * n + j, i * n + j + 1);
  for (int i = 0; i < n - 1; ++i)
    for (int j = 0; j < n; ++j) f(1, i * n + j, i * n + j + n);
  for (int i = 0; i < n - 1; ++i)
    for (int j = 0; j < n - 1; ++j) f(2, i * n + j, i * n + j + n + 1);
  for (int i = 0; i < n - 1; ++i)
    for (int j = 1; j < n; ++j) f(3, i * n + j, i * n + j + n - 1);
  if (n < 3) return;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - 2; ++j) f(4, i * n + j, i * n + j + 2);
  for (int i = 0; i < n - 2; ++i)
    for (int j = 0; j < n; ++j) f(5, i * n + j, i * n + j + 2 * n);
}

}  // namespace clothref::formula

// Cloth: the mass-spring body. Stubs 1 and 2 of the course live here:
//   initializeSpring    grid topology (structural, shear, bend) in the course's order
//   computeSpringForce  Hooke + damper forces along each spring, accumulated in spring order
// The same body also models the small scenes (one spring, one falling particle): a cloth is any set
// of particles joined by springs; the course's grid is made by initializeVertex + initializeSpring.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "clothref/base/enum_table.h"
#include "clothref/core/particles.h"

namespace clothref {

enum class SpringType { Structural, Shear, Bend };

inline constexpr EnumTable<SpringType, 3> kSpringTypeNames{{
    {SpringType::Structural, "structural"},
    {SpringType::Shear, "shear"},
    {SpringType::Bend, "bend"},
}};

// One spring between particles `start` < `end` (indices into the cloth's particles).
//   rest_length  metres
template <typename T>
struct Spring {
  std::uint32_t start;
  std::uint32_t end;
  T rest_length;
  SpringType type;
};

// The mass-spring body.
//   spring_coef  k_s, newtons / metre (the course's springCoef)
//   damper_coef  k_d, newton-seconds / metre (the course's damperCoef)
template <typename T>
struct Cloth {
  Particles<T> particles;
  std::vector<Spring<T>> springs;
  T spring_coef = T(0);
  T damper_coef = T(0);
};

// The course's Cloth::initializeVertex: an n x n grid in the plane y = `y`, spanning
// [-half_extent, half_extent] in x and z; particle i * n + j (row i, column j) sits at
// (-half_extent + j * step, y, -half_extent + i * step), step = 2 * half_extent / (n - 1).
// Every particle gets `particle_mass`. Fixed particles are set by the caller (setMass(..., 0)).
template <typename T>
Particles<T> initializeVertex(int particles_per_edge, T half_extent, T y, T particle_mass);

// Stub 1, the course's Cloth::initializeSpring: appends the grid springs of an n x n cloth in six
// row-major passes: horizontal structural, vertical structural, shear (i,j)-(i+1,j+1), shear
// (i,j)-(i+1,j-1), horizontal bend, vertical bend. Rest lengths are measured from the current
// positions: |p0 - p1| (both structural passes), |p0 - p(n+1)| (shear), |p0 - p2| (bend).
// Counts: 2n(n-1) structural, 2(n-1)^2 shear, 2n(n-2) bend. The passes are
// formula::forEachGridSpring (formula/course_formulas.h), which fast::matchCourseGrid walks too to
// recognise this topology (tests: fast/grid_springs_test.cpp, formula/course_formulas_test.cpp).
template <typename T>
void initializeSpring(Cloth<T>& cloth, int particles_per_edge);

// Stub 2, the course's Cloth::computeSpringForce: for each spring, in order, with d = x_s - x_e,
// L = |d|, n = d / L: F = n * (k_d * ((v_s - v_e) . n) + k_s * (L - rest)), then
// a_s -= F * invM_s and a_e += F * invM_e. Accumulates into the accelerations. F is
// formula::springForce (formula/course_formulas.h). On the course grid with the fast kernels on
// (the default), World's step runs its twin instead: fast::evaluateGridCloth, the same expression
// in SIMD lanes together with computeExternalForce, proven bit-equal by
// GridSprings.RandomStatesMatchTheOracleOnEveryPathAndSize (tests/fast/grid_springs_test.cpp),
// WorldEquivalence.* and verify's course-form rows (setExecution(world, false, ...) runs this).
template <typename T>
void computeSpringForce(Cloth<T>& cloth);

}  // namespace clothref

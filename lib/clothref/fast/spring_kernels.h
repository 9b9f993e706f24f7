// The spring-force sweeps of the course grid, one entry point per instruction set.
//
// The course's spring list is six constant-offset stencils over the n x n grid, pushed family by
// family in row-major order of the start particle: structural horizontal (+1), structural vertical
// (+n), shear down-right (+n+1), shear down-left (+n-1), bend horizontal (+2), bend vertical (+2n).
// Within a family a particle p receives its "end" contribution (the spring starting at p - offset)
// before its "start" contribution (the spring starting at p), and families come in list order, so
// sweeping family by family over particles reproduces the per-spring accumulation exactly.
//
// These functions see plain structure-of-arrays data only (no clothref types) and are compiled
// once per instruction set (spring_kernels_<isa>.cpp); grid_springs.h chooses between them.
#pragma once

#include <cstdint>
#include <type_traits>

namespace clothref::fast {

inline constexpr int kGridFamilies = 6;

// Mask words: all ones where a family's spring starts at that particle, zero elsewhere.
template <typename T>
using MaskWord = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;

// One call's work: particles [begin, end) get the spring accelerations of all six families.
// Every array is indexed by particle p in [-padding, count + padding) with padding >= the largest
// offset and >= 16 (the pointers point at particle 0), so stencil and vector reads past either edge
// stay in bounds; what they read there never reaches a result.
//   x, v          positions (metres) and velocities (metres / second), x, y, z arrays
//   a             accelerations (metres / second^2), accumulated into
//   inverse_mass  1 / kg, 0 for a fixed particle
//   start_valid   per family, the mask of particles where a spring of that family starts
//   force         per-call scratch, newtons, x, y, z arrays per family (same indexing)
//   offset, rest  per family: end - start, and rest length in metres
//   spring_coef, damper_coef  k_s (N/m), k_d (N s/m)
template <typename T>
struct GridSweep {
  const T* x[3];
  const T* v[3];
  T* a[3];
  const T* inverse_mass;
  const MaskWord<T>* start_valid[kGridFamilies];
  T* force[kGridFamilies][3];
  int offset[kGridFamilies];
  T rest[kGridFamilies];
  T spring_coef;
  T damper_coef;
  const T* a_w;     // the w lanes of the accelerations, written back unchanged
  T* acceleration;  // 4 x count, the course layout: [begin, end) is written back
  int count;
  int begin;
  int end;
};

// Loads particles [begin, end) of the course-layout state into the structure-of-arrays copy and
// sets their accelerations to the course's external force (Shape::computeExternalForce), which
// the sweep then accumulates into:
//   a = gravity - (v * viscous_coef) * invM per lane (w too) for a free particle, 0 for a fixed
//   one (mass 0).
//   position, velocity                4 x count, column-major (the course's layout)
//   mass, inverse_mass                count; kg and 1 / kg
//   gravity                           4 lanes, m / s^2; viscous_coef kg / s
//   x, v, a, inverse_mass_copy        the copy (GridSweep's arrays); velocity_w and a_w hold the
//                                     w lanes, which the sweeps carry unchanged
template <typename T>
struct GridLoad {
  const T* position;
  const T* velocity;
  const T* mass;
  const T* inverse_mass;
  T gravity[4];
  T viscous_coef;
  T* x[3];
  T* v[3];
  T* a[3];
  T* velocity_w;
  T* a_w;
  T* inverse_mass_copy;
  int begin;
  int end;
};

// The widest vector, in particles: ranges and padding are multiples of it.
inline constexpr int kMaxLanes = 16;

// The loads and the sweeps; identical results, different instruction sets. Ranges passed to them
// start at a multiple of 16 particles (except 0) so vector chunks never straddle two calls' ranges.
void loadGridStateSse2(const GridLoad<float>& load);
void loadGridStateSse2(const GridLoad<double>& load);
void loadGridStateAvx2(const GridLoad<float>& load);
void loadGridStateAvx2(const GridLoad<double>& load);
void loadGridStateAvx512(const GridLoad<float>& load);
void loadGridStateAvx512(const GridLoad<double>& load);
void sweepGridSpringsSse2(const GridSweep<float>& sweep);
void sweepGridSpringsSse2(const GridSweep<double>& sweep);
void sweepGridSpringsAvx2(const GridSweep<float>& sweep);
void sweepGridSpringsAvx2(const GridSweep<double>& sweep);
void sweepGridSpringsAvx512(const GridSweep<float>& sweep);
void sweepGridSpringsAvx512(const GridSweep<double>& sweep);

}  // namespace clothref::fast

// The cloth's derivative evaluation (external force, then spring forces) for a cloth whose spring
// list is exactly the course grid's, by stencil sweeps (spring_kernels.h) on a structure-of-arrays
// copy of the state. The course layout (4 x N, column per particle, w lane) stays the public
// state: each call copies x and v in and writes the accelerations back. Results are bit-identical
// to the course's computeExternalForce followed by its per-spring loop.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "clothref/fast/simd_path.h"
#include "clothref/fast/spring_kernels.h"
#include "clothref/fast/thread_pool.h"

namespace clothref::fast {

// Buffers and the grid's stencils, built once per cloth by matchCourseGrid.
template <typename T>
struct GridSpringWorkspace {
  int count = 0;    // particles, n * n
  int padding = 0;  // particles of padding each side of every array (spring_kernels.h)
  std::array<int, kGridFamilies> offset{};
  std::array<T, kGridFamilies> rest{};
  std::array<std::vector<MaskWord<T>>, kGridFamilies> start_valid;
  std::array<std::vector<T>, 3> x, v, a;
  std::vector<T> velocity_w, acceleration_w;  // the w lanes, carried unchanged
  std::vector<T> inverse_mass;
  // per thread, per family, x, y, z
  std::vector<std::array<std::array<std::vector<T>, 3>, kGridFamilies>> force;
};

// True when the springs (start[k], end[k], rest[k]) of a cloth of `count` particles are the course
// grid's six families in the course's order, each family with one rest length (bit for bit);
// then `workspace` is sized for it and for up to `threads` threads. False otherwise (the cloth
// keeps the general per-spring path).
template <typename T>
bool matchCourseGrid(int count, std::span<const std::uint32_t> start,
                     std::span<const std::uint32_t> end, std::span<const T> rest, int threads,
                     GridSpringWorkspace<T>& workspace);

// Sets `acceleration` to the course's external force (a = gravity - (v * viscous_coef) * invM, 0
// for a fixed particle) and then adds the grid's spring accelerations exactly as the course's loop
// (for each spring in order: a_s -= F invM_s, a_e += F invM_e) would.
//   position, velocity, acceleration  4 x count, column-major (x, y, z, w per particle)
//   mass, inverse_mass                count; kg (0 = fixed) and 1 / kg
//   gravity                           4 lanes (w = 0), m / s^2; viscous_coef kg / s
//   spring_coef, damper_coef          k_s (N/m), k_d (N s/m)
//   pool                              nullptr or a pool of at most the `threads` given above;
//                                     the work is split over particles, which keeps each
//                                     particle's accumulation order and so the bits
template <typename T>
void evaluateGridCloth(GridSpringWorkspace<T>& workspace, const T* position, const T* velocity,
                       T* acceleration, const T* mass, const T* inverse_mass, const T* gravity,
                       T viscous_coef, T spring_coef, T damper_coef, SimdPath path,
                       ThreadPool* pool);

}  // namespace clothref::fast

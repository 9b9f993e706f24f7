// The grid spring sweep, written once over a "batch" of lanes. Included only by the
// spring_kernels_<isa>.cpp files, each of which first defines, inside an anonymous namespace,
//   template <typename T> struct Batch  with  kLanes, V, Mask, load, store, broadcast, add, sub,
//   mul, div, sqrt, greaterThanZero, loadMask, select
// for its instruction set. Everything here then has internal linkage too, so the same template
// compiled with different -m flags never merges across translation units.
//
// The arithmetic is the course's per-spring expression, operation for operation, in the order
// Eigen's 4-wide reductions evaluate it for a Vector4 (lanes x, y, z, w with w = 0):
//   d = x_s - x_e;  z = (dx*dx + dz*dz) + (dy*dy + dw*dw);  L = sqrt(z)
//   n = z > 0 ? d / sqrt(z) : d             (Eigen's normalize leaves a zero vector alone)
//   dot = (dvx*nx + dvz*nz) + (dvy*ny + 0)  (the w lane contributes +0, which fixes the sign of 0)
//   F = n * (k_d * dot + k_s * (L - rest))
//   a_e += F * invM_e  (from the spring ending at p, first), then a_s -= F * invM_s
// dw*dw is +0 and adding +0 to dy*dy (>= +0) changes nothing, so that term is left out.
#pragma once

#include "clothref/fast/spring_kernels.h"

namespace {

template <typename T>
void loadGridStateImpl(const clothref::fast::GridLoad<T>& l) {
  using B = Batch<T>;
  using V = typename B::V;
  constexpr int kLanes = B::kLanes;
  // the course layout to the copy: restrict-qualified interleaved loops the compiler vectorizes
  {
    const T* __restrict position = l.position;
    const T* __restrict velocity = l.velocity;
    T* __restrict x0 = l.x[0];
    T* __restrict x1 = l.x[1];
    T* __restrict x2 = l.x[2];
    T* __restrict v0 = l.v[0];
    T* __restrict v1 = l.v[1];
    T* __restrict v2 = l.v[2];
    T* __restrict vw = l.velocity_w;
    for (int p = l.begin; p < l.end; ++p) {
      x0[p] = position[4 * p];
      x1[p] = position[4 * p + 1];
      x2[p] = position[4 * p + 2];
    }
    for (int p = l.begin; p < l.end; ++p) {
      v0[p] = velocity[4 * p];
      v1[p] = velocity[4 * p + 1];
      v2[p] = velocity[4 * p + 2];
      vw[p] = velocity[4 * p + 3];
    }
  }
  const V viscous = B::broadcast(l.viscous_coef);
  const V zero = B::broadcast(T(0));
  T* const a[4] = {l.a[0], l.a[1], l.a[2], l.a_w};
  const T* const v[4] = {l.v[0], l.v[1], l.v[2], l.velocity_w};
  int p = l.begin;
  for (; p + kLanes <= l.end; p += kLanes) {
    const auto fixed = B::equalToZero(B::load(l.mass + p));
    const V inverse_mass = B::load(l.inverse_mass + p);
    B::store(l.inverse_mass_copy + p, inverse_mass);
    for (int k = 0; k < 4; ++k) {
      const V ak = B::sub(B::broadcast(l.gravity[k]),
                          B::mul(B::mul(B::load(v[k] + p), viscous), inverse_mass));
      B::store(a[k] + p, B::select(fixed, zero, ak));
    }
  }
  for (; p < l.end; ++p) {
    l.inverse_mass_copy[p] = l.inverse_mass[p];
    for (int k = 0; k < 4; ++k)
      a[k][p] =
          l.mass[p] == T(0) ? T(0) : l.gravity[k] - (v[k][p] * l.viscous_coef) * l.inverse_mass[p];
  }
}

// Particles per tile: the forces of a tile's springs stay in cache until the tile's
// accumulation reads them. A multiple of every lane count.
constexpr int kTileParticles = 512;

template <typename T>
void sweepGridSpringsImpl(const clothref::fast::GridSweep<T>& s) {
  using B = Batch<T>;
  using V = typename B::V;
  using clothref::fast::kGridFamilies;
  constexpr int kLanes = B::kLanes;
  const V spring_coef = B::broadcast(s.spring_coef);
  const V damper_coef = B::broadcast(s.damper_coef);
  const V zero = B::broadcast(T(0));
  const T* const x0 = s.x[0];
  const T* const x1 = s.x[1];
  const T* const x2 = s.x[2];
  const T* const v0 = s.v[0];
  const T* const v1 = s.v[1];
  const T* const v2 = s.v[2];
  for (int tile = s.begin; tile < s.end; tile += kTileParticles) {
    const int tile_end = tile + kTileParticles < s.end ? tile + kTileParticles : s.end;
    // 1. the forces of every family's springs that start in this tile; the first tile also
    //    computes those starting up to `offset` before the range, whose end contributions land
    //    in it (same inputs, same bits as the neighbouring range's own computation)
    for (int family = 0; family < kGridFamilies; ++family) {
      const int offset = s.offset[family];
      const V rest = B::broadcast(s.rest[family]);
      T* const fx = s.force[family][0];
      T* const fy = s.force[family][1];
      T* const fz = s.force[family][2];
      const int lo = tile != s.begin ? tile : (s.begin > offset ? s.begin - offset : 0);
      const int hi = tile_end < s.count - offset ? tile_end : s.count - offset;
      for (int p = lo; p < hi; p += kLanes) {
        const V dx = B::sub(B::load(x0 + p), B::load(x0 + p + offset));
        const V dy = B::sub(B::load(x1 + p), B::load(x1 + p + offset));
        const V dz = B::sub(B::load(x2 + p), B::load(x2 + p + offset));
        const V squared = B::add(B::add(B::mul(dx, dx), B::mul(dz, dz)), B::mul(dy, dy));
        const V length = B::sqrt(squared);
        const auto positive = B::greaterThanZero(squared);
        const V nx = B::select(positive, B::div(dx, length), dx);
        const V ny = B::select(positive, B::div(dy, length), dy);
        const V nz = B::select(positive, B::div(dz, length), dz);
        const V dvx = B::sub(B::load(v0 + p), B::load(v0 + p + offset));
        const V dvy = B::sub(B::load(v1 + p), B::load(v1 + p + offset));
        const V dvz = B::sub(B::load(v2 + p), B::load(v2 + p + offset));
        const V dot =
            B::add(B::add(B::mul(dvx, nx), B::mul(dvz, nz)), B::add(B::mul(dvy, ny), zero));
        const V scalar =
            B::add(B::mul(damper_coef, dot), B::mul(spring_coef, B::sub(length, rest)));
        B::store(fx + p, B::mul(nx, scalar));
        B::store(fy + p, B::mul(ny, scalar));
        B::store(fz + p, B::mul(nz, scalar));
      }
    }
    // 2. every particle of the tile, families in list order, end contribution before start
    for (int p = tile; p < tile_end; p += kLanes) {
      const V inverse_mass = B::load(s.inverse_mass + p);
      V a[3] = {B::load(s.a[0] + p), B::load(s.a[1] + p), B::load(s.a[2] + p)};
      for (int family = 0; family < kGridFamilies; ++family) {
        const clothref::fast::MaskWord<T>* valid = s.start_valid[family];
        const int offset = s.offset[family];
        const auto ends_here = B::loadMask(valid + p - offset);
        const auto starts_here = B::loadMask(valid + p);
        for (int k = 0; k < 3; ++k) {
          const T* f = s.force[family][k];
          a[k] = B::select(ends_here, B::add(a[k], B::mul(B::load(f + p - offset), inverse_mass)),
                           a[k]);
          a[k] = B::select(starts_here, B::sub(a[k], B::mul(B::load(f + p), inverse_mass)), a[k]);
        }
      }
      for (int k = 0; k < 3; ++k) B::store(s.a[k] + p, a[k]);
    }
    // 3. back to the course layout, all four lanes (w as the load set it: the sweeps add nothing
    //    there)
    T* __restrict acceleration = s.acceleration;
    const T* __restrict a0 = s.a[0];
    const T* __restrict a1 = s.a[1];
    const T* __restrict a2 = s.a[2];
    const T* __restrict aw = s.a_w;
    for (int p = tile; p < tile_end; ++p) {
      acceleration[4 * p] = a0[p];
      acceleration[4 * p + 1] = a1[p];
      acceleration[4 * p + 2] = a2[p];
      acceleration[4 * p + 3] = aw[p];
    }
  }
}

}  // namespace

// The contact filter (contact_filter.h), written once over a "batch" of float lanes. Included only
// by the contact_filter_<isa>.cpp files, each of which first defines, inside an anonymous
// namespace,
//   struct Batch  with  kLanes, V, load, store, broadcast, add, sub, mul, notGreater (the lanes'
//   bits of !(a > b), NaN included) and transpose (kLanes particles of the course layout to x, y,
//   z and w vectors)
// for its instruction set. Everything here then has internal linkage too, so the same code
// compiled with different -m flags never merges across translation units.
#pragma once

#include <cstdint>

#include "clothref/fast/contact_filter.h"

namespace {

using clothref::fast::ContactScan;
using clothref::fast::kContactBlock;

// The fold of the w lane (contact_filter.h): + 0 for a finite w, NaN otherwise.
inline Batch::V foldW(Batch::V coordinate, Batch::V w) {
  return Batch::add(coordinate, Batch::mul(w, Batch::broadcast(0.0f)));
}

void copyContactPositionsImpl(const float* positions, int particles, float* x, float* y, float* z) {
  int j = 0;
  for (; j + Batch::kLanes <= particles; j += Batch::kLanes) {
    Batch::V c[4];
    Batch::transpose(positions + 4 * j, c);
    Batch::store(x + j, foldW(c[0], c[3]));
    Batch::store(y + j, foldW(c[1], c[3]));
    Batch::store(z + j, foldW(c[2], c[3]));
  }
  for (; j < particles; ++j) {
    const float* p = positions + 4 * j;
    const float w = p[3] * 0.0f;
    x[j] = p[0] + w;
    y[j] = p[1] + w;
    z[j] = p[2] + w;
  }
}

struct Centre {
  Batch::V x, y, z;
};

Centre loadCentre(const float* c) {
  const float w = c[3] * 0.0f;
  return {Batch::broadcast(c[0] + w), Batch::broadcast(c[1] + w), Batch::broadcast(c[2] + w)};
}

// Bit k set when particle j0 + k may touch, for the block's vectors from `first` on (the bits of
// the vectors before it are 0).
std::uint64_t flagBlock(const ContactScan& s, int j0, int first, const Centre& c, Batch::V reach) {
  std::uint64_t bits = 0;
  for (int v = first; v < kContactBlock / Batch::kLanes; ++v) {
    const int j = j0 + v * Batch::kLanes;
    const Batch::V dx = Batch::sub(c.x, Batch::load(s.x + j));
    const Batch::V dy = Batch::sub(c.y, Batch::load(s.y + j));
    const Batch::V dz = Batch::sub(c.z, Batch::load(s.z + j));
    const Batch::V squared =
        Batch::add(Batch::add(Batch::mul(dx, dx), Batch::mul(dy, dy)), Batch::mul(dz, dz));
    bits |= std::uint64_t(Batch::notGreater(squared, reach)) << (v * Batch::kLanes);
  }
  return bits;
}

long scanContactsImpl(const ContactScan& scan) {
  const ContactScan s = scan;  // a local copy: its pointers stay in registers across the calls
  const Batch::V reach = Batch::broadcast(s.reach_squared);
  Centre c = loadCentre(s.center);
  long tested = 0;
  for (int j0 = 0; j0 < s.particles; j0 += kContactBlock) {
    // the last block's padding holds no particles
    const int left = s.particles - j0;
    const std::uint64_t valid =
        left >= kContactBlock ? ~std::uint64_t(0) : (std::uint64_t(1) << left) - 1;
    std::uint64_t bits = flagBlock(s, j0, 0, c, reach) & valid;
    while (bits) {
      const int k = __builtin_ctzll(bits);
      ++tested;
      if (s.resolve(s.context, j0 + k)) {
        // the centre moved: flag the rest of the block again, from the vector holding k
        c = loadCentre(s.center);
        bits = flagBlock(s, j0, k / Batch::kLanes, c, reach) & valid;
      }
      bits &= k + 1 < kContactBlock ? ~std::uint64_t(0) << (k + 1) : 0;
    }
  }
  return tested;
}

}  // namespace

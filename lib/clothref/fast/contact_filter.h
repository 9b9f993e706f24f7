// The contact filter: which sphere-particle pairs may touch, several pairs per instruction. It is
// conservative (it may flag pairs the exact test then rejects, never the reverse), so it decides
// only what the exact per-pair test skips anyway, and never changes a bit of the result.
// It reads a structure-of-arrays copy of the cloth's positions (x, y and z arrays), made once per
// collide, so a vector holds one coordinate of consecutive particles and the squared distances
// need no permutes. One set of entry points per instruction set (contact_filter_<isa>.cpp); float
// only, since double runs are not the speed target (they use a plain loop on the course layout).
#pragma once

namespace clothref::fast {

// Particles per filter block: the copy's arrays are padded to a multiple of it.
inline constexpr int kContactBlock = 64;

// The copy: x[j] = position(0, j) + position(3, j) * 0, and the same for y and z (metres). The w
// lane is folded in that way (+-0 for a finite w, NaN otherwise) rather than kept: the filter then
// leaves out w^2 >= 0, which only lowers the distance, and a NaN or infinite w still gives a NaN
// distance, which is flagged (the exact test takes such pairs: a NaN length is not < 0).
//   positions  4 x particles, column-major (the course layout), metres
//   x, y, z    at least particles rounded up to kContactBlock each; the padding is not read as
//              particles (its flags are masked off)
void copyContactPositionsSse2(const float* positions, int particles, float* x, float* y, float* z);
void copyContactPositionsAvx2(const float* positions, int particles, float* x, float* y, float* z);
void copyContactPositionsAvx512(const float* positions, int particles, float* x, float* y,
                                float* z);

// One sphere's pass over the cloth, in particle order: every particle j whose squared distance to
// the centre, (dx^2 + dy^2) + dz^2 on the copy, is not greater than `reach_squared` (NaN counts
// as not greater) goes to `resolve`, the exact per-pair contact, which returns whether the pair
// touched. A touching contact moves the centre and particle j (and updates j in the copy), so the
// pass then re-reads the centre and flags the particles after j again.
struct ContactScan {
  const float* x;  // the copy (copyContactPositions*), metres
  const float* y;
  const float* z;
  int particles;
  const float* center;  // the sphere's 4 lanes (x, y, z, w), metres, w folded in like the copy's
  float reach_squared;  // square metres
  bool (*resolve)(void* context, int particle);
  void* context;
};

// Returns the number of particles passed to `resolve`.
long scanContactsSse2(const ContactScan& scan);
long scanContactsAvx2(const ContactScan& scan);
long scanContactsAvx512(const ContactScan& scan);

}  // namespace clothref::fast

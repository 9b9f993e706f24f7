// The contact filter: which sphere-particle pairs may touch, several pairs per instruction. It is
// conservative (it may flag pairs the exact test then rejects, never the reverse), so it decides
// only what the exact per-pair test skips anyway, and never changes a bit of the result.
// One entry point per instruction set (contact_filter_<isa>.cpp); float only, since double runs
// are not the speed target (they use the same code with a plain loop).
#pragma once

namespace clothref::fast {

// The first particle j in [begin, end) whose squared distance to `center`, computed in float in
// the course's order ((x^2 + z^2) + (y^2 + w^2) of center - x_j), is not greater than
// `reach_squared` (NaN counts as not greater); `end` if none.
//   center         4 lanes (x, y, z, w), metres
//   positions      4 x particles, column-major, metres
//   reach_squared  square metres
int findContactCandidateSse2(const float* center, float reach_squared, const float* positions,
                             int begin, int end);
int findContactCandidateAvx2(const float* center, float reach_squared, const float* positions,
                             int begin, int end);
int findContactCandidateAvx512(const float* center, float reach_squared, const float* positions,
                               int begin, int end);

}  // namespace clothref::fast

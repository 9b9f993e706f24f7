// The contact filter on AVX-512F: four particles (4 lanes each) per instruction, sixteen per loop.
// The maskz forms with a full mask are the plain instructions; GCC 12 warns on the plain
// intrinsics' undefined pass-through operand.
#include <immintrin.h>

#include "clothref/fast/contact_filter.h"

namespace clothref::fast {

namespace {

// Lane 0 of every 128-bit group gets (x^2 + z^2) + (y^2 + w^2) of c - x for four particles.
inline __m512 squaredDistances(__m512 c, const float* x) {
  const __m512 n = _mm512_sub_ps(c, _mm512_loadu_ps(x));
  const __m512 squares = _mm512_mul_ps(n, n);
  const __m512 pairs =
      _mm512_add_ps(squares, _mm512_maskz_permute_ps(0xFFFF, squares, 0x4E));  // x+z, y+w
  return _mm512_add_ps(pairs, _mm512_maskz_permute_ps(0xFFFF, pairs, 0xB1));
}

// Bits 0, 4, 8, 12: the lane-0 results of the four particles.
constexpr __mmask16 kParticleLanes = 0x1111;

}  // namespace

int findContactCandidateAvx512(const float* center, float reach_squared, const float* positions,
                               int begin, int end) {
  const __m512 c = _mm512_maskz_broadcast_f32x4(0xFFFF, _mm_loadu_ps(center));
  const __m512 reach = _mm512_set1_ps(reach_squared);
  int j = begin;
  for (; j + 16 <= end; j += 16) {
    const float* x = positions + 4 * j;
    // not greater: smaller, equal or NaN
    const __mmask16 m0 = _mm512_cmp_ps_mask(squaredDistances(c, x), reach, _CMP_NGT_UQ);
    const __mmask16 m1 = _mm512_cmp_ps_mask(squaredDistances(c, x + 16), reach, _CMP_NGT_UQ);
    const __mmask16 m2 = _mm512_cmp_ps_mask(squaredDistances(c, x + 32), reach, _CMP_NGT_UQ);
    const __mmask16 m3 = _mm512_cmp_ps_mask(squaredDistances(c, x + 48), reach, _CMP_NGT_UQ);
    if (((m0 | m1 | m2 | m3) & kParticleLanes) == 0) continue;
    const __mmask16 masks[4] = {m0, m1, m2, m3};
    for (int q = 0; q < 4; ++q) {
      const unsigned bits = masks[q] & kParticleLanes;
      if (bits) return j + 4 * q + __builtin_ctz(bits) / 4;
    }
  }
  for (; j + 4 <= end; j += 4) {
    const unsigned bits =
        _mm512_cmp_ps_mask(squaredDistances(c, positions + 4 * j), reach, _CMP_NGT_UQ) &
        kParticleLanes;
    if (bits) return j + __builtin_ctz(bits) / 4;
  }
  return findContactCandidateSse2(center, reach_squared, positions, j, end);
}

}  // namespace clothref::fast

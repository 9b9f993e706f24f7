// The contact filter on AVX2: two particles (4 lanes each) per instruction, eight per loop.
#include <immintrin.h>

#include "clothref/fast/contact_filter.h"

namespace clothref::fast {

namespace {

// Lane 0 of each 128-bit half gets (x^2 + z^2) + (y^2 + w^2) of c - x for two particles.
inline __m256 squaredDistances(__m256 c, const float* x) {
  const __m256 n = _mm256_sub_ps(c, _mm256_loadu_ps(x));
  const __m256 squares = _mm256_mul_ps(n, n);
  const __m256 pairs = _mm256_add_ps(squares, _mm256_permute_ps(squares, 0x4E));  // x+z, y+w
  return _mm256_add_ps(pairs, _mm256_permute_ps(pairs, 0xB1));
}

// Bits 0 and 4 of the sign mask: the lane-0 results of the two particles.
constexpr int kParticleLanes = 0x11;

}  // namespace

int findContactCandidateAvx2(const float* center, float reach_squared, const float* positions,
                             int begin, int end) {
  const __m128 c128 = _mm_loadu_ps(center);
  const __m256 c = _mm256_insertf128_ps(_mm256_castps128_ps256(c128), c128, 1);
  const __m256 reach = _mm256_set1_ps(reach_squared);
  int j = begin;
  for (; j + 8 <= end; j += 8) {
    const float* x = positions + 4 * j;
    // not greater: smaller, equal or NaN
    const int m0 = _mm256_movemask_ps(_mm256_cmp_ps(squaredDistances(c, x), reach, _CMP_NGT_UQ));
    const int m1 =
        _mm256_movemask_ps(_mm256_cmp_ps(squaredDistances(c, x + 8), reach, _CMP_NGT_UQ));
    const int m2 =
        _mm256_movemask_ps(_mm256_cmp_ps(squaredDistances(c, x + 16), reach, _CMP_NGT_UQ));
    const int m3 =
        _mm256_movemask_ps(_mm256_cmp_ps(squaredDistances(c, x + 24), reach, _CMP_NGT_UQ));
    if (((m0 | m1 | m2 | m3) & kParticleLanes) == 0) continue;
    const int masks[4] = {m0, m1, m2, m3};
    for (int q = 0; q < 4; ++q) {
      const unsigned bits = unsigned(masks[q] & kParticleLanes);
      if (bits) return j + 2 * q + __builtin_ctz(bits) / 4;
    }
  }
  return findContactCandidateSse2(center, reach_squared, positions, j, end);
}

}  // namespace clothref::fast

// The contact filter on SSE2: one particle (its 4 lanes) per instruction.
#include <immintrin.h>

#include "clothref/fast/contact_filter.h"

namespace clothref::fast {

int findContactCandidateSse2(const float* center, float reach_squared, const float* positions,
                             int begin, int end) {
  const __m128 c = _mm_loadu_ps(center);
  const __m128 reach = _mm_set_ss(reach_squared);
  for (int j = begin; j < end; ++j) {
    const __m128 n = _mm_sub_ps(c, _mm_loadu_ps(positions + 4 * j));
    const __m128 squares = _mm_mul_ps(n, n);
    const __m128 pairs = _mm_add_ps(squares, _mm_movehl_ps(squares, squares));  // x+z, y+w
    const __m128 sum = _mm_add_ss(pairs, _mm_shuffle_ps(pairs, pairs, 1));
    if (!_mm_comigt_ss(sum, reach)) return j;  // not greater: smaller, equal or NaN
  }
  return end;
}

}  // namespace clothref::fast

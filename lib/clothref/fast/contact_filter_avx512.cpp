// The contact filter on AVX-512F: sixteen particles per instruction.
#include <immintrin.h>

namespace {

struct Batch {
  static constexpr int kLanes = 16;
  using V = __m512;
  static V load(const float* p) { return _mm512_loadu_ps(p); }
  static void store(float* p, V v) { _mm512_storeu_ps(p, v); }
  static V broadcast(float a) { return _mm512_set1_ps(a); }
  static V add(V a, V b) { return _mm512_add_ps(a, b); }
  static V sub(V a, V b) { return _mm512_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm512_mul_ps(a, b); }
  static unsigned notGreater(V a, V b) { return _mm512_cmp_ps_mask(a, b, _CMP_NGT_UQ); }
  // particles p[0..15] (4 lanes each) to c[0] = their x, ..., c[3] = their w: two rounds of
  // two-source permutes (x and y, z and w of eight particles, then of sixteen)
  static void transpose(const float* p, V c[4]) {
    const __m512i xy8 = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
    const __m512i zw8 =
        _mm512_setr_epi32(2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27, 31);
    const __m512i low16 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 16, 17, 18, 19, 20, 21, 22, 23);
    const __m512i high16 =
        _mm512_setr_epi32(8, 9, 10, 11, 12, 13, 14, 15, 24, 25, 26, 27, 28, 29, 30, 31);
    const V r0 = load(p), r1 = load(p + 16), r2 = load(p + 32), r3 = load(p + 48);
    const V xy_low = _mm512_permutex2var_ps(r0, xy8, r1);
    const V zw_low = _mm512_permutex2var_ps(r0, zw8, r1);
    const V xy_high = _mm512_permutex2var_ps(r2, xy8, r3);
    const V zw_high = _mm512_permutex2var_ps(r2, zw8, r3);
    c[0] = _mm512_permutex2var_ps(xy_low, low16, xy_high);
    c[1] = _mm512_permutex2var_ps(xy_low, high16, xy_high);
    c[2] = _mm512_permutex2var_ps(zw_low, low16, zw_high);
    c[3] = _mm512_permutex2var_ps(zw_low, high16, zw_high);
  }
};

}  // namespace

#include "clothref/fast/contact_filter_impl.h"

namespace clothref::fast {

void copyContactPositionsAvx512(const float* positions, int particles, float* x, float* y,
                                float* z) {
  copyContactPositionsImpl(positions, particles, x, y, z);
}

long scanContactsAvx512(const ContactScan& scan) { return scanContactsImpl(scan); }

}  // namespace clothref::fast

// The contact filter on AVX2: eight particles per instruction.
#include <immintrin.h>

namespace {

struct Batch {
  static constexpr int kLanes = 8;
  using V = __m256;
  static V load(const float* p) { return _mm256_loadu_ps(p); }
  static void store(float* p, V v) { _mm256_storeu_ps(p, v); }
  static V broadcast(float a) { return _mm256_set1_ps(a); }
  static V add(V a, V b) { return _mm256_add_ps(a, b); }
  static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  static unsigned notGreater(V a, V b) {
    return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_NGT_UQ)));
  }
  // particles p[0..7] (4 lanes each) to c[0] = their x, ..., c[3] = their w: rows j and j + 4
  // share a register, then each 128-bit half is transposed as _MM_TRANSPOSE4_PS does
  static void transpose(const float* p, V c[4]) {
    V r[4];
    for (int k = 0; k < 4; ++k)
      r[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4 * k)),
                                  _mm_loadu_ps(p + 16 + 4 * k), 1);
    const V xy01 = _mm256_unpacklo_ps(r[0], r[1]), xy23 = _mm256_unpacklo_ps(r[2], r[3]);
    const V zw01 = _mm256_unpackhi_ps(r[0], r[1]), zw23 = _mm256_unpackhi_ps(r[2], r[3]);
    c[0] = _mm256_shuffle_ps(xy01, xy23, 0x44);
    c[1] = _mm256_shuffle_ps(xy01, xy23, 0xEE);
    c[2] = _mm256_shuffle_ps(zw01, zw23, 0x44);
    c[3] = _mm256_shuffle_ps(zw01, zw23, 0xEE);
  }
};

}  // namespace

#include "clothref/fast/contact_filter_impl.h"

namespace clothref::fast {

void copyContactPositionsAvx2(const float* positions, int particles, float* x, float* y, float* z) {
  copyContactPositionsImpl(positions, particles, x, y, z);
}

long scanContactsAvx2(const ContactScan& scan) { return scanContactsImpl(scan); }

}  // namespace clothref::fast

// The contact filter on SSE2: four particles per instruction, the x86-64 baseline.
#include <immintrin.h>

namespace {

struct Batch {
  static constexpr int kLanes = 4;
  using V = __m128;
  static V load(const float* p) { return _mm_loadu_ps(p); }
  static void store(float* p, V v) { _mm_storeu_ps(p, v); }
  static V broadcast(float a) { return _mm_set1_ps(a); }
  static V add(V a, V b) { return _mm_add_ps(a, b); }
  static V sub(V a, V b) { return _mm_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm_mul_ps(a, b); }
  static unsigned notGreater(V a, V b) { return unsigned(_mm_movemask_ps(_mm_cmpngt_ps(a, b))); }
  // particles p[0..3] (4 lanes each) to c[0] = their x, ..., c[3] = their w
  static void transpose(const float* p, V c[4]) {
    c[0] = load(p);
    c[1] = load(p + 4);
    c[2] = load(p + 8);
    c[3] = load(p + 12);
    _MM_TRANSPOSE4_PS(c[0], c[1], c[2], c[3]);
  }
};

}  // namespace

#include "clothref/fast/contact_filter_impl.h"

namespace clothref::fast {

void copyContactPositionsSse2(const float* positions, int particles, float* x, float* y, float* z) {
  copyContactPositionsImpl(positions, particles, x, y, z);
}

long scanContactsSse2(const ContactScan& scan) { return scanContactsImpl(scan); }

}  // namespace clothref::fast

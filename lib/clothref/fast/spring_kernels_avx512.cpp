// The grid spring sweep on AVX-512F (16 floats or 8 doubles per instruction; compiled with
// -mavx512f; -ffp-contract=off keeps FMA out). Lane selection uses the k mask registers.
#include <immintrin.h>

#include "clothref/fast/spring_kernels.h"

namespace {

template <typename T>
struct Batch;

template <>
struct Batch<float> {
  static constexpr int kLanes = 16;
  using V = __m512;
  using Mask = __mmask16;
  static V load(const float* p) { return _mm512_loadu_ps(p); }
  static void store(float* p, V v) { _mm512_storeu_ps(p, v); }
  static V broadcast(float x) { return _mm512_set1_ps(x); }
  static V add(V a, V b) { return _mm512_add_ps(a, b); }
  static V sub(V a, V b) { return _mm512_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm512_mul_ps(a, b); }
  static V div(V a, V b) { return _mm512_div_ps(a, b); }
  static V sqrt(V a) { return _mm512_maskz_sqrt_ps(0xFFFF, a); }  // maskz: GCC 12 warns on sqrt_ps
  static Mask greaterThanZero(V a) {
    return _mm512_cmp_ps_mask(a, _mm512_setzero_ps(), _CMP_GT_OQ);
  }
  static Mask equalToZero(V a) { return _mm512_cmp_ps_mask(a, _mm512_setzero_ps(), _CMP_EQ_OQ); }
  static Mask loadMask(const std::uint32_t* p) {
    const __m512i bits = _mm512_loadu_si512(p);
    return _mm512_test_epi32_mask(bits, bits);
  }
  static V select(Mask m, V a, V b) { return _mm512_mask_blend_ps(m, b, a); }
};

template <>
struct Batch<double> {
  static constexpr int kLanes = 8;
  using V = __m512d;
  using Mask = __mmask8;
  static V load(const double* p) { return _mm512_loadu_pd(p); }
  static void store(double* p, V v) { _mm512_storeu_pd(p, v); }
  static V broadcast(double x) { return _mm512_set1_pd(x); }
  static V add(V a, V b) { return _mm512_add_pd(a, b); }
  static V sub(V a, V b) { return _mm512_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm512_mul_pd(a, b); }
  static V div(V a, V b) { return _mm512_div_pd(a, b); }
  static V sqrt(V a) { return _mm512_maskz_sqrt_pd(0xFF, a); }
  static Mask greaterThanZero(V a) {
    return _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ);
  }
  static Mask equalToZero(V a) { return _mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_EQ_OQ); }
  static Mask loadMask(const std::uint64_t* p) {
    const __m512i bits = _mm512_loadu_si512(p);
    return _mm512_test_epi64_mask(bits, bits);
  }
  static V select(Mask m, V a, V b) { return _mm512_mask_blend_pd(m, b, a); }
};

}  // namespace

#include "clothref/fast/spring_kernels_impl.h"

namespace clothref::fast {

void loadGridStateAvx512(const GridLoad<float>& load) { loadGridStateImpl(load); }
void loadGridStateAvx512(const GridLoad<double>& load) { loadGridStateImpl(load); }
void sweepGridSpringsAvx512(const GridSweep<float>& sweep) { sweepGridSpringsImpl(sweep); }
void sweepGridSpringsAvx512(const GridSweep<double>& sweep) { sweepGridSpringsImpl(sweep); }

}  // namespace clothref::fast

// The grid spring sweep on AVX2 (8 floats or 4 doubles per instruction; compiled with -mavx2;
// -ffp-contract=off keeps FMA out).
#include <immintrin.h>

#include "clothref/fast/spring_kernels.h"

namespace {

template <typename T>
struct Batch;

template <>
struct Batch<float> {
  static constexpr int kLanes = 8;
  using V = __m256;
  using Mask = __m256;
  static V load(const float* p) { return _mm256_loadu_ps(p); }
  static void store(float* p, V v) { _mm256_storeu_ps(p, v); }
  static V broadcast(float x) { return _mm256_set1_ps(x); }
  static V add(V a, V b) { return _mm256_add_ps(a, b); }
  static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
  static V div(V a, V b) { return _mm256_div_ps(a, b); }
  static V sqrt(V a) { return _mm256_sqrt_ps(a); }
  static Mask greaterThanZero(V a) { return _mm256_cmp_ps(a, _mm256_setzero_ps(), _CMP_GT_OQ); }
  static Mask equalToZero(V a) { return _mm256_cmp_ps(a, _mm256_setzero_ps(), _CMP_EQ_OQ); }
  static Mask loadMask(const std::uint32_t* p) {
    return _mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
  }
  static V select(Mask m, V a, V b) { return _mm256_blendv_ps(b, a, m); }
};

template <>
struct Batch<double> {
  static constexpr int kLanes = 4;
  using V = __m256d;
  using Mask = __m256d;
  static V load(const double* p) { return _mm256_loadu_pd(p); }
  static void store(double* p, V v) { _mm256_storeu_pd(p, v); }
  static V broadcast(double x) { return _mm256_set1_pd(x); }
  static V add(V a, V b) { return _mm256_add_pd(a, b); }
  static V sub(V a, V b) { return _mm256_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm256_mul_pd(a, b); }
  static V div(V a, V b) { return _mm256_div_pd(a, b); }
  static V sqrt(V a) { return _mm256_sqrt_pd(a); }
  static Mask greaterThanZero(V a) { return _mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_GT_OQ); }
  static Mask equalToZero(V a) { return _mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_EQ_OQ); }
  static Mask loadMask(const std::uint64_t* p) {
    return _mm256_castsi256_pd(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
  }
  static V select(Mask m, V a, V b) { return _mm256_blendv_pd(b, a, m); }
};

}  // namespace

#include "clothref/fast/spring_kernels_impl.h"

namespace clothref::fast {

void loadGridStateAvx2(const GridLoad<float>& load) { loadGridStateImpl(load); }
void loadGridStateAvx2(const GridLoad<double>& load) { loadGridStateImpl(load); }
void sweepGridSpringsAvx2(const GridSweep<float>& sweep) { sweepGridSpringsImpl(sweep); }
void sweepGridSpringsAvx2(const GridSweep<double>& sweep) { sweepGridSpringsImpl(sweep); }

}  // namespace clothref::fast

// The grid spring sweep on SSE2 (4 floats or 2 doubles per instruction), the x86-64 baseline.
#include <immintrin.h>

#include "clothref/fast/spring_kernels.h"

namespace {

template <typename T>
struct Batch;

template <>
struct Batch<float> {
  static constexpr int kLanes = 4;
  using V = __m128;
  using Mask = __m128;
  static V load(const float* p) { return _mm_loadu_ps(p); }
  static void store(float* p, V v) { _mm_storeu_ps(p, v); }
  static V broadcast(float x) { return _mm_set1_ps(x); }
  static V add(V a, V b) { return _mm_add_ps(a, b); }
  static V sub(V a, V b) { return _mm_sub_ps(a, b); }
  static V mul(V a, V b) { return _mm_mul_ps(a, b); }
  static V div(V a, V b) { return _mm_div_ps(a, b); }
  static V sqrt(V a) { return _mm_sqrt_ps(a); }
  static Mask greaterThanZero(V a) { return _mm_cmpgt_ps(a, _mm_setzero_ps()); }
  static Mask equalToZero(V a) { return _mm_cmpeq_ps(a, _mm_setzero_ps()); }
  static Mask loadMask(const std::uint32_t* p) {
    return _mm_castsi128_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
  }
  static V select(Mask m, V a, V b) { return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b)); }
};

template <>
struct Batch<double> {
  static constexpr int kLanes = 2;
  using V = __m128d;
  using Mask = __m128d;
  static V load(const double* p) { return _mm_loadu_pd(p); }
  static void store(double* p, V v) { _mm_storeu_pd(p, v); }
  static V broadcast(double x) { return _mm_set1_pd(x); }
  static V add(V a, V b) { return _mm_add_pd(a, b); }
  static V sub(V a, V b) { return _mm_sub_pd(a, b); }
  static V mul(V a, V b) { return _mm_mul_pd(a, b); }
  static V div(V a, V b) { return _mm_div_pd(a, b); }
  static V sqrt(V a) { return _mm_sqrt_pd(a); }
  static Mask greaterThanZero(V a) { return _mm_cmpgt_pd(a, _mm_setzero_pd()); }
  static Mask equalToZero(V a) { return _mm_cmpeq_pd(a, _mm_setzero_pd()); }
  static Mask loadMask(const std::uint64_t* p) {
    return _mm_castsi128_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
  }
  static V select(Mask m, V a, V b) { return _mm_or_pd(_mm_and_pd(m, a), _mm_andnot_pd(m, b)); }
};

}  // namespace

#include "clothref/fast/spring_kernels_impl.h"

namespace clothref::fast {

void loadGridStateSse2(const GridLoad<float>& load) { loadGridStateImpl(load); }
void loadGridStateSse2(const GridLoad<double>& load) { loadGridStateImpl(load); }
void sweepGridSpringsSse2(const GridSweep<float>& sweep) { sweepGridSpringsImpl(sweep); }
void sweepGridSpringsSse2(const GridSweep<double>& sweep) { sweepGridSpringsImpl(sweep); }

}  // namespace clothref::fast

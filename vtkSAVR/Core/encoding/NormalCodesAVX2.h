#pragma once
// EncodeNormal four lanes at a time with AVX2, inline, for the kernels that encode normals
// while they are in registers (EncodeNormalsAVX2, and the grid's values-and-normals kernel).
// Operation for operation what EncodeNormal computes in double precision: the same bits.

#include "encoding/AttributeCodes.h"

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))

#include <immintrin.h>

#include <cstdint>
#include <limits>

namespace savr
{
namespace detail
{

// Four 64-bit lane masks as four 32-bit ones.
__attribute__((target("avx2"))) inline __m128i Narrow(__m256d mask)
{
  const __m256i low = _mm256_permutevar8x32_epi32(
    _mm256_castpd_si256(mask), _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6));
  return _mm256_castsi256_si128(low);
}

// An octahedral coordinate in [-1, 1] as its step, as EncodeNormal quantizes it.
__attribute__((target("avx2"))) inline __m128i OctahedralStep(__m256d c, int steps)
{
  const __m256d half = _mm256_set1_pd(0.5);
  const __m256d scaled = _mm256_add_pd(
    _mm256_mul_pd(_mm256_add_pd(_mm256_mul_pd(c, half), half), _mm256_set1_pd(steps - 1)), half);
  return _mm_min_epi32(
    _mm_max_epi32(_mm256_cvttpd_epi32(scaled), _mm_setzero_si128()), _mm_set1_epi32(steps - 1));
}

// EncodeNormal's codes of four gradients (x, y and z of each lane), operation for operation in
// double precision (so the same bits).
__attribute__((target("avx2"))) inline __m128i NormalCodes(__m256d x, __m256d y, __m256d z)
{
  constexpr int kSteps = kNormalSteps;
  const __m256d zero = _mm256_setzero_pd();
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d minusOne = _mm256_set1_pd(-1.0);
  const __m256d infinity = _mm256_set1_pd(std::numeric_limits<double>::infinity());
  const __m256d absMask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFFLL));
  const __m256d ax = _mm256_and_pd(x, absMask);
  const __m256d ay = _mm256_and_pd(y, absMask);
  const __m256d l1 = _mm256_add_pd(_mm256_add_pd(ax, ay), _mm256_and_pd(z, absMask));
  const __m256d valid =
    _mm256_and_pd(_mm256_cmp_pd(l1, zero, _CMP_GT_OQ), _mm256_cmp_pd(l1, infinity, _CMP_LT_OQ));
  __m256d u = _mm256_div_pd(x, l1);
  __m256d v = _mm256_div_pd(y, l1);
  const __m256d su = _mm256_blendv_pd(minusOne, one, _mm256_cmp_pd(u, zero, _CMP_GE_OQ));
  const __m256d sv = _mm256_blendv_pd(minusOne, one, _mm256_cmp_pd(v, zero, _CMP_GE_OQ));
  const __m256d fu = _mm256_mul_pd(_mm256_sub_pd(one, _mm256_and_pd(v, absMask)), su);
  const __m256d fv = _mm256_mul_pd(_mm256_sub_pd(one, _mm256_and_pd(u, absMask)), sv);
  const __m256d below = _mm256_cmp_pd(z, zero, _CMP_LT_OQ);
  u = _mm256_blendv_pd(u, fu, below);
  v = _mm256_blendv_pd(v, fv, below);
  const __m128i code = _mm_add_epi32(
    OctahedralStep(u, kSteps), _mm_mullo_epi32(OctahedralStep(v, kSteps), _mm_set1_epi32(kSteps)));
  return _mm_blendv_epi8(_mm_set1_epi32(kNoNormal), code, Narrow(valid));
}

} // namespace detail
} // namespace savr

#endif

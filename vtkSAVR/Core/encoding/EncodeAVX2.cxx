// The sample and normal encoders with AVX2 (see EncodeAVX2.h).

#include "encoding/EncodeAVX2.h"

#include "encoding/NormalCodesAVX2.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace savr
{
namespace detail
{

bool HaveAVX2()
{
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  static const bool have = __builtin_cpu_supports("avx2");
  return have;
#else
  return false;
#endif
}

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))

__attribute__((target("avx2"))) bool EncodeAVX2(double offset, double scale, std::uint32_t levels,
  std::uint32_t infiniteCode, std::uint32_t nanCode, const float* values, int n,
  std::uint32_t* codes)
{
  const __m256d offsetV = _mm256_set1_pd(offset);
  const __m256d scaleV = _mm256_set1_pd(scale);
  const __m256d zero = _mm256_setzero_pd();
  const __m256d top = _mm256_set1_pd(levels - 1.0);
  const __m256d half = _mm256_set1_pd(0.5);
  const __m128i topCode = _mm_set1_epi32(static_cast<int>(levels - 1));
  const __m128i nanV = _mm_set1_epi32(static_cast<int>(nanCode));
  const __m128i infiniteV = _mm_set1_epi32(static_cast<int>(infiniteCode));
  const __m128 infinity = _mm_set1_ps(std::numeric_limits<float>::infinity());
  const __m128 signMask = _mm_castsi128_ps(_mm_set1_epi32(0x7FFFFFFF));
  int i = 0;
  int numbers = 0; // lanes that were not NaN (bits of the groups' masks)
  for (; i + 4 <= n; i += 4)
  {
    const __m128 v = _mm_loadu_ps(values + i);
    numbers |= _mm_movemask_ps(_mm_cmp_ps(v, v, _CMP_ORD_Q));
    // As Encode: x = (value - offset) * scale; 0 unless x > 0; the top code from levels - 1 on;
    // else x + 0.5 truncated.
    const __m256d x = _mm256_mul_pd(_mm256_sub_pd(_mm256_cvtps_pd(v), offsetV), scaleV);
    const __m128i rounded = _mm256_cvttpd_epi32(_mm256_add_pd(x, half));
    const __m128i positive = Narrow(_mm256_cmp_pd(x, zero, _CMP_GT_OQ));
    const __m128i atTop = Narrow(_mm256_cmp_pd(x, top, _CMP_GE_OQ));
    __m128i code = _mm_blendv_epi8(rounded, topCode, atTop);
    code = _mm_and_si128(code, positive);
    // Infinities and NaN.
    const __m128 magnitude = _mm_and_ps(v, signMask);
    const __m128i isInfinite = _mm_castps_si128(_mm_cmp_ps(magnitude, infinity, _CMP_EQ_OQ));
    const __m128i isNaN = _mm_castps_si128(_mm_cmp_ps(v, v, _CMP_UNORD_Q));
    code = _mm_blendv_epi8(code, infiniteV, isInfinite);
    code = _mm_blendv_epi8(code, nanV, isNaN);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(codes + i), code);
  }
  for (; i < n; ++i)
  {
    const float v = values[i];
    if (v != v)
    {
      codes[i] = nanCode;
      continue;
    }
    numbers = 1;
    if (!std::isfinite(v))
    {
      codes[i] = infiniteCode;
      continue;
    }
    const double x = (v - offset) * scale;
    codes[i] =
      !(x > 0.0) ? 0u : (x >= levels - 1 ? levels - 1 : static_cast<std::uint32_t>(x + 0.5));
  }
  return numbers != 0;
}

__attribute__((target("avx2"))) void EncodeNormalsAVX2(
  const float* gradients, int n, std::uint16_t* normals)
{
  int i = 0;
  for (; i + 4 <= n; i += 4)
  {
    const float* g = gradients + 3 * static_cast<std::ptrdiff_t>(i);
    const __m128i codes = NormalCodes(_mm256_set_pd(g[9], g[6], g[3], g[0]),
      _mm256_set_pd(g[10], g[7], g[4], g[1]), _mm256_set_pd(g[11], g[8], g[5], g[2]));
    alignas(16) std::int32_t out[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(out), codes);
    for (int l = 0; l < 4; ++l)
    {
      normals[i + l] = static_cast<std::uint16_t>(out[l]);
    }
  }
  for (; i < n; ++i)
  {
    normals[i] = EncodeNormal(gradients + 3 * static_cast<std::ptrdiff_t>(i));
  }
}

#else

void EncodeNormalsAVX2(const float* gradients, int n, std::uint16_t* normals)
{
  for (int i = 0; i < n; ++i)
  {
    normals[i] = EncodeNormal(gradients + 3 * static_cast<std::ptrdiff_t>(i));
  }
}

bool EncodeAVX2(
  double, double, std::uint32_t, std::uint32_t, std::uint32_t, const float*, int, std::uint32_t*)
{
  return true;
}

#endif

} // namespace detail
} // namespace savr

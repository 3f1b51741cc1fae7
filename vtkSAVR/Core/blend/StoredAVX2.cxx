#include "blend/StoredAVX2.h"

#include <cstring>

namespace savr
{
namespace detail
{

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
__attribute__((target("avx2"))) void FileInSlotOfFour(
  std::uint8_t* rows, int slot, const std::uint32_t* codes, int count)
{
  const __m128i shift = _mm_cvtsi32_si128(8 * slot);
  const __m256i mask = _mm256_sll_epi32(_mm256_set1_epi32(0xFF), shift);
  int j = 0;
  for (; j + 8 <= count; j += 8)
  {
    const __m256i code = _mm256_sll_epi32(
      _mm256_and_si256(
        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(codes + j)), _mm256_set1_epi32(0xFF)),
      shift);
    __m256i* words = reinterpret_cast<__m256i*>(rows + 4 * static_cast<std::size_t>(j));
    _mm256_storeu_si256(words,
      slot == 0 ? code
                : _mm256_or_si256(_mm256_andnot_si256(mask, _mm256_loadu_si256(words)), code));
  }
  for (; j < count; ++j)
  {
    if (slot == 0)
    {
      std::memset(rows + 4 * static_cast<std::size_t>(j), 0, 4);
    }
    rows[4 * static_cast<std::size_t>(j) + slot] = static_cast<std::uint8_t>(codes[j]);
  }
}
#else
void FileInSlotOfFour(std::uint8_t* rows, int slot, const std::uint32_t* codes, int count)
{
  for (int j = 0; j < count; ++j)
  {
    if (slot == 0)
    {
      std::memset(rows + 4 * static_cast<std::size_t>(j), 0, 4);
    }
    rows[4 * static_cast<std::size_t>(j) + slot] = static_cast<std::uint8_t>(codes[j]);
  }
}
#endif

} // namespace detail
} // namespace savr

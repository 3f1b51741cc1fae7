#pragma once
// Sample codes and normal codes eight or four at a time with AVX2 where the CPU has it (chosen
// at run time): the same codes as SampleEncoding::Encode and EncodeNormal.

#include <cstdint>

namespace savr
{
namespace detail
{

/// Whether this CPU runs the AVX2 kernels (these, and the grid's).
bool HaveAVX2();

/// codes[i] = the stored code of values[i] for i in [0, n), exactly as SampleEncoding::Encode
/// gives it (offset, scale and levels from it), except that NaN becomes `nanCode`. Returns
/// whether any value was not NaN. AVX2 only.
bool EncodeAVX2(double offset, double scale, std::uint32_t levels, std::uint32_t infiniteCode,
  std::uint32_t nanCode, const float* values, int n, std::uint32_t* codes);

/// normals[i] = EncodeNormal(gradients + 3 i) for i in [0, n), the same bits, four at a time.
/// AVX2 only.
void EncodeNormalsAVX2(const float* gradients, int n, std::uint16_t* normals);

} // namespace detail
} // namespace savr

#include "encoding/SampleEncoding.h"

#include <algorithm>

namespace savr
{

namespace
{
// The part of `data` inside `window`, or the point of the window nearest to it; for integral
// data, to whole levels.
std::array<double, 2> WithinWindow(
  const std::array<double, 2>& data, const std::array<double, 2>& window, bool integral)
{
  if (!(window[0] <= window[1]) || !(data[0] <= data[1]))
  {
    return data;
  }
  std::array<double, 2> range = { std::max(data[0], window[0]), std::min(data[1], window[1]) };
  if (range[0] > range[1])
  {
    // Wholly outside: every sample takes the one code of the window's nearer end.
    range[0] = range[1] = data[0] > window[1] ? window[1] : window[0];
  }
  if (integral)
  {
    range = { std::max(data[0], std::floor(range[0])), std::min(data[1], std::ceil(range[1])) };
    if (range[0] > range[1])
    {
      range[1] = range[0];
    }
  }
  return range;
}
} // namespace

std::array<double, 2> SampleEncoding::ValuesToCode(
  const Sampler& sampler, std::array<double, 2> window)
{
  return WithinWindow(sampler.ValueRange(), window, sampler.ExactBits() > 0);
}

SampleEncoding SampleEncoding::ForSampler(
  const Sampler& sampler, bool fineCodes, std::array<double, 2> window)
{
  SampleEncoding e;
  const auto range = ValuesToCode(sampler, window);
  const double span = range[1] - range[0];
  e.HasNaNCode = sampler.MayReturnNaN();
  const std::uint32_t reserved = e.HasNaNCode ? 1u : 0u;
  e.Offset = range[0];
  // Samples travel as float: integers beyond 2^24 in magnitude are not exact there.
  const bool exact =
    sampler.ExactBits() > 0 && std::max(std::abs(range[0]), std::abs(range[1])) <= 16777216.0;
  // Fractional bits: as many as fit in 16 bits beside the levels (8 for 8-bit data).
  int bits = 0;
  while (fineCodes && exact && bits < 8 && (span + 1.0) * (1u << (bits + 1)) + reserved <= 65536.0)
  {
    ++bits;
  }
  if (bits > 0)
  {
    e.Bytes = 2;
    e.Levels = 65536u - reserved;
    e.Scale = static_cast<double>(1u << bits);
    e.FractionBits = bits;
  }
  else if (exact && span + reserved < 256.0)
  {
    e.Bytes = 1;
    e.Levels = 256u - reserved;
    e.Scale = 1.0;
  }
  else if (exact && span + reserved < 65536.0)
  {
    e.Bytes = 2;
    e.Levels = 65536u - reserved;
    e.Scale = 1.0;
  }
  else
  {
    e.Bytes = 2;
    e.Levels = 65536u - reserved;
    // Computed in double so that ranges near 1e-30 or 1e30 keep their resolution.
    e.Scale = span > 0.0 ? (e.Levels - 1) / span : 1.0;
    if (!std::isfinite(e.Scale) || e.Scale <= 0.0)
    {
      e.Scale = 1.0;
    }
  }
  e.NaNCode = e.Levels;
  return e;
}

} // namespace savr

#include "encoding/SampleEncoding.h"

#include <algorithm>

namespace savr
{

SampleEncoding SampleEncoding::ForSampler(const Sampler& sampler, bool fineCodes)
{
  SampleEncoding e;
  const auto range = sampler.ValueRange();
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

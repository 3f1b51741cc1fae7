#pragma once
// How a sample is stored: at the precision of the data and no more. Integral data whose range
// fits in 8 or 16 bits is stored exactly (rounded to the nearest integer after interpolation);
// anything else is normalized over its finite range into 16 bits. Non-finite samples get a code
// of their own when the sampler can produce them.

#include "Sampler.h"

#include <cmath>
#include <cstdint>

namespace savr
{

struct SampleEncoding
{
  int Bytes = 2;
  double Offset = 0.0;          // value of code 0
  double Scale = 1.0;           // codes per unit of value
  std::uint32_t Levels = 65536; // value codes are [0, Levels)
  bool HasNaNCode = false;
  std::uint32_t NaNCode = 0; // == Levels when HasNaNCode

  static SampleEncoding ForSampler(const Sampler& sampler);

  std::uint32_t Encode(float value) const
  {
    if (!std::isfinite(value))
    {
      return this->HasNaNCode ? this->NaNCode : 0u;
    }
    // Rounded by truncating x + 0.5 (x > 0 here): a libm call per sample would cost more.
    const double x = (value - this->Offset) * this->Scale;
    if (!(x > 0.0))
    {
      return 0u;
    }
    return x >= this->Levels - 1 ? this->Levels - 1 : static_cast<std::uint32_t>(x + 0.5);
  }

  double Decode(std::uint32_t code) const { return this->Offset + code / this->Scale; }

  /// Largest difference between a value inside the range and its decoded code.
  double MaxError() const { return 0.5 / this->Scale; }

  /// Number of entries a per-code table needs (value codes plus the NaN code).
  std::uint32_t TableSize() const { return this->Levels + (this->HasNaNCode ? 1u : 0u); }
};

} // namespace savr

#pragma once
// How a sample is stored: at the precision of the data and of the transfer function, no more.
// Integral data whose range fits in 8 or 16 bits is stored at its integer levels (an interpolated
// sample rounded to the nearest one), unless the transfer function has features narrower than a
// level: then the codes keep fractional bits, as many as 16 bits hold beside the range (8 for
// 8-bit data). Anything else is normalized over its finite range into 16 bits. Non-finite samples
// get a code of their own when the sampler can produce them.
// The codes need only cover what the transfer functions can tell apart: given a window (their
// domain), they span the part of the data's range inside it, and a sample beyond it takes the
// nearest end's code. An outlier then costs no precision where the image has detail.

#include "sampler/Sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

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
  int FractionBits = 0;      // bits below one level of integral data

  /// The whole line: every finite value is told apart.
  static constexpr std::array<double, 2> kWholeLine = { -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };

  /// The encoding of `sampler`'s samples; `fineCodes` keeps fractional bits for integral data
  /// (when 16 bits have room for any). The codes cover the data's finite range within `window`
  /// (widened to whole levels for integral data); data wholly outside it gets the one code of the
  /// window's nearer end.
  static SampleEncoding ForSampler(
    const Sampler& sampler, bool fineCodes = false, std::array<double, 2> window = kWholeLine);

  /// The values ForSampler's codes cover: the data's finite range within `window` (widened to
  /// whole levels for integral data), or the window's end nearer to the data.
  static std::array<double, 2> ValuesToCode(
    const Sampler& sampler, std::array<double, 2> window = kWholeLine);

  /// The values the codes stand for: [Decode(0), Decode(Levels - 1)].
  std::array<double, 2> CodedRange() const
  {
    return { this->Offset, this->Decode(this->Levels - 1) };
  }

  /// Whether samples stored in this encoding serve blends that would want `wanted`: they cover
  /// its coded range (to half of one of its codes), at least half as finely. (Coarser codes, or
  /// a range they do not reach, need the samples taken again.)
  bool Serves(const SampleEncoding& wanted) const
  {
    const double slack = 0.5 / wanted.Scale;
    const std::array<double, 2> have = this->CodedRange();
    const std::array<double, 2> want = wanted.CodedRange();
    return this->HasNaNCode == wanted.HasNaNCode && have[0] <= want[0] + slack &&
           have[1] >= want[1] - slack && this->Scale >= 0.5 * wanted.Scale;
  }

  /// Whether a transfer function, given as `opacity` and `color` (RGB, or the same gray three
  /// times; both clamped to [0, 1] as tables are) with its nodes at `nodes`, has a feature
  /// narrower than one code of this encoding: between the two codes either side of a node it
  /// strays from the straight line through their values by more than `tolerance`. Between its
  /// nodes a piecewise linear function is a line, so the nodes are where it can stray.
  template <typename Opacity, typename Color>
  bool HasFeaturesBetweenCodes(const double* nodes, std::size_t count, Opacity&& opacity,
    Color&& color, double tolerance = 1.0 / 64.0) const;

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

template <typename Opacity, typename Color>
bool SampleEncoding::HasFeaturesBetweenCodes(
  const double* nodes, std::size_t count, Opacity&& opacity, Color&& color, double tolerance) const
{
  const auto clamped = [](double v)
  { return std::isfinite(v) ? std::min(std::max(v, 0.0), 1.0) : 0.0; };
  for (std::size_t i = 0; i < count; ++i)
  {
    const double code = (nodes[i] - this->Offset) * this->Scale;
    if (!(code > 0.0 && code < this->Levels - 1.0))
    {
      continue;
    }
    const double below = std::floor(code);
    const double w = code - below;
    if (w == 0.0)
    {
      continue; // on a code: the table holds it
    }
    const double v0 = this->Decode(static_cast<std::uint32_t>(below));
    const double v1 = this->Decode(static_cast<std::uint32_t>(below) + 1u);
    const double a0 = clamped(opacity(v0));
    const double a1 = clamped(opacity(v1));
    const double a = clamped(opacity(nodes[i]));
    if (std::abs(a - ((1.0 - w) * a0 + w * a1)) > tolerance)
    {
      return true;
    }
    // A colour matters as far as it is seen: weighted by the opacity there.
    double c0[3], c1[3], c[3];
    color(v0, c0);
    color(v1, c1);
    color(nodes[i], c);
    for (int k = 0; k < 3; ++k)
    {
      const double line = (1.0 - w) * clamped(c0[k]) + w * clamped(c1[k]);
      if (std::abs(clamped(c[k]) - line) * std::max(a, std::max(a0, a1)) > tolerance)
      {
        return true;
      }
    }
  }
  return false;
}

} // namespace savr

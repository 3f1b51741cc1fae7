#include "TransferFunctionTable.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace savr
{

void TransferFunctionTable::Build(
  const SampleEncoding& encoding, const double* rgb, const double* opacity, double unitDistance)
{
  static std::atomic<std::uint64_t> builds{ 0 };
  this->Built = ++builds;
  this->Code = encoding;
  const std::uint32_t size = encoding.TableSize();
  this->RGB.assign(3 * size, 0.0f);
  this->Alpha.assign(size, 0.0f);
  this->Sigma.assign(size, 0.0);
  const double unit = unitDistance > 0.0 && std::isfinite(unitDistance) ? unitDistance : 1.0;
  for (std::uint32_t c = 0; c < encoding.Levels; ++c)
  {
    double a = opacity[c];
    a = std::isfinite(a) ? std::min(std::max(a, 0.0), 1.0) : 0.0;
    for (int i = 0; i < 3; ++i)
    {
      const double v = rgb[3 * c + i];
      this->RGB[3 * c + i] =
        static_cast<float>(std::isfinite(v) ? std::min(std::max(v, 0.0), 1.0) : 0.0);
    }
    this->Alpha[c] = static_cast<float>(a);
    const double depth = a < 1.0 ? -std::log1p(-a) : kMaxOpticalDepth;
    this->Sigma[c] = std::min(depth, kMaxOpticalDepth) / unit;
  }
}

double TransferFunctionTable::IntervalAlpha(std::uint32_t code, double h) const
{
  return -std::expm1(-this->Sigma[code] * h);
}

} // namespace savr

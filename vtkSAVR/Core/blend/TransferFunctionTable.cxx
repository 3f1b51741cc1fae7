#include "blend/TransferFunctionTable.h"

#include "blend/Composite.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace savr
{

void TransferFunctionTable::Build(const SampleEncoding& encoding, const double* rgb,
  const double* opacity, double unitDistance, double maxColor)
{
  const double most = maxColor > 0.0 && std::isfinite(maxColor) ? maxColor : 1.0;
  static std::atomic<std::uint64_t> builds{ 0 };
  this->Built = ++builds;
  this->Code = encoding;
  const std::uint32_t size = encoding.TableSize();
  this->RGB.assign(3 * size, 0.0f);
  this->Alpha.assign(size, 0.0f);
  this->Sigma.assign(size, 0.0);
  const double unit = unitDistance > 0.0 && std::isfinite(unitDistance) ? unitDistance : 1.0;
  this->Unit = unit;
  this->FirstTerms.clear();
  this->SecondTerms.clear();
  this->SecondLevels = 0;
  this->Levels = ComponentLevels();
  for (std::uint32_t c = 0; c < encoding.Levels; ++c)
  {
    double a = opacity[c];
    a = std::isfinite(a) ? std::min(std::max(a, 0.0), 1.0) : 0.0;
    for (int i = 0; i < 3; ++i)
    {
      const double v = rgb[3 * c + i];
      this->RGB[3 * c + i] =
        static_cast<float>(std::isfinite(v) ? std::min(std::max(v, 0.0), most) : 0.0);
    }
    this->Alpha[c] = static_cast<float>(a);
    const double depth = a < 1.0 ? -std::log1p(-a) : kMaxOpticalDepth;
    this->Sigma[c] = std::min(depth, kMaxOpticalDepth) / unit;
  }
  // Integrals per code step (the value step is the same between any two codes).
  this->SigmaIntegral.assign(size, 0.0);
  this->EmissionIntegral.assign(3 * size, 0.0);
  for (std::uint32_t c = 1; c < encoding.Levels; ++c)
  {
    this->SigmaIntegral[c] =
      this->SigmaIntegral[c - 1] + 0.5 * (this->Sigma[c - 1] + this->Sigma[c]);
    for (int i = 0; i < 3; ++i)
    {
      this->EmissionIntegral[3 * c + i] = this->EmissionIntegral[3 * (c - 1) + i] +
                                          0.5 * (this->Sigma[c - 1] * this->RGB[3 * (c - 1) + i] +
                                                  this->Sigma[c] * this->RGB[3 * c + i]);
    }
  }
}

void TransferFunctionTable::SetComponentLevels(ComponentLevels levels)
{
  levels.Count = std::min(std::max(levels.Count, 0), 4);
  for (int c = 0; c < levels.Count; ++c)
  {
    // A level per possible packed index, none missing, none poisonous.
    for (std::vector<float>* table : { &levels.RGBA[c], &levels.Medium[c] })
    {
      table->resize(4 * static_cast<std::size_t>(levels.PairLevels), 0.0f);
      for (float& v : *table)
      {
        v = std::isfinite(v) && v > 0.0f ? v : 0.0f;
      }
    }
  }
  this->Levels = std::move(levels);
}

void TransferFunctionTable::SetComponentTerms(
  std::vector<double> first, std::vector<double> second, bool emission)
{
  // Non-finite or negative terms would poison every sample they meet: zero them.
  const auto clean = [](std::vector<double>& terms)
  {
    for (double& v : terms)
    {
      v = std::isfinite(v) && v > 0.0 ? v : 0.0;
    }
  };
  first.resize(5 * static_cast<std::size_t>(this->Code.Levels), 0.0);
  second.resize(second.size() / 5 * 5);
  clean(first);
  clean(second);
  this->FirstTerms = std::move(first);
  this->SecondTerms = std::move(second);
  this->SecondLevels = static_cast<std::uint32_t>(this->SecondTerms.size() / 5);
  this->Emission = emission;
  if (this->SecondLevels == 0)
  {
    this->FirstTerms.clear();
  }
}

void TransferFunctionTable::Segment(std::uint32_t front, std::uint32_t back, double length,
  double& alpha, Eigen::Array3d& color) const
{
  if (front == back)
  {
    alpha = composite::IntervalOpacity(this->Sigma[front], length);
    color =
      Eigen::Array3d(this->RGB[3 * front], this->RGB[3 * front + 1], this->RGB[3 * front + 2]);
    return;
  }
  // The segment is cut into pieces of equal value range, composited front to back. Each piece's
  // optical depth is exact (from the extinction integral); its colour is the extinction-weighted
  // mean over it. Attenuation inside the segment is resolved to pieces of optical depth
  // kPieceDepth or less on average, at most kSegmentPieces of them: a transparent segment takes
  // none, a faint one a single piece (its colour then off by under kPieceDepth / 2 of its own
  // small contribution).
  const std::int64_t codes = static_cast<std::int64_t>(back) - front;
  const std::int64_t span = codes < 0 ? -codes : codes;
  const double perCode = length / static_cast<double>(span);
  const double depth =
    (this->SigmaIntegral[std::max(front, back)] - this->SigmaIntegral[std::min(front, back)]) *
    perCode;
  if (!(depth > 0.0))
  {
    alpha = 0.0;
    color.setZero();
    return;
  }
  const std::int64_t pieces = std::min<std::int64_t>(std::min<std::int64_t>(span, kSegmentPieces),
    std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(depth / kPieceDepth))));
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();
  std::int64_t from = front;
  for (std::int64_t p = 1; p <= pieces && T > 0.0; ++p)
  {
    const std::int64_t to = front + codes * p / pieces;
    const std::int64_t lo = std::min(from, to);
    const std::int64_t hi = std::max(from, to);
    const double extinction = this->SigmaIntegral[hi] - this->SigmaIntegral[lo];
    const double a = composite::IntervalOpacity(extinction, perCode);
    if (a > 0.0)
    {
      Eigen::Array3d emitted;
      for (int c = 0; c < 3; ++c)
      {
        emitted[c] = this->EmissionIntegral[3 * hi + c] - this->EmissionIntegral[3 * lo + c];
      }
      composite::Over(C, T, a, emitted / extinction);
    }
    from = to;
  }
  alpha = 1.0 - T;
  color = alpha > 0.0 ? Eigen::Array3d(C / alpha) : Eigen::Array3d::Zero();
}

double TransferFunctionTable::IntervalAlpha(std::uint32_t code, double h) const
{
  return composite::IntervalOpacity(this->Sigma[code], h);
}

} // namespace savr

#include "blend/ShadingTable.h"

#include "blend/TransferFunctionTable.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace savr
{
void ShadingTable::Build(const std::vector<Light>& lights, const Eigen::Vector3d& toViewer,
  const std::vector<ShadingCoefficients>& components, bool twoSided)
{
  static std::atomic<std::uint64_t> builds{ 0 };
  this->Built = ++builds;
  std::vector<ShadingCoefficients> sets(
    components.begin(), components.begin() + std::min<std::size_t>(components.size(), 4));
  if (sets.empty())
  {
    sets.emplace_back();
  }
  this->Sets = static_cast<int>(sets.size());
  this->Factors.assign(6 * kCodes * sets.size(), 0.0f);
  for (int code = 0; code < static_cast<int>(kCodes); ++code)
  {
    const bool hasNormal = code != kNoNormal && code < kNormalSteps * kNormalSteps;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    if (hasNormal)
    {
      // The surface normal opposes the gradient (it points from higher values to lower, out
      // of a dense object), as in VTK's volume mappers: a light above the head lights its top.
      n = -DecodeNormal(static_cast<std::uint16_t>(code)).cast<double>();
      if (twoSided && n.dot(toViewer) < 0.0)
      {
        n = -n; // two-sided: face the viewer
      }
    }
    for (std::size_t k = 0; k < sets.size(); ++k)
    {
      const ShadingCoefficients& c = sets[k];
      Eigen::Array3d d = Eigen::Array3d::Zero();
      Eigen::Array3d s = Eigen::Array3d::Zero();
      for (const Light& light : lights)
      {
        d += c.Ambient * light.Ambient.array();
        const double cosine = n.dot(light.Direction);
        if (!hasNormal || cosine <= 0.0)
        {
          continue;
        }
        d += c.Diffuse * cosine * light.Diffuse.array();
        const double h = n.dot((light.Direction + toViewer).normalized());
        if (h > 0.001 && c.Specular > 0.0)
        {
          s += c.Specular * std::pow(h, c.SpecularPower) * light.Specular.array();
        }
      }
      float* f = &this->Factors[6 * (k * kCodes + code)];
      for (int i = 0; i < 3; ++i)
      {
        f[i] = static_cast<float>(d[i]);
        f[3 + i] = static_cast<float>(s[i]);
      }
    }
  }
}

} // namespace savr

namespace savr
{

void GradientOpacityTable::Build(const double* factors, const double* scales, int sets)
{
  static std::atomic<std::uint64_t> builds{ 0 };
  this->Built = ++builds;
  this->Count = std::min(std::max(sets, 1), kMostSets);
  for (int k = 0; k < this->Count; ++k)
  {
    for (int i = 0; i < 256; ++i)
    {
      const double f = factors[256 * k + i];
      this->Factors[256 * k + i] = std::isfinite(f) ? std::min(std::max(f, 0.0), 1.0) : 0.0;
    }
    this->CodesPerUnit[k] = scales[k] > 0.0 && std::isfinite(scales[k]) ? scales[k] : 1.0;
  }
}

double GradientOpacityTable::IntervalAlpha(
  const TransferFunctionTable& tf, std::uint32_t code, std::uint32_t magnitude, double h) const
{
  const double alpha = static_cast<double>(tf.Opacity(code)) * this->Factor(0, magnitude);
  const double depth = alpha < 1.0 ? -std::log1p(-alpha) : TransferFunctionTable::kMaxOpticalDepth;
  return composite::IntervalOpacity(
    std::min(depth, TransferFunctionTable::kMaxOpticalDepth) / tf.UnitDistance(), h);
}

} // namespace savr

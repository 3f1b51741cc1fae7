#include "blend/ShadingTable.h"

#include "blend/TransferFunctionTable.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace savr
{
namespace
{
constexpr int kSteps = 255; // quantization steps per octahedral coordinate
}

std::uint16_t EncodeNormal(const float gradient[3])
{
  const double x = gradient[0];
  const double y = gradient[1];
  const double z = gradient[2];
  const double l1 = std::abs(x) + std::abs(y) + std::abs(z);
  if (!(l1 > 0.0) || !std::isfinite(l1))
  {
    return kNoNormal;
  }
  double u = x / l1;
  double v = y / l1;
  if (z < 0.0)
  {
    const double fu = (1.0 - std::abs(v)) * (u >= 0.0 ? 1.0 : -1.0);
    const double fv = (1.0 - std::abs(u)) * (v >= 0.0 ? 1.0 : -1.0);
    u = fu;
    v = fv;
  }
  const int iu = static_cast<int>((u * 0.5 + 0.5) * (kSteps - 1) + 0.5);
  const int iv = static_cast<int>((v * 0.5 + 0.5) * (kSteps - 1) + 0.5);
  return static_cast<std::uint16_t>(
    std::min(std::max(iu, 0), kSteps - 1) + kSteps * std::min(std::max(iv, 0), kSteps - 1));
}

Eigen::Vector3f DecodeNormal(std::uint16_t code)
{
  const float u = (code % kSteps) / float(kSteps - 1) * 2.0f - 1.0f;
  const float v = (code / kSteps) / float(kSteps - 1) * 2.0f - 1.0f;
  Eigen::Vector3f n(u, v, 1.0f - std::abs(u) - std::abs(v));
  if (n.z() < 0.0f)
  {
    const float fu = (1.0f - std::abs(v)) * (u >= 0.0f ? 1.0f : -1.0f);
    const float fv = (1.0f - std::abs(u)) * (v >= 0.0f ? 1.0f : -1.0f);
    n.x() = fu;
    n.y() = fv;
  }
  return n.normalized();
}

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
    const bool hasNormal = code != kNoNormal && code < kSteps * kSteps;
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

std::uint8_t EncodeMagnitude(const float gradient[3], double scale)
{
  const double m = std::sqrt(static_cast<double>(gradient[0]) * gradient[0] +
                             static_cast<double>(gradient[1]) * gradient[1] +
                             static_cast<double>(gradient[2]) * gradient[2]) *
                   scale;
  return static_cast<std::uint8_t>(m >= 254.5 ? 255.0 : (m > 0.0 ? m + 0.5 : 0.0));
}

double GradientOpacityTable::IntervalAlpha(
  const TransferFunctionTable& tf, std::uint32_t code, std::uint32_t magnitude, double h) const
{
  const double alpha = static_cast<double>(tf.Opacity(code)) * this->Factor(0, magnitude);
  const double depth = alpha < 1.0 ? -std::log1p(-alpha) : TransferFunctionTable::kMaxOpticalDepth;
  return detail::IntervalOpacity(
    std::min(depth, TransferFunctionTable::kMaxOpticalDepth) / tf.UnitDistance(), h);
}

} // namespace savr

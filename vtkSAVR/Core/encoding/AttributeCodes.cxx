// Normal and magnitude codes (see AttributeCodes.h).

#include "encoding/AttributeCodes.h"

#include <algorithm>
#include <cmath>

namespace savr
{

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
  const int iu = static_cast<int>((u * 0.5 + 0.5) * (kNormalSteps - 1) + 0.5);
  const int iv = static_cast<int>((v * 0.5 + 0.5) * (kNormalSteps - 1) + 0.5);
  return static_cast<std::uint16_t>(std::min(std::max(iu, 0), kNormalSteps - 1) +
                                    kNormalSteps * std::min(std::max(iv, 0), kNormalSteps - 1));
}

Eigen::Vector3f DecodeNormal(std::uint16_t code)
{
  const float u = (code % kNormalSteps) / float(kNormalSteps - 1) * 2.0f - 1.0f;
  const float v = (code / kNormalSteps) / float(kNormalSteps - 1) * 2.0f - 1.0f;
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

std::uint8_t EncodeMagnitude(const float gradient[3], double scale)
{
  const double m = std::sqrt(static_cast<double>(gradient[0]) * gradient[0] +
                             static_cast<double>(gradient[1]) * gradient[1] +
                             static_cast<double>(gradient[2]) * gradient[2]) *
                   scale;
  return static_cast<std::uint8_t>(m >= 254.5 ? 255.0 : (m > 0.0 ? m + 0.5 : 0.0));
}

} // namespace savr

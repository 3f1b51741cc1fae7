#include "ComponentPairSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace savr
{

ComponentPairSampler::ComponentPairSampler(
  std::shared_ptr<const Sampler> first, std::shared_ptr<const Sampler> second, int gradientFrom)
  : Components{ std::move(first), std::move(second) }
  , GradientFrom(gradientFrom == 1 ? 1 : 0)
{
  for (int c = 0; c < 2; ++c)
  {
    this->Ranges[c] = this->Components[c]->ValueRange();
  }
}

void ComponentPairSampler::Unpack(double code, const std::array<double, 2>& firstRange,
  const std::array<double, 2>& secondRange, double& first, double& second)
{
  const long long packed = std::llround(code);
  const long long q0 = packed % kFirstLevels;
  const long long q1 = packed / kFirstLevels;
  first = firstRange[0] + (firstRange[1] - firstRange[0]) * q0 / (kFirstLevels - 1.0);
  second = secondRange[0] + (secondRange[1] - secondRange[0]) * q1 / (kSecondLevels - 1.0);
}

void ComponentPairSampler::SampleRay(
  const Ray& ray, double t0, double dt, int count, float* out, const SkipMask* /*skip*/) const
{
  this->Components[0]->SampleRay(ray, t0, dt, count, out);
  const auto quantize = [](float v, const std::array<double, 2>& range, int levels)
  {
    const double span = range[1] - range[0];
    const double x = span > 0.0 ? (v - range[0]) / span * (levels - 1) : 0.0;
    return std::min(std::max(std::llround(x), 0LL), static_cast<long long>(levels - 1));
  };
  // The second component in pieces, on the stack.
  constexpr int kPiece = 256;
  float second[kPiece];
  for (int start = 0; start < count; start += kPiece)
  {
    const int n = std::min(kPiece, count - start);
    this->Components[1]->SampleRay(ray, t0 + start * dt, dt, n, second);
    for (int k = 0; k < n; ++k)
    {
      float& v = out[start + k];
      if (v != v || second[k] != second[k])
      {
        v = std::numeric_limits<float>::quiet_NaN();
        continue;
      }
      const long long q0 = quantize(v, this->Ranges[0], kFirstLevels);
      const long long q1 = quantize(second[k], this->Ranges[1], kSecondLevels);
      v = static_cast<float>(q0 + kFirstLevels * q1);
    }
  }
}

} // namespace savr

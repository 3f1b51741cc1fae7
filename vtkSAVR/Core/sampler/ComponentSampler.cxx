#include "sampler/ComponentSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace savr
{

ComponentSampler::ComponentSampler(
  std::vector<std::shared_ptr<const Sampler>> components, int gradientFrom)
  : Components(std::move(components))
{
  if (this->Components.size() > 4)
  {
    this->Components.resize(4);
  }
  for (const auto& component : this->Components)
  {
    this->Ranges.push_back(component->ValueRange());
  }
  this->GradientFrom = gradientFrom >= 0 && gradientFrom < this->NumberOfComponents()
                         ? gradientFrom
                         : (gradientFrom == kAllGradients ? kAllGradients : 0);
}

void ComponentSampler::GradientAt(const Ray& ray, double t, float gradient[3]) const
{
  if (this->GradientFrom != kAllGradients)
  {
    this->Components[this->GradientFrom]->GradientAt(ray, t, gradient);
    return;
  }
  gradient[0] = gradient[1] = gradient[2] = 0.0f;
  for (int c = 0; c < this->NumberOfComponents(); ++c)
  {
    const double span = this->Ranges[c][1] - this->Ranges[c][0];
    if (!(span > 0.0))
    {
      continue; // constant: no gradient
    }
    float g[3];
    this->Components[c]->GradientAt(ray, t, g);
    for (int i = 0; i < 3; ++i)
    {
      gradient[i] += static_cast<float>(g[i] / span);
    }
  }
}

void ComponentSampler::ComponentGradientsAlongRay(const Ray& ray, double t0, double dt, int first,
  int last, const float* values, float* gradients) const
{
  if (first > last)
  {
    return;
  }
  std::fill(gradients + 12 * static_cast<std::size_t>(first),
    gradients + 12 * (static_cast<std::size_t>(last) + 1), 0.0f);
  if (this->GradientFrom != kAllGradients)
  {
    return; // the components' gradients are not prepared
  }
  // One component's gradients at a time, then spread to their places.
  thread_local std::vector<float> one;
  one.resize(3 * (static_cast<std::size_t>(last) + 1));
  for (int c = 0; c < this->NumberOfComponents(); ++c)
  {
    this->Components[c]->GradientsAlongRay(ray, t0, dt, first, last, values, one.data());
    for (int i = first; i <= last; ++i)
    {
      std::copy_n(&one[3 * static_cast<std::size_t>(i)], 3,
        gradients + 3 * (4 * static_cast<std::size_t>(i) + c));
    }
  }
}

void ComponentSampler::PrepareGradients() const
{
  for (int c = 0; c < this->NumberOfComponents(); ++c)
  {
    if (this->GradientFrom == kAllGradients || c == this->GradientFrom)
    {
      this->Components[c]->PrepareGradients();
    }
  }
}

std::size_t ComponentSampler::GradientBytes() const
{
  std::size_t bytes = 0;
  for (int c = 0; c < this->NumberOfComponents(); ++c)
  {
    if (this->GradientFrom == kAllGradients || c == this->GradientFrom)
    {
      bytes += this->Components[c]->GradientBytes();
    }
  }
  return bytes;
}

void ComponentSampler::Unpack(double code, const std::array<double, 2>& firstRange,
  const std::array<double, 2>& secondRange, double& first, double& second)
{
  const long long packed = std::llround(code);
  const long long q0 = packed % kFirstLevels;
  const long long q1 = packed / kFirstLevels;
  first = firstRange[0] + (firstRange[1] - firstRange[0]) * q0 / (kFirstLevels - 1.0);
  second = secondRange[0] + (secondRange[1] - secondRange[0]) * q1 / (kSecondLevels - 1.0);
}

bool ComponentSampler::MayReturnNaN() const
{
  return std::any_of(this->Components.begin(), this->Components.end(),
    [](const std::shared_ptr<const Sampler>& c) { return c->MayReturnNaN(); });
}

template <typename Out>
void ComponentSampler::SamplePair(
  int first, const Ray& ray, double t0, double dt, int count, Out* out, Out invalid) const
{
  const auto quantize = [](float v, const std::array<double, 2>& range, int levels)
  {
    const double span = range[1] - range[0];
    const double x = span > 0.0 ? (v - range[0]) / span * (levels - 1) : 0.0;
    return std::min(std::max(std::llround(x), 0LL), static_cast<long long>(levels - 1));
  };
  const bool hasSecond = first + 1 < this->NumberOfComponents();
  // The components in pieces, on the stack.
  constexpr int kPiece = 256;
  float a[kPiece];
  float b[kPiece];
  for (int start = 0; start < count; start += kPiece)
  {
    const int n = std::min(kPiece, count - start);
    const double t = t0 + start * dt;
    this->Components[first]->SampleRay(ray, t, dt, n, a);
    if (hasSecond)
    {
      this->Components[first + 1]->SampleRay(ray, t, dt, n, b);
    }
    else
    {
      std::fill(b, b + n, 0.0f);
    }
    for (int k = 0; k < n; ++k)
    {
      // NaN and infinities have no level: the sample is invalid (transparent), as a
      // single-component sample that is not finite.
      if (!std::isfinite(a[k]) || !std::isfinite(b[k]))
      {
        out[start + k] = invalid;
        continue;
      }
      const long long q0 = quantize(a[k], this->Ranges[first], kFirstLevels);
      const long long q1 = hasSecond ? quantize(b[k], this->Ranges[first + 1], kSecondLevels) : 0LL;
      out[start + k] = static_cast<Out>(q0 + kFirstLevels * q1);
    }
  }
}

void ComponentSampler::SampleRay(
  const Ray& ray, double t0, double dt, int count, float* out, const SkipMask* /*skip*/) const
{
  this->SamplePair<float>(0, ray, t0, dt, count, out, std::numeric_limits<float>::quiet_NaN());
}

void ComponentSampler::SampleRaySecond(
  const Ray& ray, double t0, double dt, int count, std::uint16_t* second) const
{
  if (this->NumberOfComponents() <= 2)
  {
    std::fill(second, second + count, kNoSecondCode);
    return;
  }
  this->SamplePair<std::uint16_t>(2, ray, t0, dt, count, second, kNoSecondCode);
}

bool ComponentSampler::ComputeGradientsOnDemand() const
{
  bool lower = false;
  for (int c = 0; c < this->NumberOfComponents(); ++c)
  {
    if (this->GradientFrom == kAllGradients || c == this->GradientFrom)
    {
      lower = this->Components[c]->ComputeGradientsOnDemand() || lower;
    }
  }
  return lower;
}

} // namespace savr

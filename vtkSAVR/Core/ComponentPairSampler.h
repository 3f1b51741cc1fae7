#pragma once
// Two-component data as one stored code per sample: each component is sampled by its own
// sampler, quantized to 8 bits over its range and packed as first + 256 * second. The transfer
// function table is then built over the pairs (65,280 codes), so that editing either component's
// transfer functions re-blends the stored samples without resampling.

#include "Sampler.h"

#include <memory>

namespace savr
{

class ComponentPairSampler final : public Sampler
{
public:
  /// Levels of the first component (codes 0..255) and of the second (0..254, so that a code for
  /// NaN still fits 16 bits).
  static constexpr int kFirstLevels = 256;
  static constexpr int kSecondLevels = 255;

  /// `gradientFrom` (0 or 1) chooses the component whose gradient shading uses.
  ComponentPairSampler(
    std::shared_ptr<const Sampler> first, std::shared_ptr<const Sampler> second, int gradientFrom);

  /// The component values a packed code stands for.
  static void Unpack(double code, const std::array<double, 2>& firstRange,
    const std::array<double, 2>& secondRange, double& first, double& second);

  const std::array<double, 2>& FirstRange() const { return this->Ranges[0]; }
  const std::array<double, 2>& SecondRange() const { return this->Ranges[1]; }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    return this->Components[0]->Clip(ray, tEnter, tExit);
  }
  std::array<double, 2> ValueRange() const override
  {
    return { 0.0, (kFirstLevels - 1) + kFirstLevels * (kSecondLevels - 1.0) };
  }
  int ExactBits() const override { return 16; }
  bool MayReturnNaN() const override
  {
    return this->Components[0]->MayReturnNaN() || this->Components[1]->MayReturnNaN();
  }
  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip = nullptr) const override;
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override
  {
    this->Components[this->GradientFrom]->GradientAt(ray, t, gradient);
  }

private:
  std::shared_ptr<const Sampler> Components[2];
  std::array<double, 2> Ranges[2];
  int GradientFrom;
};

} // namespace savr

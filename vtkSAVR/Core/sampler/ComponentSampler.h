#pragma once
// Data with two to four components as codes per sample: each component is sampled by its own
// sampler and quantized to 8 bits over its range. The first two are packed as the sample's value
// (first + 256 * second); the third and fourth, when present, as its second code (third + 256 *
// fourth, Sampler::SampleRaySecond). Transfer-function tables are built over the packed pairs
// (65,280 codes each), so that editing any component's functions re-blends the stored samples
// without resampling.

#include "sampler/Sampler.h"

#include <memory>
#include <vector>

namespace savr
{

class ComponentSampler final : public Sampler
{
public:
  /// Levels of the first component of a pair (codes 0..255) and of the second (0..254, so that
  /// a code for NaN still fits 16 bits).
  static constexpr int kFirstLevels = 256;
  static constexpr int kSecondLevels = 255;
  /// Codes a packed pair can take.
  static constexpr std::uint32_t kPairCodes = kFirstLevels * kSecondLevels;

  /// Two to four components on the same region (more are ignored); `gradientFrom` chooses the
  /// component whose gradient shading uses, or, when kAllGradients, the gradients of all of them,
  /// each over its value range, are summed: where one component changes (its surface) the
  /// normal is its own, whichever of them the transfer functions show. Each component's own
  /// gradient (ComponentGradientsAlongRay, for gradient opacity) needs kAllGradients.
  static constexpr int kAllGradients = -1;
  ComponentSampler(std::vector<std::shared_ptr<const Sampler>> components, int gradientFrom);

  /// The values a packed pair code stands for, given the two components' ranges.
  static void Unpack(double code, const std::array<double, 2>& firstRange,
    const std::array<double, 2>& secondRange, double& first, double& second);

  int NumberOfComponents() const { return static_cast<int>(this->Components.size()); }
  /// Range of component c; {0, 0} for a component that is absent (the fourth of three).
  std::array<double, 2> Range(int c) const
  {
    return c < this->NumberOfComponents() ? this->Ranges[c] : std::array<double, 2>{ 0.0, 0.0 };
  }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    return this->Components[0]->Clip(ray, tEnter, tExit);
  }
  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override
  {
    return this->Components[0]->HullCorners(corners);
  }
  std::array<double, 2> ValueRange() const override { return { 0.0, kPairCodes - 1.0 }; }
  int ExactBits() const override { return 16; }
  bool MayReturnNaN() const override;
  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip = nullptr) const override;
  bool HasSecondCode() const override { return this->Components.size() > 2; }
  void SampleRaySecond(
    const Ray& ray, double t0, double dt, int count, std::uint16_t* second) const override;
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override;
  void ComponentGradientsAlongRay(const Ray& ray, double t0, double dt, int first, int last,
    const float* values, float* gradients) const override;
  void PrepareGradients() const override;
  std::size_t GradientBytes() const override;
  bool ComputeGradientsOnDemand() const override;

private:
  // Packs components `first` and first + 1 (absent: code 0) along the ray into `out`;
  // `invalid` is what a sample gets where either is NaN.
  template <typename Out>
  void SamplePair(
    int first, const Ray& ray, double t0, double dt, int count, Out* out, Out invalid) const;

  std::vector<std::shared_ptr<const Sampler>> Components;
  std::vector<std::array<double, 2>> Ranges;
  int GradientFrom;
};

} // namespace savr

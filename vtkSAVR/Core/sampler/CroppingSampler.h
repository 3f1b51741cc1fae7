#pragma once
// Orthogonal cropping as VTK's volume mappers define it: three pairs of axis-aligned planes in
// data coordinates cut the data into 27 regions, and a bit per region says whether it shows.
// Samples in hidden regions read as NaN (transparent).

#include "sampler/Sampler.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>

namespace savr
{

class CroppingSampler final : public Sampler
{
public:
  /// `planes` are xmin, xmax, ymin, ymax, zmin, zmax in the coordinates `worldToData` maps to;
  /// bit (x + 3 y + 9 z) of `regions` shows the region that is x, y, z = 0 below, 1 between,
  /// 2 above the planes of each axis.
  CroppingSampler(std::shared_ptr<const Sampler> inner, const Eigen::Affine3d& worldToData,
    const double planes[6], std::uint32_t regions);

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    return this->Inner->Clip(ray, tEnter, tExit);
  }
  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override
  {
    return this->Inner->HullCorners(corners);
  }
  /// With the middle region alone shown (a subvolume), the part of [t0, t1] inside it.
  bool Restrict(const Ray& ray, double& t0, double& t1) const override;
  std::array<double, 2> ValueRange() const override { return this->Inner->ValueRange(); }
  int ExactBits() const override { return this->Inner->ExactBits(); }
  bool MayReturnNaN() const override { return true; }
  const std::vector<float>& BlockRanges() const override { return this->Inner->BlockRanges(); }
  void SkipDistances(std::vector<std::uint8_t>& skip) const override
  {
    this->Inner->SkipDistances(skip);
  }
  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip = nullptr) const override;
  // Cropping only adds NaN.
  int FirstUnskipped(
    const Ray& ray, double t0, double dt, int count, const SkipMask* skip) const override
  {
    return this->Inner->FirstUnskipped(ray, t0, dt, count, skip);
  }
  double FirstUnskippedAt(const Ray& ray, double t0, double t1, const SkipMask* skip) const override
  {
    return this->Inner->FirstUnskippedAt(ray, t0, t1, skip);
  }
  void SampleRayGradients(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const override;
  bool TracesPaths() const override { return this->Inner->TracesPaths(); }
  bool TracePath(const Ray& ray, double t0, double t1, double spacing, std::size_t maxPieces,
    std::vector<PathPiece>& path) const override
  {
    return this->Inner->TracePath(ray, t0, t1, spacing, maxPieces, path);
  }
  void SampleAlongPath(const Ray& ray, const PathPiece* path, std::size_t pieces, double traceStart,
    double t0, double dt, int count, float* out) const override;
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override
  {
    this->Inner->GradientAt(ray, t, gradient);
  }
  // `values` come cropped (NaN where hidden): the inner sampler gives those zero gradients.
  void GradientsAlongRay(const Ray& ray, double t0, double dt, int first, int last,
    const float* values, float* gradients) const override
  {
    this->Inner->GradientsAlongRay(ray, t0, dt, first, last, values, gradients);
  }
  void ComponentGradientsAlongRay(const Ray& ray, double t0, double dt, int first, int last,
    const float* values, float* gradients) const override
  {
    this->Inner->ComponentGradientsAlongRay(ray, t0, dt, first, last, values, gradients);
  }
  void PrepareGradients() const override { this->Inner->PrepareGradients(); }
  std::size_t GradientBytes() const override { return this->Inner->GradientBytes(); }
  bool ComputeGradientsOnDemand() const override { return this->Inner->ComputeGradientsOnDemand(); }
  // Hidden samples are NaN by their value; their second code does not matter.
  bool HasSecondCode() const override { return this->Inner->HasSecondCode(); }
  void SampleRaySecond(
    const Ray& ray, double t0, double dt, int count, std::uint16_t* second) const override
  {
    this->Inner->SampleRaySecond(ray, t0, dt, count, second);
  }

private:
  // Sets the samples of hidden regions to NaN.
  void Crop(const Ray& ray, double t0, double dt, int count, float* out) const;

  std::shared_ptr<const Sampler> Inner;
  Eigen::Affine3d WorldToData;
  double Planes[6];
  std::uint32_t Regions;
};

} // namespace savr

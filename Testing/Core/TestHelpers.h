#pragma once
// Procedural scenes for the engine's tests: expected values come from the scenes' definitions.

#include "reference/ReferenceIntegrator.h"
#include "blend/TransferFunctionTable.h"
#include "frame/FrameLoop.h"
#include "image/GridSampler.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace savr_test
{

/// Perspective camera as VTK's: world to normalized device coordinates, inverted.
inline savr::View PerspectiveView(const Eigen::Vector3d& eye, const Eigen::Vector3d& center,
  const Eigen::Vector3d& up, double fovyDegrees, int width, int height, double zNear, double zFar)
{
  const Eigen::Vector3d f = (center - eye).normalized();
  const Eigen::Vector3d s = f.cross(up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d viewM = Eigen::Matrix4d::Identity();
  viewM.block<1, 3>(0, 0) = s.transpose();
  viewM.block<1, 3>(1, 0) = u.transpose();
  viewM.block<1, 3>(2, 0) = -f.transpose();
  viewM(0, 3) = -s.dot(eye);
  viewM(1, 3) = -u.dot(eye);
  viewM(2, 3) = f.dot(eye);
  const double t = 1.0 / std::tan(0.5 * fovyDegrees * M_PI / 180.0);
  const double aspect = static_cast<double>(width) / height;
  Eigen::Matrix4d proj = Eigen::Matrix4d::Zero();
  proj(0, 0) = t / aspect;
  proj(1, 1) = t;
  proj(2, 2) = -(zFar + zNear) / (zFar - zNear);
  proj(2, 3) = -2.0 * zFar * zNear / (zFar - zNear);
  proj(3, 2) = -1.0;
  savr::View view;
  view.Width = width;
  view.Height = height;
  view.NDCToWorld = (proj * viewM).inverse();
  return view;
}

/// Parallel rays along +x through the square |y|, |z| < halfSize, from x = xNear to x = xFar.
inline savr::View ParallelViewAlongX(int size, double halfSize, double xNear, double xFar)
{
  // NDC (nx, ny, nz) -> world (xNear + (nz + 1) / 2 * (xFar - xNear), nx * halfSize, ny * halfSize)
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 2) = 0.5 * (xFar - xNear);
  m(0, 3) = xNear + 0.5 * (xFar - xNear);
  m(1, 0) = halfSize;
  m(2, 1) = halfSize;
  m(3, 3) = 1.0;
  savr::View view;
  view.Width = size;
  view.Height = size;
  view.NDCToWorld = m;
  return view;
}

/// A slab [0, length] x [-1, 1] x [-1, 1] of one value, over the range [0, 1].
class ConstantSlab final : public savr::Sampler
{
public:
  ConstantSlab(double length, float value)
    : Length(length)
    , Value(value)
  {
  }
  bool Clip(const savr::Ray& ray, double& tEnter, double& tExit) const override
  {
    // Rays of these tests run along +x inside |y|, |z| < 1.
    if (std::abs(ray.Origin.y()) > 1.0 || std::abs(ray.Origin.z()) > 1.0)
    {
      return false;
    }
    tEnter = (0.0 - ray.Origin.x()) / ray.Direction.x();
    tExit = (this->Length - ray.Origin.x()) / ray.Direction.x();
    return tEnter < tExit;
  }
  std::array<double, 2> ValueRange() const override { return { 0.0, 1.0 }; }
  int ExactBits() const override { return 0; }
  bool MayReturnNaN() const override { return false; }
  void SampleRay(
    const savr::Ray&, double, double, int count, float* out, const savr::SkipMask*) const override
  {
    std::fill(out, out + count, this->Value);
  }

private:
  double Length;
  float Value;
};

/// Passes every call on to another sampler: tests derive from it to change or watch one call.
class ForwardingSampler : public savr::Sampler
{
public:
  explicit ForwardingSampler(std::shared_ptr<const savr::Sampler> inner)
    : Inner(std::move(inner))
  {
  }
  bool Clip(const savr::Ray& ray, double& tEnter, double& tExit) const override
  {
    return this->Inner->Clip(ray, tEnter, tExit);
  }
  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override
  {
    return this->Inner->HullCorners(corners);
  }
  std::array<double, 2> ValueRange() const override { return this->Inner->ValueRange(); }
  int ExactBits() const override { return this->Inner->ExactBits(); }
  bool MayReturnNaN() const override { return this->Inner->MayReturnNaN(); }
  void SampleRay(const savr::Ray& ray, double t0, double dt, int count, float* out,
    const savr::SkipMask* skip) const override
  {
    this->Inner->SampleRay(ray, t0, dt, count, out, skip);
  }
  void GradientAt(const savr::Ray& ray, double t, float gradient[3]) const override
  {
    this->Inner->GradientAt(ray, t, gradient);
  }
  void SampleRayGradients(const savr::Ray& ray, double t0, double dt, int count, float* out,
    float* gradients) const override
  {
    this->Inner->SampleRayGradients(ray, t0, dt, count, out, gradients);
  }
  void PrepareGradients() const override { this->Inner->PrepareGradients(); }
  bool HasSecondCode() const override { return this->Inner->HasSecondCode(); }
  void SampleRaySecond(
    const savr::Ray& ray, double t0, double dt, int count, std::uint16_t* second) const override
  {
    this->Inner->SampleRaySecond(ray, t0, dt, count, second);
  }
  const std::vector<float>& BlockRanges() const override { return this->Inner->BlockRanges(); }
  void SkipDistances(std::vector<std::uint8_t>& skip) const override
  {
    this->Inner->SkipDistances(skip);
  }

private:
  std::shared_ptr<const savr::Sampler> Inner;
};

/// A smooth float field on an n^3 grid spanning [-1, 1]^3.
struct WaveGrid
{
  explicit WaveGrid(int n, savr::Interpolation interpolation = savr::Interpolation::Linear)
    : Values(static_cast<std::size_t>(n) * n * n)
  {
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
          const double x = -1.0 + 2.0 * i / (n - 1);
          const double y = -1.0 + 2.0 * j / (n - 1);
          const double z = -1.0 + 2.0 * k / (n - 1);
          this->Values[i + n * (j + n * k)] =
            static_cast<float>(std::sin(3 * x) * std::cos(2 * y) + 0.5 * z * z + 0.3 * x * y);
        }
    this->Grid.Data = this->Values.data();
    this->Grid.Type = savr::ScalarType::Float32;
    this->Grid.Dims = { n, n, n };
    this->Grid.Interpolation = interpolation;
    // index = (world + 1) * (n - 1) / 2
    this->Grid.WorldToIndex = Eigen::Affine3d::Identity();
    this->Grid.WorldToIndex.scale(0.5 * (n - 1));
    this->Grid.WorldToIndex.translate(Eigen::Vector3d(1, 1, 1));
  }
  std::shared_ptr<const savr::Sampler> Sampler() const
  {
    std::string error;
    return savr::MakeGridSampler(this->Grid, error);
  }
  std::vector<float> Values;
  savr::GridDescription Grid;
};

/// Tabulates colour and opacity functions of the value over every code of `encoding`.
inline savr::TransferFunctionTable MakeTable(const savr::SampleEncoding& encoding,
  const std::function<Eigen::Vector3d(double)>& color, const std::function<double(double)>& opacity,
  double unitDistance = 1.0)
{
  std::vector<double> rgb(3 * encoding.Levels);
  std::vector<double> alpha(encoding.Levels);
  for (std::uint32_t c = 0; c < encoding.Levels; ++c)
  {
    const double v = encoding.Decode(c);
    const Eigen::Vector3d col = color(v);
    rgb[3 * c] = col[0];
    rgb[3 * c + 1] = col[1];
    rgb[3 * c + 2] = col[2];
    alpha[c] = opacity(v);
  }
  savr::TransferFunctionTable table;
  table.Build(encoding, rgb.data(), alpha.data(), unitDistance);
  return table;
}

inline double MaxAbsDifference(const std::vector<float>& a, const std::vector<float>& b)
{
  double d = a.size() == b.size() ? 0.0 : std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
  {
    d = std::max(d, static_cast<double>(std::abs(a[i] - b[i])));
  }
  return d;
}

// Whether two images hold the same floats, bit for bit.
inline bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

inline double MaxValue(const std::vector<float>& a)
{
  double m = 0.0;
  for (float v : a)
  {
    m = std::max(m, static_cast<double>(v));
  }
  return m;
}

} // namespace savr_test

namespace savr_test
{

/// The double-precision reference (savr::ReferenceImage) with `steps` steps per ray.
inline std::vector<float> ReferenceImage(const savr::View& view, const savr::Sampler& sampler,
  const std::function<Eigen::Vector3d(double)>& color, const std::function<double(double)>& opacity,
  double unitDistance, int steps)
{
  savr::ReferenceTransferFunction tf{ color, opacity, unitDistance };
  return savr::ReferenceImage(view, sampler, tf, std::numeric_limits<double>::infinity(), steps);
}

inline double RootMeanSquare(const std::vector<float>& a, const std::vector<float>& b)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sum += (static_cast<double>(a[i]) - b[i]) * (static_cast<double>(a[i]) - b[i]);
  }
  return a.empty() ? 0.0 : std::sqrt(sum / a.size());
}

inline bool AllFinite(const std::vector<float>& a)
{
  for (float v : a)
  {
    if (!std::isfinite(v))
    {
      return false;
    }
  }
  return true;
}

} // namespace savr_test

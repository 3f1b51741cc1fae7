#include "GridSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace savr
{
namespace
{

// Points this close outside the grid (in index units) still count as inside: ray entry and exit
// points are computed with round-off and must not read as NaN.
constexpr double kBoundaryTolerance = 1e-6;

template <typename T>
class GridSamplerT final : public Sampler
{
public:
  GridSamplerT(const GridDescription& grid, int exactBits)
    : Values(static_cast<const T*>(grid.data))
    , Stride(grid.components)
    , WorldToIndex(grid.worldToIndex)
    , Linear(grid.interpolation == Interpolation::Linear)
    , CellData(grid.cellData)
    , Bits(exactBits)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->PointDims[a] = grid.dims[a];
      this->ValueDims[a] = grid.cellData ? grid.dims[a] - 1 : grid.dims[a];
    }
    this->ScanValues();
  }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    const Eigen::Vector3d o = this->WorldToIndex * ray.origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.direction;
    tEnter = -std::numeric_limits<double>::infinity();
    tExit = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
    {
      const double hi = this->PointDims[a] - 1;
      if (d[a] == 0.0)
      {
        if (o[a] < 0.0 || o[a] > hi)
        {
          return false;
        }
        continue;
      }
      double t0 = (0.0 - o[a]) / d[a];
      double t1 = (hi - o[a]) / d[a];
      if (t0 > t1)
      {
        std::swap(t0, t1);
      }
      tEnter = std::max(tEnter, t0);
      tExit = std::min(tExit, t1);
    }
    return tEnter < tExit;
  }

  std::array<double, 2> ValueRange() const override { return this->Range; }
  int ExactBits() const override { return this->Bits; }
  bool MayReturnNaN() const override { return this->HasNonFinite; }

  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out) const override
  {
    const Eigen::Vector3d o = this->WorldToIndex * ray.origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.direction;
    for (int i = 0; i < count; ++i)
    {
      const Eigen::Vector3d p = o + (t0 + i * dt) * d;
      out[i] = this->Linear ? this->SampleLinear(p) : this->SampleNearest(p);
    }
  }

private:
  // Continuous coordinates in the value grid (cell centres for cell data), clamped to it, or
  // false when `p` lies outside the data.
  bool ToValueGrid(const Eigen::Vector3d& p, double c[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      const double hi = this->PointDims[a] - 1;
      if (!(p[a] >= -kBoundaryTolerance && p[a] <= hi + kBoundaryTolerance))
      {
        return false;
      }
      const double v = this->CellData ? p[a] - 0.5 : p[a];
      c[a] = std::min(std::max(v, 0.0), static_cast<double>(this->ValueDims[a] - 1));
    }
    return true;
  }

  float Value(long long i, long long j, long long k) const
  {
    const long long index = i + this->ValueDims[0] * (j + this->ValueDims[1] * k);
    return static_cast<float>(this->Values[index * this->Stride]);
  }

  float SampleNearest(const Eigen::Vector3d& p) const
  {
    double c[3];
    if (!this->ToValueGrid(p, c))
    {
      return std::numeric_limits<float>::quiet_NaN();
    }
    return this->Value(std::lround(c[0]), std::lround(c[1]), std::lround(c[2]));
  }

  float SampleLinear(const Eigen::Vector3d& p) const
  {
    double c[3];
    if (!this->ToValueGrid(p, c))
    {
      return std::numeric_limits<float>::quiet_NaN();
    }
    long long i0[3];
    long long i1[3];
    float w[3];
    for (int a = 0; a < 3; ++a)
    {
      const double f = std::floor(c[a]);
      i0[a] = static_cast<long long>(f);
      i1[a] = std::min<long long>(i0[a] + 1, this->ValueDims[a] - 1);
      w[a] = static_cast<float>(c[a] - f);
    }
    const float c00 = this->Value(i0[0], i0[1], i0[2]) * (1 - w[0]) + this->Value(i1[0], i0[1], i0[2]) * w[0];
    const float c10 = this->Value(i0[0], i1[1], i0[2]) * (1 - w[0]) + this->Value(i1[0], i1[1], i0[2]) * w[0];
    const float c01 = this->Value(i0[0], i0[1], i1[2]) * (1 - w[0]) + this->Value(i1[0], i0[1], i1[2]) * w[0];
    const float c11 = this->Value(i0[0], i1[1], i1[2]) * (1 - w[0]) + this->Value(i1[0], i1[1], i1[2]) * w[0];
    const float c0 = c00 * (1 - w[1]) + c10 * w[1];
    const float c1 = c01 * (1 - w[1]) + c11 * w[1];
    return c0 * (1 - w[2]) + c1 * w[2];
  }

  void ScanValues()
  {
    const long long n = static_cast<long long>(this->ValueDims[0]) * this->ValueDims[1] * this->ValueDims[2];
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (long long i = 0; i < n; ++i)
    {
      const double v = static_cast<double>(this->Values[i * this->Stride]);
      if (!std::isfinite(v))
      {
        this->HasNonFinite = true;
        continue;
      }
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    this->Range = lo <= hi ? std::array<double, 2>{ lo, hi } : std::array<double, 2>{ 0.0, 0.0 };
  }

  const T* Values;
  int Stride;
  Eigen::Affine3d WorldToIndex;
  bool Linear;
  bool CellData;
  int Bits;
  long long PointDims[3] = { 0, 0, 0 };
  long long ValueDims[3] = { 0, 0, 0 };
  std::array<double, 2> Range = { 0.0, 0.0 };
  bool HasNonFinite = false;
};

template <typename T>
std::shared_ptr<const Sampler> Make(const GridDescription& grid, int exactBits)
{
  return std::make_shared<GridSamplerT<T>>(grid, exactBits);
}

} // namespace

std::shared_ptr<const Sampler> MakeGridSampler(const GridDescription& grid, std::string& error)
{
  if (!grid.data)
  {
    error = "the grid has no scalar values";
    return nullptr;
  }
  if (grid.components < 1)
  {
    error = "the grid's scalars have no components";
    return nullptr;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (grid.dims[a] < 2)
    {
      error = "the grid needs at least 2 points along every axis";
      return nullptr;
    }
  }
  if (!grid.worldToIndex.matrix().allFinite() ||
    std::abs(grid.worldToIndex.linear().determinant()) == 0.0)
  {
    error = "the grid's spacing or orientation is degenerate (zero spacing or a singular matrix)";
    return nullptr;
  }
  switch (grid.type)
  {
    case ScalarType::Int8:
      return Make<std::int8_t>(grid, 8);
    case ScalarType::UInt8:
      return Make<std::uint8_t>(grid, 8);
    case ScalarType::Int16:
      return Make<std::int16_t>(grid, 16);
    case ScalarType::UInt16:
      return Make<std::uint16_t>(grid, 16);
    case ScalarType::Int32:
      return Make<std::int32_t>(grid, 0);
    case ScalarType::UInt32:
      return Make<std::uint32_t>(grid, 0);
    case ScalarType::Int64:
      return Make<std::int64_t>(grid, 0);
    case ScalarType::UInt64:
      return Make<std::uint64_t>(grid, 0);
    case ScalarType::Float32:
      return Make<float>(grid, 0);
    case ScalarType::Float64:
      return Make<double>(grid, 0);
  }
  error = "unsupported scalar type";
  return nullptr;
}

} // namespace savr

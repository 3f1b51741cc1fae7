#include "image/GridSampler.h"

#include "encoding/AttributeCodes.h"
#include "image/BlockWalk.h"
#include "image/GridAVX2.h"
#include "image/GridGradients.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <type_traits>
#include <vector>

namespace savr
{
namespace
{

// Points this close outside the grid (in index units) still count as inside: ray entry and exit
// points are computed with round-off and must not read as NaN.
constexpr double kBoundaryTolerance = 1e-6;
// Cells per block edge. A block whose points all hold one value is sampled without
// interpolation: the value is known exactly, and air and padding are often such blocks.
constexpr std::size_t kBlock = 8;
constexpr int kBlockShift = 3; // log2(kBlock)

template <typename T>
class GridSamplerT final : public Sampler
{
  // 8-bit differences (at most 510 at a face) fit the gradient codes exactly, and 10 bits.
  static constexpr bool kExact = std::is_integral<T>::value && sizeof(T) == 1;

public:
  GridSamplerT(const GridDescription& grid, int exactBits)
    : Values(static_cast<const T*>(grid.Data))
    , Stride(grid.Components)
    , WorldToIndex(grid.WorldToIndex)
    , Linear(grid.Interpolation == Interpolation::Linear)
    , CellData(grid.CellData)
    , Bits(exactBits)
    , Vectorize(grid.Vectorize)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->PointDims[a] = grid.Dims[a];
      this->ValueDims[a] = grid.CellData ? grid.Dims[a] - 1 : grid.Dims[a];
      this->MaxIndex[a] = static_cast<double>(grid.Dims[a] - 1);
      this->MaxValueIndex[a] = static_cast<double>(this->ValueDims[a] - 1);
      this->LastCell[a] = std::max<long long>(this->ValueDims[a] - 2, 0);
    }
    this->CellShift = grid.CellData ? 0.5 : 0.0;
    this->Step[0] = grid.Components;
    this->Step[1] = this->Step[0] * this->ValueDims[0];
    this->Step[2] = this->Step[1] * this->ValueDims[1];
    for (int a = 0; a < 3; ++a)
    {
      // A single value along an axis is its own neighbour.
      this->Neighbour[a] = this->ValueDims[a] > 1 ? this->Step[a] : 0;
    }
    this->ScanValues();
    this->ScanBlocks();
    this->SetUpAVX2();
  }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    const Eigen::Vector3d hi(static_cast<double>(this->PointDims[0] - 1),
      static_cast<double>(this->PointDims[1] - 1), static_cast<double>(this->PointDims[2] - 1));
    return ClipToBox(this->WorldToIndex * ray.Origin, this->WorldToIndex.linear() * ray.Direction,
      Eigen::Vector3d::Zero(), hi, tEnter, tExit);
  }

  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override
  {
    const Eigen::Affine3d toWorld = this->WorldToIndex.inverse();
    for (int c = 0; c < 8; ++c)
    {
      corners[c] = toWorld * Eigen::Vector3d((c & 1) ? this->PointDims[0] - 1.0 : 0.0,
                               (c & 2) ? this->PointDims[1] - 1.0 : 0.0,
                               (c & 4) ? this->PointDims[2] - 1.0 : 0.0);
    }
    return toWorld.matrix().allFinite();
  }

  std::array<double, 2> ValueRange() const override { return this->Range; }
  int ExactBits() const override { return this->Bits; }
  bool MayReturnNaN() const override { return this->HasNonFinite; }

  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip) const override
  {
    const Eigen::Vector3d o = this->WorldToIndex * ray.Origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.Direction;
    const std::uint8_t* skipped = this->SkipFlags(skip);
    int first = count;
    int last = -1;
    this->InsideSamples(o, d, t0, dt, count, first, last);
    for (int i = 0; i < count && i < first; ++i)
    {
      out[i] = std::numeric_limits<float>::quiet_NaN();
    }
    for (int i = std::max(last + 1, 0); i < count; ++i)
    {
      out[i] = std::numeric_limits<float>::quiet_NaN();
    }
    const double oa[3] = { o[0], o[1], o[2] };
    const double da[3] = { d[0], d[1], d[2] };
    if (this->UseAVX2)
    {
      // Eight at a time.
      detail::SampleLinearAVX2(this->AVX2Data, oa, da, t0, dt, first, last, out, skipped);
      return;
    }
    const double perCell = PerCell(d);
    int i = first;
    while (i <= last)
    {
      i = this->SampleOne(o, d, t0, dt, i, last, out, skipped, perCell);
    }
  }

  // The samples SampleOne passes over, without reading a value: its NaN samples are the
  // vector path's, bit for bit.
  int FirstUnskipped(
    const Ray& ray, double t0, double dt, int count, const SkipMask* skip) const override
  {
    const std::uint8_t* skipped = this->SkipFlags(skip);
    if (!skipped || count <= 0)
    {
      return 0;
    }
    const Eigen::Vector3d o = this->WorldToIndex * ray.Origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.Direction;
    int first = count;
    int last = -1;
    this->InsideSamples(o, d, t0, dt, count, first, last);
    const double perCell = PerCell(d);
    int i = first;
    while (i <= last)
    {
      long long i0[3];
      float w[3];
      const std::size_t block = this->Locate(o, d, t0 + i * dt, i0, w);
      if (!skipped[block])
      {
        return i;
      }
      i = this->PastSkipped(o, d, t0, dt, i, last, i0, skipped[block], perCell);
    }
    return count;
  }

  // The blocks' walk (BlockWalk.h), locating points as sampling does.
  double FirstUnskippedAt(const Ray& ray, double t0, double t1, const SkipMask* skip) const override
  {
    const Eigen::Vector3d o = this->WorldToIndex * ray.Origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.Direction;
    const auto locate = [&](double t, long long b[3])
    {
      long long i0[3];
      float w[3];
      this->Locate(o, d, t, i0, w);
      for (int a = 0; a < 3; ++a)
      {
        b[a] = i0[a] >> kBlockShift;
      }
    };
    return detail::FirstUnskippedBlock(
      this->Lattice(), o, d, PerCell(d), t0, t1, this->SkipFlags(skip), locate);
  }

  // Per-point gradients (GridGradients.h), interpolated at every sample inside the grid.
  void SampleRayGradients(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const override
  {
    this->SampleRay(ray, t0, dt, count, out, nullptr);
    this->GradientsAlongRay(ray, t0, dt, 0, count - 1, out, gradients);
  }

  // One kernel interpolates each group's values and gradients and encodes its normals (the
  // same bits as SampleRayGradients, then EncodeNormal).
  bool SampleRayNormals(const Ray& ray, double t0, double dt, int count, float* out,
    std::uint16_t* normals) const override
  {
    this->PrepareGradients();
    if (!this->UseGradientAVX2)
    {
      return false;
    }
    const Eigen::Vector3d o = this->WorldToIndex * ray.Origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.Direction;
    int first = count;
    int last = -1;
    this->InsideSamples(o, d, t0, dt, count, first, last);
    if (first <= last)
    {
      const double oa[3] = { o[0], o[1], o[2] };
      const double da[3] = { d[0], d[1], d[2] };
      detail::SampleValuesAndNormalsAVX2(
        this->AVX2Data, this->GradientAVX2Data, oa, da, t0, dt, first, last, out, normals);
    }
    for (int i = 0; i < count; ++i)
    {
      if (i < first || i > last)
      {
        out[i] = std::numeric_limits<float>::quiet_NaN();
      }
      if (out[i] != out[i])
      {
        normals[i] = kNoNormal;
      }
    }
    return true;
  }

  void GradientsAlongRay(const Ray& ray, double t0, double dt, int from, int to,
    const float* values, float* gradients) const override
  {
    if (from > to)
    {
      return;
    }
    this->PrepareGradients();
    const Eigen::Vector3d o = this->WorldToIndex * ray.Origin;
    const Eigen::Vector3d d = this->WorldToIndex.linear() * ray.Direction;
    // Samples [first, last] lie inside: the same for any run asked for, so that each sample's
    // gradient does not depend on the run.
    int first = to + 1;
    int last = -1;
    this->InsideSamples(o, d, t0, dt, to + 1, first, last);
    first = std::max(first, from);
    if (first <= last)
    {
      if (this->UseGradientAVX2)
      {
        const double oa[3] = { o[0], o[1], o[2] };
        const double da[3] = { d[0], d[1], d[2] };
        detail::SampleGradientsAVX2(
          this->AVX2Data, this->GradientAVX2Data, oa, da, t0, dt, first, last, gradients);
      }
      else
      {
        for (int i = first; i <= last; ++i)
        {
          const double t = t0 + i * dt;
          double c[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
          this->GradientAtValueCoordinates(c, gradients + 3 * static_cast<std::size_t>(i));
        }
      }
    }
    for (int i = from; i <= to; ++i)
    {
      if (i < first || i > last || values[i] != values[i])
      {
        std::fill(gradients + 3 * static_cast<std::size_t>(i),
          gradients + 3 * static_cast<std::size_t>(i) + 3, 0.0f);
      }
    }
  }

  void PrepareGradients() const override
  {
    if (this->GradientsReady.load(std::memory_order_acquire))
    {
      return;
    }
    std::lock_guard<std::mutex> lock(this->GradientsMutex);
    if (!this->GradientsReady.load(std::memory_order_relaxed))
    {
      this->ComputeGradients();
      this->GradientsReady.store(true, std::memory_order_release);
    }
  }

  std::size_t GradientBytes() const override
  {
    return this->GradientsOnDemand
             ? 0
             : detail::GradientGrid::BytesFor(
                 static_cast<std::size_t>(
                   this->ValueDims[0] * this->ValueDims[1] * this->ValueDims[2]),
                 this->BlockConstant.size(), kExact);
  }

  bool ComputeGradientsOnDemand() const override
  {
    std::lock_guard<std::mutex> lock(this->GradientsMutex);
    if (this->GradientsOnDemand)
    {
      return false;
    }
    // Kept codes, if computed already, are let go; the next PrepareGradients keeps none.
    this->GradientsOnDemand = true;
    this->GradientsReady.store(false, std::memory_order_release);
    this->Gradients = detail::GradientGrid();
    this->UseGradientAVX2 = false;
    return true;
  }

private:
  // Samples [first, last] lie inside the grid (grown by the boundary tolerance); the others
  // are NaN. Deciding this once per call keeps bounds tests out of the loop.
  void InsideSamples(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t0, double dt,
    int count, int& first, int& last) const
  {
    double tIn = -std::numeric_limits<double>::infinity();
    double tOut = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
    {
      const double lo = -kBoundaryTolerance;
      const double hi = this->MaxIndex[a] + kBoundaryTolerance;
      if (d[a] == 0.0)
      {
        if (!(o[a] >= lo && o[a] <= hi))
        {
          tIn = std::numeric_limits<double>::infinity();
        }
        continue;
      }
      const double inverse = 1.0 / d[a];
      const double ta = (lo - o[a]) * inverse;
      const double tb = (hi - o[a]) * inverse;
      tIn = std::max(tIn, std::min(ta, tb));
      tOut = std::min(tOut, std::max(ta, tb));
    }
    first = count;
    last = -1;
    if (tIn <= tOut && dt > 0.0)
    {
      const double f = std::ceil((tIn - t0) / dt);
      const double l = std::floor((tOut - t0) / dt);
      first = static_cast<int>(std::max(0.0, std::min(f, static_cast<double>(count))));
      last = static_cast<int>(std::max(-1.0, std::min(l, static_cast<double>(count - 1))));
    }
  }

  // The per-point gradients, and the kernel's view of them.
  void ComputeGradients() const
  {
    detail::GradientShape shape;
    for (int a = 0; a < 3; ++a)
    {
      shape.Dims[a] = this->ValueDims[a];
      shape.Step[a] = this->Step[a];
      shape.Blocks[a] = this->Blocks[a];
    }
    shape.BlockShift = kBlockShift;
    if (this->GradientsOnDemand)
    {
      this->Gradients.PrepareOnDemand(
        this->Values, shape, this->WorldToIndex.linear().transpose(), kExact);
    }
    else
    {
      this->Gradients.Compute(
        this->Values, shape, this->WorldToIndex.linear().transpose(), kExact, kExact);
    }
    const long long* step = this->Gradients.PointStep();
    for (int a = 0; a < 3; ++a)
    {
      this->GradientNeighbour[a] = this->ValueDims[a] > 1 ? step[a] : 0;
    }
    const long long points = this->ValueDims[0] * this->ValueDims[1] * this->ValueDims[2];
    if (!this->UseAVX2 || this->GradientsOnDemand || 6 * points + 16 > 0x7FFFFFFFLL)
    {
      return;
    }
    detail::GradientArrays& k = this->GradientAVX2Data;
    k.Codes = this->Gradients.CodeData();
    k.Packed = this->Gradients.PackedData();
    k.ZeroBlocks = this->Gradients.ZeroBlockData();
    for (int a = 0; a < 3; ++a)
    {
      k.Step[a] = static_cast<int>(step[a]);
      k.Neighbour[a] = static_cast<int>(this->GradientNeighbour[a]);
    }
    std::copy(this->Gradients.ToWorldData(), this->Gradients.ToWorldData() + 9, k.ToWorld);
    this->UseGradientAVX2 = true;
  }

  // The gradient at point-index coordinates `c` (inside the grid), from the per-point ones as
  // the values are interpolated (computed already).
  void GradientAtValueCoordinates(double c[3], float gradient[3]) const
  {
    this->ClampToValueGrid(c);
    long long i0[3];
    float w[3];
    this->LowerCorner(c, i0, w);
    const bool demand = this->Gradients.OnDemand();
    if (this->Linear)
    {
      if (demand)
      {
        this->Gradients.InterpolateFrom(this->Values, i0, this->GradientNeighbour, w, gradient);
        return;
      }
      this->Gradients.Interpolate(i0, this->GradientNeighbour, w, gradient);
      return;
    }
    const long long nearest[3] = { i0[0] + (w[0] >= 0.5f && this->GradientNeighbour[0] != 0),
      i0[1] + (w[1] >= 0.5f && this->GradientNeighbour[1] != 0),
      i0[2] + (w[2] >= 0.5f && this->GradientNeighbour[2] != 0) };
    if (demand)
    {
      this->Gradients.AtPointFrom(this->Values, nearest, gradient);
      return;
    }
    this->Gradients.AtPoint(nearest, gradient);
  }

public:
  const std::vector<float>& BlockRanges() const override { return this->Ranges; }

  void SkipDistances(std::vector<std::uint8_t>& skip) const override
  {
    detail::ChessboardSkipDistances(this->Lattice(), skip);
  }

  // The interpolation of the points' gradients (GridGradients.h), turned into world space.
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override
  {
    this->PrepareGradients();
    const Eigen::Vector3d p = this->WorldToIndex * ray.At(t);
    double c[3] = { p[0], p[1], p[2] };
    this->GradientAtValueCoordinates(c, gradient);
    for (int a = 0; a < 3; ++a)
    {
      gradient[a] = std::isfinite(gradient[a]) ? gradient[a] : 0.0f;
    }
  }

private:
  // Sample i (inside the grid) into out[i]; in a skipped block, every sample up to where the
  // ray leaves it, or up to where it may reach a block that is not skipped, is NaN. Returns the
  // next sample to take. `perCell`: the ray parameter of one cell along the fastest axis.
  int SampleOne(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t0, double dt, int i,
    int last, float* out, const std::uint8_t* skipped, double perCell) const
  {
    long long i0[3];
    float w[3];
    const std::size_t block = this->Locate(o, d, t0 + i * dt, i0, w);
    if (skipped && skipped[block])
    {
      const int next = this->PastSkipped(o, d, t0, dt, i, last, i0, skipped[block], perCell);
      std::fill(out + i, out + next, std::numeric_limits<float>::quiet_NaN());
      return next;
    }
    out[i] = this->Interpolate(block, i0, w);
    return i + 1;
  }

  // The flags of `skip` when they are this grid's blocks' (one per block), else null.
  const std::uint8_t* SkipFlags(const SkipMask* skip) const
  {
    return skip && skip->Skip && skip->Skip->size() == this->BlockConstant.size()
             ? skip->Skip->data()
             : nullptr;
  }

  detail::BlockLattice Lattice() const
  {
    detail::BlockLattice lattice;
    std::copy(this->Blocks, this->Blocks + 3, lattice.Blocks);
    lattice.Shift = kBlockShift;
    lattice.CellShift = this->CellShift;
    return lattice;
  }

  // The ray parameter it takes to move one cell along the axis the ray moves fastest on.
  static double PerCell(const Eigen::Vector3d& d)
  {
    const double fastest = std::max({ std::abs(d[0]), std::abs(d[1]), std::abs(d[2]) });
    return fastest > 0.0 ? 1.0 / fastest : std::numeric_limits<double>::infinity();
  }

  // The cell (lower corner and weights) and block of the ray's point at t (index space).
  std::size_t Locate(
    const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t, long long i0[3], float w[3]) const
  {
    double c[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
    this->ClampToValueGrid(c);
    this->LowerCorner(c, i0, w);
    return this->BlockIndex(i0);
  }

  // After sample i, in a skipped block (cell i0, flag `flag`): the first sample at most last + 1
  // past both the block and the flag's reach (SkipReach), all of whose samples are skipped too.
  int PastSkipped(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t0, double dt, int i,
    int last, const long long i0[3], std::uint8_t flag, double perCell) const
  {
    const double tExit = std::max(
      this->BlockExit(o, d, i0), t0 + i * dt + detail::SkipReach(flag, kBlockShift) * perCell);
    int next = i + 1;
    // A long leap (a fine lattice's) starts two steps short of where it ends: every sample
    // before that lies short of the exit however the sums round, so the steps from there find
    // the sample stepping from i would.
    if (tExit - t0 > (next + 16) * dt && dt > 1e-9 * std::abs(tExit))
    {
      const double ahead = std::floor((tExit - t0) / dt) - 2.0;
      next = static_cast<int>(std::max(double(next), std::min(ahead, double(last) + 1.0)));
    }
    while (next <= last && t0 + next * dt < tExit)
    {
      ++next;
    }
    return next;
  }

  // The vector path, for linear interpolation of 8- and 16-bit unsigned and float data whose
  // array fits 32-bit offsets, on CPUs with AVX2.
  void SetUpAVX2()
  {
    constexpr bool u8 = std::is_same<T, std::uint8_t>::value;
    constexpr bool u16 = std::is_same<T, std::uint16_t>::value;
    constexpr bool f32 = std::is_same<T, float>::value;
    long long last = 0;
    for (int a = 0; a < 3; ++a)
    {
      last += this->Step[a] * (this->ValueDims[a] - 1);
    }
    const long long bytes = (last + 1) * static_cast<long long>(sizeof(T));
    if (!(u8 || u16 || f32) || !this->Linear || !this->Vectorize || !detail::HaveAVX2() ||
        bytes < 4 || this->BlockConstant.size() < 4 || bytes > 0x7FFFFFFFLL - 8 ||
        this->Blocks[0] * this->Blocks[1] * this->Blocks[2] > 0x7FFFFFFFLL)
    {
      return;
    }
    detail::GridArrays& k = this->AVX2Data;
    k.Values = this->Values;
    k.Bytes = static_cast<std::size_t>(bytes);
    k.Type = u8 ? detail::GridValueType::UInt8
                : (u16 ? detail::GridValueType::UInt16 : detail::GridValueType::Float32);
    for (int a = 0; a < 3; ++a)
    {
      k.Step[a] = static_cast<int>(this->Step[a]);
      k.Neighbour[a] = static_cast<int>(this->Neighbour[a]);
      k.LastCell[a] = static_cast<int>(this->LastCell[a]);
      k.MaxValueIndex[a] = this->MaxValueIndex[a];
    }
    k.CellShift = this->CellShift;
    k.BlockConstant = this->BlockConstant.data();
    k.AnyConstant = std::any_of(
      this->BlockConstant.begin(), this->BlockConstant.end(), [](float v) { return v == v; });
    k.Blocks[0] = static_cast<int>(this->Blocks[0]);
    k.Blocks[1] = static_cast<int>(this->Blocks[1]);
    k.NumberOfBlocks = static_cast<int>(this->BlockConstant.size());
    k.BlockShift = kBlockShift;
    this->UseAVX2 = true;
  }

  // Turns point-index coordinates (inside the grid) into coordinates in the value grid (cell
  // centres for cell data), clamped to it.
  void ClampToValueGrid(double c[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      const double v = c[a] - this->CellShift;
      c[a] = v < 0.0 ? 0.0 : (v > this->MaxValueIndex[a] ? this->MaxValueIndex[a] : v);
    }
  }

  // Lower corner of the value-grid cell holding `c`, kept one below the last point so that the
  // upper corner exists (the weight then reaches 1 at the last point), and the weights.
  void LowerCorner(const double c[3], long long i0[3], float w[3]) const
  {
    for (int a = 0; a < 3; ++a)
    {
      long long f = static_cast<long long>(c[a]);
      f = f > this->LastCell[a] ? this->LastCell[a] : f;
      i0[a] = f;
      w[a] = static_cast<float>(c[a] - static_cast<double>(f));
    }
  }

  // Ray parameter where the ray (in point-index coordinates) leaves the block holding the cell
  // with lower corner `i0`, slightly early so that round-off never skips a sample outside it.
  double BlockExit(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const long long i0[3]) const
  {
    double tExit = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
    {
      const double lo =
        static_cast<double>(static_cast<std::size_t>(i0[a]) / kBlock * kBlock) + this->CellShift;
      const double hi = lo + static_cast<double>(kBlock);
      if (d[a] > 0.0)
      {
        tExit = std::min(tExit, (hi - o[a]) / d[a]);
      }
      else if (d[a] < 0.0)
      {
        tExit = std::min(tExit, (lo - o[a]) / d[a]);
      }
    }
    return tExit - 1e-9 * (1.0 + std::abs(tExit));
  }

  float Interpolate(std::size_t block, const long long i0[3], const float w[3]) const
  {
    const float constant = this->BlockConstant[block];
    if (constant == constant) // not NaN: every point of the block holds this value
    {
      return constant;
    }
    const T* v =
      this->Values + (i0[0] * this->Step[0] + i0[1] * this->Step[1] + i0[2] * this->Step[2]);
    const long long sx = this->Neighbour[0];
    const long long sy = this->Neighbour[1];
    const long long sz = this->Neighbour[2];
    if (!this->Linear)
    {
      return static_cast<float>(
        Held(v[(w[0] >= 0.5f) * sx + (w[1] >= 0.5f) * sy + (w[2] >= 0.5f) * sz]));
    }
    const T v0 = Held(v[0]);
    const T vy = Held(v[sy]);
    const T vz = Held(v[sz]);
    const T vyz = Held(v[sz + sy]);
    const float c00 = v0 + w[0] * (static_cast<float>(Held(v[sx])) - v0);
    const float c10 = vy + w[0] * (static_cast<float>(Held(v[sy + sx])) - vy);
    const float c01 = vz + w[0] * (static_cast<float>(Held(v[sz + sx])) - vz);
    const float c11 = vyz + w[0] * (static_cast<float>(Held(v[sz + sy + sx])) - vyz);
    const float c0 = c00 + w[1] * (c10 - c00);
    const float c1 = c01 + w[1] * (c11 - c01);
    return c0 + w[2] * (c1 - c0);
  }

  float Value(long long i, long long j, long long k) const
  {
    return static_cast<float>(
      Held(this->Values[i * this->Step[0] + j * this->Step[1] + k * this->Step[2]]));
  }

  // Samples are floats: a finite double beyond a float's largest value is held there, where a
  // transfer function over values a float holds gives what it gives its largest values (and
  // samples are clamped to its domain). Other values, and other types, as they are.
  static T Held(T v)
  {
    if constexpr (std::is_same<T, double>::value)
    {
      constexpr double kHeld = static_cast<double>(std::numeric_limits<float>::max());
      return std::isfinite(v) ? std::min(std::max(v, -kHeld), kHeld) : v;
    }
    else
    {
      return v;
    }
  }

  // Lower cell corners are at most ValueDims - 2, so their blocks always exist.
  std::size_t BlockIndex(const long long i[3]) const
  {
    const auto bx = static_cast<std::size_t>(i[0]) / kBlock;
    const auto by = static_cast<std::size_t>(i[1]) / kBlock;
    const auto bz = static_cast<std::size_t>(i[2]) / kBlock;
    return bx + this->Blocks[0] * (by + this->Blocks[1] * bz);
  }

  // Per block: the range of its points' finite values, and its one value if all hold it.
  void ScanBlocks()
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Blocks[a] =
        std::max<long long>(1, (this->ValueDims[a] - 1 + static_cast<long long>(kBlock) - 1) /
                                 static_cast<long long>(kBlock));
    }
    const std::size_t blocks =
      static_cast<std::size_t>(this->Blocks[0] * this->Blocks[1] * this->Blocks[2]);
    this->BlockConstant.assign(blocks, std::numeric_limits<float>::quiet_NaN());
    this->Ranges.assign(2 * blocks, 0.0f);
    for (long long bz = 0; bz < this->Blocks[2]; ++bz)
      for (long long by = 0; by < this->Blocks[1]; ++by)
        for (long long bx = 0; bx < this->Blocks[0]; ++bx)
        {
          const long long size = static_cast<long long>(kBlock);
          const long long lo[3] = { bx * size, by * size, bz * size };
          long long hi[3];
          for (int a = 0; a < 3; ++a)
          {
            hi[a] = std::min(lo[a] + size, this->ValueDims[a] - 1);
          }
          float low = std::numeric_limits<float>::infinity();
          float high = -low;
          bool finite = true;
          for (long long k = lo[2]; k <= hi[2]; ++k)
            for (long long j = lo[1]; j <= hi[1]; ++j)
              for (long long i = lo[0]; i <= hi[0]; ++i)
              {
                const float v = this->Value(i, j, k);
                if (!std::isfinite(v))
                {
                  finite = false;
                  continue;
                }
                low = std::min(low, v);
                high = std::max(high, v);
              }
          const std::size_t b =
            static_cast<std::size_t>(bx + this->Blocks[0] * (by + this->Blocks[1] * bz));
          this->Ranges[2 * b] = low;
          this->Ranges[2 * b + 1] = high;
          if (finite && low == high)
          {
            this->BlockConstant[b] = low;
          }
        }
  }

  void ScanValues()
  {
    const long long n = this->ValueDims[0] * this->ValueDims[1] * this->ValueDims[2];
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
  double CellShift = 0.0; // cell centres lie half a point index in
  int Bits;
  bool Vectorize;
  long long PointDims[3] = { 0, 0, 0 };
  long long ValueDims[3] = { 0, 0, 0 };
  long long Step[3] = { 0, 0, 0 };      // array elements between neighbours along each axis
  long long Neighbour[3] = { 0, 0, 0 }; // Step, or 0 along an axis with a single value
  long long LastCell[3] = { 0, 0, 0 };  // largest lower cell corner
  double MaxIndex[3] = { 0, 0, 0 };     // last point index
  double MaxValueIndex[3] = { 0, 0, 0 };
  std::array<double, 2> Range = { 0.0, 0.0 };
  bool HasNonFinite = false;
  long long Blocks[3] = { 1, 1, 1 };
  std::vector<float> BlockConstant; // per block: its one value, or NaN
  std::vector<float> Ranges;        // per block: smallest and largest finite value
  detail::GridArrays AVX2Data;
  bool UseAVX2 = false;
  // Per-point gradients, computed on first use (PrepareGradients).
  mutable std::mutex GradientsMutex;
  mutable std::atomic<bool> GradientsReady{ false };
  mutable bool GradientsOnDemand = false; // ComputeGradientsOnDemand was asked
  mutable detail::GradientGrid Gradients;
  mutable long long GradientNeighbour[3] = { 0, 0, 0 }; // points between neighbours, or 0
  mutable detail::GradientArrays GradientAVX2Data;
  mutable bool UseGradientAVX2 = false;
};

template <typename T>
std::shared_ptr<const Sampler> Make(const GridDescription& grid, int exactBits)
{
  return std::make_shared<GridSamplerT<T>>(grid, exactBits);
}

} // namespace

std::shared_ptr<const Sampler> MakeGridSampler(const GridDescription& grid, std::string& error)
{
  if (!grid.Data)
  {
    error = "the grid has no scalar values";
    return nullptr;
  }
  if (grid.Components < 1)
  {
    error = "the grid's scalars have no components";
    return nullptr;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (grid.Dims[a] < 2)
    {
      error = "the grid needs at least 2 points along every axis";
      return nullptr;
    }
  }
  if (!grid.WorldToIndex.matrix().allFinite() ||
      std::abs(grid.WorldToIndex.linear().determinant()) == 0.0)
  {
    error = "the grid's spacing or orientation is degenerate (zero spacing or a singular matrix)";
    return nullptr;
  }
  switch (grid.Type)
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
      return Make<std::int32_t>(grid, 32);
    case ScalarType::UInt32:
      return Make<std::uint32_t>(grid, 32);
    case ScalarType::Int64:
      return Make<std::int64_t>(grid, 64);
    case ScalarType::UInt64:
      return Make<std::uint64_t>(grid, 64);
    case ScalarType::Float32:
      return Make<float>(grid, 0);
    case ScalarType::Float64:
      return Make<double>(grid, 0);
  }
  error = "unsupported scalar type";
  return nullptr;
}

} // namespace savr

#include "amr/AMRSampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace savr
{
namespace
{

constexpr std::uint8_t kHiddenCell = 32;
// Points this close outside the hierarchy's level-0 region (in level-0 cells) still count as
// inside: ray entry and exit points carry round-off.
constexpr double kBoundaryTolerance = 1e-6;
// Level-0 blocks are binned on a grid of at most this many bins per axis.
constexpr int kBinsPerAxis = 16;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

struct Block
{
  int Level = 0;
  long long Lo[3] = { 0, 0, 0 }; // valid cells (inclusive)
  long long Hi[3] = { 0, 0, 0 };
  long long ValueLo[3] = { 0, 0, 0 }; // the array's first value index (global, at Level)
  long long ValueCount[3] = { 0, 0, 0 };
  long long CellCount[3] = { 0, 0, 0 };
  const void* Data = nullptr;
  const std::uint8_t* Ghosts = nullptr;
  std::vector<int> Children; // blocks of the next level that overlap this one
  // The block's valid region in hierarchy coordinates.
  Eigen::Vector3d Min = Eigen::Vector3d::Zero();
  Eigen::Vector3d Max = Eigen::Vector3d::Zero();

  bool Contains(const Eigen::Vector3d& q, double tolerance) const
  {
    return q[0] >= this->Min[0] - tolerance && q[0] <= this->Max[0] + tolerance &&
           q[1] >= this->Min[1] - tolerance && q[1] <= this->Max[1] + tolerance &&
           q[2] >= this->Min[2] - tolerance && q[2] <= this->Max[2] + tolerance;
  }
};

template <typename T>
class AMRSamplerT final : public Sampler
{
public:
  AMRSamplerT(const AMRDescription& amr, std::vector<Block> blocks, int exactBits)
    : Blocks(std::move(blocks))
    , Origin(amr.Origin)
    , Spacing(amr.Spacing)
    , WorldToData(amr.WorldToData)
    , Linear(amr.Interpolation == Interpolation::Linear)
    , Shift(amr.CellData ? 0.5 : 0.0)
    , Bits(exactBits)
  {
    this->BuildIndex();
    this->ScanValues();
    const bool given = (amr.BoundsMin.array() <= amr.BoundsMax.array()).all() &&
                       amr.BoundsMin.allFinite() && amr.BoundsMax.allFinite();
    this->ClipMin = given ? amr.BoundsMin : this->DomainMin;
    this->ClipMax = given ? amr.BoundsMax : this->DomainMax;
  }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    return ClipToBox(this->WorldToData * ray.Origin, this->WorldToData.linear() * ray.Direction,
      this->ClipMin, this->ClipMax, tEnter, tExit);
  }

  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override
  {
    const Eigen::Affine3d toWorld = this->WorldToData.inverse();
    for (int c = 0; c < 8; ++c)
    {
      corners[c] = toWorld * Eigen::Vector3d((c & 1) ? this->ClipMax[0] : this->ClipMin[0],
                               (c & 2) ? this->ClipMax[1] : this->ClipMin[1],
                               (c & 4) ? this->ClipMax[2] : this->ClipMin[2]);
    }
    return toWorld.matrix().allFinite();
  }

  std::array<double, 2> ValueRange() const override { return this->Range; }
  int ExactBits() const override { return this->Bits; }
  bool MayReturnNaN() const override { return this->HasHoles; }

  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* /*skip*/) const override
  {
    const Eigen::Vector3d o = this->WorldToData * ray.Origin;
    const Eigen::Vector3d d = this->WorldToData.linear() * ray.Direction;
    const Block* current = nullptr;
    for (int i = 0; i < count; ++i)
    {
      const Eigen::Vector3d q = o + (t0 + i * dt) * d;
      // Consecutive samples mostly stay in one leaf block: test it before searching.
      if (!(current && current->Children.empty() && current->Contains(q, 0.0)))
      {
        current = this->Find(q, std::numeric_limits<int>::max());
      }
      out[i] = current ? this->SampleIn(*current, q) : kNaN;
    }
  }

  // Central differences one cell of the sampled level apart, in hierarchy coordinates, turned
  // into world space.
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override
  {
    const Eigen::Vector3d q = this->WorldToData * ray.At(t);
    const Block* block = this->Find(q, std::numeric_limits<int>::max());
    if (!block)
    {
      gradient[0] = gradient[1] = gradient[2] = 0.0f;
      return;
    }
    Eigen::Vector3d g;
    for (int a = 0; a < 3; ++a)
    {
      const double h = this->Spacing[block->Level][a];
      Eigen::Vector3d plus = q;
      Eigen::Vector3d minus = q;
      plus[a] = std::min(q[a] + h, this->DomainMax[a]);
      minus[a] = std::max(q[a] - h, this->DomainMin[a]);
      const float vp = this->ValueAtPoint(plus);
      const float vm = this->ValueAtPoint(minus);
      g[a] = plus[a] > minus[a] && vp == vp && vm == vm ? (vp - vm) / (plus[a] - minus[a]) : 0.0;
    }
    const Eigen::Vector3d world = this->WorldToData.linear().transpose() * g;
    for (int a = 0; a < 3; ++a)
    {
      gradient[a] = std::isfinite(world[a]) ? static_cast<float>(world[a]) : 0.0f;
    }
  }

private:
  // The finest block of level at most `maxLevel` containing q, or null.
  const Block* Find(const Eigen::Vector3d& q, int maxLevel) const
  {
    const Block* found = nullptr;
    long long bin[3];
    for (int a = 0; a < 3; ++a)
    {
      const double b = std::floor((q[a] - this->DomainMin[a]) / this->BinSize[a]);
      if (!(b >= -1.0 && b <= static_cast<double>(this->Bins[a])))
      {
        return nullptr;
      }
      bin[a] = std::min(std::max(static_cast<long long>(b), 0LL), this->Bins[a] - 1);
    }
    const std::vector<int>& roots =
      this->BinBlocks[bin[0] + this->Bins[0] * (bin[1] + this->Bins[1] * bin[2])];
    const double tolerance = kBoundaryTolerance * this->Spacing[0].maxCoeff();
    for (int r : roots)
    {
      if (this->Blocks[r].Contains(q, tolerance))
      {
        found = &this->Blocks[r];
        break;
      }
    }
    while (found && found->Level < maxLevel)
    {
      const Block* child = nullptr;
      for (int c : found->Children)
      {
        if (this->Blocks[c].Contains(q, 0.0))
        {
          child = &this->Blocks[c];
          break;
        }
      }
      if (!child)
      {
        break;
      }
      found = child;
    }
    return found;
  }

  float ValueAtPoint(const Eigen::Vector3d& q) const
  {
    const Block* block = this->Find(q, std::numeric_limits<int>::max());
    return block ? this->SampleIn(*block, q) : kNaN;
  }

  // The field at q, sampled on `block` (which contains q).
  float SampleIn(const Block& block, const Eigen::Vector3d& q) const
  {
    const int level = block.Level;
    const Eigen::Vector3d& h = this->Spacing[level];
    double c[3];
    long long cell[3];
    for (int a = 0; a < 3; ++a)
    {
      const double x = (q[a] - this->Origin[a]) / h[a];
      cell[a] = std::min(std::max(static_cast<long long>(std::floor(x)), block.Lo[a]), block.Hi[a]);
      c[a] = x - this->Shift;
    }
    if (block.Ghosts)
    {
      const long long local =
        (cell[0] - block.ValueLo[0]) +
        block.CellCount[0] *
          ((cell[1] - block.ValueLo[1]) + block.CellCount[1] * (cell[2] - block.ValueLo[2]));
      if (block.Ghosts[local] & kHiddenCell)
      {
        return kNaN;
      }
    }
    if (!this->Linear)
    {
      long long v[3];
      for (int a = 0; a < 3; ++a)
      {
        // The nearest value: the cell itself, or the nearest of its corner points.
        v[a] = this->Shift > 0.0 ? cell[a] : static_cast<long long>(std::floor(c[a] + 0.5));
      }
      return this->Value(block, v, q);
    }
    return this->Trilinear(block, c);
  }

  // Trilinear interpolation between the 8 values around value-lattice coordinates c of the
  // block's level; values outside the block come from wherever the hierarchy holds them.
  float Trilinear(const Block& block, const double c[3]) const
  {
    long long v0[3];
    double w[3];
    bool inside = true;
    const Eigen::Vector3d& lowest = this->LowestValue[block.Level];
    const Eigen::Vector3d& highest = this->HighestValue[block.Level];
    for (int a = 0; a < 3; ++a)
    {
      // Within the outermost values of the hierarchy, as a single grid clamps.
      const double x = std::min(std::max(c[a], lowest[a]), highest[a]);
      const double f = std::floor(x);
      v0[a] = static_cast<long long>(f);
      w[a] = x - f;
      inside =
        inside && v0[a] >= block.ValueLo[a] && v0[a] + 1 < block.ValueLo[a] + block.ValueCount[a];
    }
    float corner[8];
    if (inside)
    {
      const T* data = static_cast<const T*>(block.Data);
      const long long sx = 1;
      const long long sy = block.ValueCount[0];
      const long long sz = sy * block.ValueCount[1];
      const T* p = data + (v0[0] - block.ValueLo[0]) + sy * (v0[1] - block.ValueLo[1]) +
                   sz * (v0[2] - block.ValueLo[2]);
      for (int k = 0; k < 8; ++k)
      {
        corner[k] = static_cast<float>(p[(k & 1) * sx + ((k >> 1) & 1) * sy + ((k >> 2) & 1) * sz]);
      }
    }
    else
    {
      const Eigen::Vector3d& h = this->Spacing[block.Level];
      for (int k = 0; k < 8; ++k)
      {
        const long long v[3] = { v0[0] + (k & 1), v0[1] + ((k >> 1) & 1), v0[2] + ((k >> 2) & 1) };
        Eigen::Vector3d at;
        for (int a = 0; a < 3; ++a)
        {
          at[a] = this->Origin[a] + (static_cast<double>(v[a]) + this->Shift) * h[a];
        }
        corner[k] = this->Value(block, v, at);
      }
    }
    const float c00 = corner[0] + static_cast<float>(w[0]) * (corner[1] - corner[0]);
    const float c10 = corner[2] + static_cast<float>(w[0]) * (corner[3] - corner[2]);
    const float c01 = corner[4] + static_cast<float>(w[0]) * (corner[5] - corner[4]);
    const float c11 = corner[6] + static_cast<float>(w[0]) * (corner[7] - corner[6]);
    const float a0 = c00 + static_cast<float>(w[1]) * (c10 - c00);
    const float a1 = c01 + static_cast<float>(w[1]) * (c11 - c01);
    return a0 + static_cast<float>(w[2]) * (a1 - a0);
  }

  // Value index v of `block`'s level, at hierarchy position `at`: read from the block when its
  // array holds it, else from the block of the same level holding it, else interpolated on the
  // finest coarser level there; outside the hierarchy, the block's nearest value.
  float Value(const Block& block, const long long v[3], const Eigen::Vector3d& at) const
  {
    if (const T* p = this->Lookup(block, v))
    {
      return static_cast<float>(*p);
    }
    const Block* other = this->Find(at, block.Level);
    if (other && other->Level == block.Level)
    {
      if (const T* p = this->Lookup(*other, v))
      {
        return static_cast<float>(*p);
      }
    }
    else if (other && other->Level < block.Level)
    {
      const Eigen::Vector3d& h = this->Spacing[other->Level];
      double c[3];
      for (int a = 0; a < 3; ++a)
      {
        c[a] = (at[a] - this->Origin[a]) / h[a] - this->Shift;
      }
      return this->Trilinear(*other, c);
    }
    long long clamped[3];
    for (int a = 0; a < 3; ++a)
    {
      clamped[a] =
        std::min(std::max(v[a], block.ValueLo[a]), block.ValueLo[a] + block.ValueCount[a] - 1);
    }
    return static_cast<float>(*this->Lookup(block, clamped));
  }

  const T* Lookup(const Block& block, const long long v[3]) const
  {
    long long local[3];
    for (int a = 0; a < 3; ++a)
    {
      local[a] = v[a] - block.ValueLo[a];
      if (local[a] < 0 || local[a] >= block.ValueCount[a])
      {
        return nullptr;
      }
    }
    return static_cast<const T*>(block.Data) +
           (local[0] + block.ValueCount[0] * (local[1] + block.ValueCount[1] * local[2]));
  }

  void BuildIndex()
  {
    // The level-0 region, and a bin grid over it listing the level-0 blocks in each bin.
    this->DomainMin = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    this->DomainMax = -this->DomainMin;
    double volume = 0.0;
    for (Block& b : this->Blocks)
    {
      const Eigen::Vector3d& h = this->Spacing[b.Level];
      for (int a = 0; a < 3; ++a)
      {
        b.Min[a] = this->Origin[a] + static_cast<double>(b.Lo[a]) * h[a];
        b.Max[a] = this->Origin[a] + static_cast<double>(b.Hi[a] + 1) * h[a];
      }
      if (b.Level == 0)
      {
        this->DomainMin = this->DomainMin.cwiseMin(b.Min);
        this->DomainMax = this->DomainMax.cwiseMax(b.Max);
        volume += (b.Max - b.Min).prod();
      }
    }
    for (const Eigen::Vector3d& h : this->Spacing)
    {
      const Eigen::Vector3d lo = (this->DomainMin - this->Origin).cwiseQuotient(h);
      const Eigen::Vector3d hi = (this->DomainMax - this->Origin).cwiseQuotient(h);
      this->LowestValue.push_back(lo);
      this->HighestValue.push_back(hi - Eigen::Vector3d::Constant(2.0 * this->Shift));
    }
    const double box = (this->DomainMax - this->DomainMin).prod();
    this->HasHoles = volume < box * (1.0 - 1e-9);
    for (int a = 0; a < 3; ++a)
    {
      const double cells = (this->DomainMax[a] - this->DomainMin[a]) / this->Spacing[0][a];
      this->Bins[a] = std::max(
        1LL, std::min<long long>(kBinsPerAxis, static_cast<long long>(std::lround(cells))));
      this->BinSize[a] =
        (this->DomainMax[a] - this->DomainMin[a]) / static_cast<double>(this->Bins[a]);
    }
    this->BinBlocks.assign(
      static_cast<std::size_t>(this->Bins[0] * this->Bins[1] * this->Bins[2]), {});
    for (int i = 0; i < static_cast<int>(this->Blocks.size()); ++i)
    {
      const Block& b = this->Blocks[i];
      if (b.Level != 0)
      {
        continue;
      }
      long long lo[3];
      long long hi[3];
      for (int a = 0; a < 3; ++a)
      {
        const double tolerance = kBoundaryTolerance * this->Spacing[0][a];
        lo[a] = std::max(0LL, static_cast<long long>(std::floor(
                                (b.Min[a] - tolerance - this->DomainMin[a]) / this->BinSize[a])));
        hi[a] = std::min(this->Bins[a] - 1,
          static_cast<long long>(
            std::floor((b.Max[a] + tolerance - this->DomainMin[a]) / this->BinSize[a])));
      }
      for (long long z = lo[2]; z <= hi[2]; ++z)
        for (long long y = lo[1]; y <= hi[1]; ++y)
          for (long long x = lo[0]; x <= hi[0]; ++x)
          {
            this->BinBlocks[x + this->Bins[0] * (y + this->Bins[1] * z)].push_back(i);
          }
    }
    // Each block's children: the blocks of the next level overlapping it.
    std::vector<std::vector<int>> byLevel;
    for (int i = 0; i < static_cast<int>(this->Blocks.size()); ++i)
    {
      const int level = this->Blocks[i].Level;
      if (static_cast<int>(byLevel.size()) <= level)
      {
        byLevel.resize(level + 1);
      }
      byLevel[level].push_back(i);
    }
    for (std::size_t level = 0; level + 1 < byLevel.size(); ++level)
    {
      for (int p : byLevel[level])
      {
        Block& parent = this->Blocks[p];
        for (int c : byLevel[level + 1])
        {
          const Block& child = this->Blocks[c];
          bool overlap = true;
          for (int a = 0; a < 3; ++a)
          {
            overlap = overlap && child.Min[a] < parent.Max[a] && child.Max[a] > parent.Min[a];
          }
          if (overlap)
          {
            parent.Children.push_back(c);
          }
        }
      }
    }
  }

  void ScanValues()
  {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Block& b : this->Blocks)
    {
      const T* data = static_cast<const T*>(b.Data);
      const long long n = b.ValueCount[0] * b.ValueCount[1] * b.ValueCount[2];
      for (long long i = 0; i < n; ++i)
      {
        const double v = static_cast<double>(data[i]);
        if (!std::isfinite(v))
        {
          this->HasHoles = true;
          continue;
        }
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      if (b.Ghosts)
      {
        const long long cells = b.CellCount[0] * b.CellCount[1] * b.CellCount[2];
        for (long long i = 0; i < cells; ++i)
        {
          this->HasHoles = this->HasHoles || (b.Ghosts[i] & kHiddenCell) != 0;
        }
      }
    }
    this->Range = lo <= hi ? std::array<double, 2>{ lo, hi } : std::array<double, 2>{ 0.0, 0.0 };
  }

  std::vector<Block> Blocks;
  Eigen::Vector3d Origin;
  std::vector<Eigen::Vector3d> Spacing;
  Eigen::Affine3d WorldToData;
  bool Linear;
  double Shift; // value positions lie this many cells in from the cell corners
  int Bits;
  Eigen::Vector3d DomainMin = Eigen::Vector3d::Zero();
  Eigen::Vector3d DomainMax = Eigen::Vector3d::Zero();
  // What rays are clipped to: AMRDescription's bounds, or the domain of the blocks given.
  Eigen::Vector3d ClipMin = Eigen::Vector3d::Zero();
  Eigen::Vector3d ClipMax = Eigen::Vector3d::Zero();
  long long Bins[3] = { 1, 1, 1 };
  Eigen::Vector3d BinSize = Eigen::Vector3d::Ones();
  std::vector<std::vector<int>> BinBlocks;
  // Per level: the value-lattice coordinates of the hierarchy's outermost values.
  std::vector<Eigen::Vector3d> LowestValue;
  std::vector<Eigen::Vector3d> HighestValue;
  std::array<double, 2> Range = { 0.0, 0.0 };
  bool HasHoles = false;
};

template <typename T>
std::shared_ptr<const Sampler> Make(const AMRDescription& amr, std::vector<Block> blocks, int bits)
{
  return std::make_shared<AMRSamplerT<T>>(amr, std::move(blocks), bits);
}

} // namespace

std::shared_ptr<const Sampler> MakeAMRSampler(const AMRDescription& amr, std::string& error)
{
  if (amr.Blocks.empty())
  {
    error = "the AMR hierarchy has no blocks";
    return nullptr;
  }
  if (!amr.WorldToData.matrix().allFinite() ||
      std::abs(amr.WorldToData.linear().determinant()) == 0.0 || !amr.Origin.allFinite())
  {
    error =
      "the AMR hierarchy's placement is degenerate (a singular matrix or a non-finite origin)";
    return nullptr;
  }
  for (const Eigen::Vector3d& h : amr.Spacing)
  {
    if (!h.allFinite() || !(h.minCoeff() > 0.0))
    {
      error = "an AMR level's spacing is zero, negative or not finite";
      return nullptr;
    }
  }
  std::vector<Block> blocks;
  bool haveRoot = false;
  for (const AMRBlockDescription& d : amr.Blocks)
  {
    if (d.Level < 0 || d.Level >= static_cast<int>(amr.Spacing.size()))
    {
      error = "an AMR block's level has no spacing";
      return nullptr;
    }
    if (!d.Data)
    {
      error = "an AMR block has no scalar values";
      return nullptr;
    }
    Block b;
    b.Level = d.Level;
    b.Data = d.Data;
    b.Ghosts = d.CellGhosts;
    for (int a = 0; a < 3; ++a)
    {
      b.Lo[a] = d.Lo[a];
      b.Hi[a] = d.Hi[a];
      b.ValueLo[a] = d.ArrayLo[a];
      b.CellCount[a] = d.ArrayCells[a];
      b.ValueCount[a] = d.ArrayCells[a] + (amr.CellData ? 0 : 1);
      if (d.Hi[a] < d.Lo[a] || d.ArrayCells[a] < 1 || d.Lo[a] < d.ArrayLo[a] ||
          d.Hi[a] >= d.ArrayLo[a] + d.ArrayCells[a])
      {
        error = "an AMR block's box is empty or lies outside its array";
        return nullptr;
      }
    }
    haveRoot = haveRoot || d.Level == 0;
    blocks.push_back(std::move(b));
  }
  if (!haveRoot)
  {
    error = "the AMR hierarchy has no level-0 block";
    return nullptr;
  }
  switch (amr.Type)
  {
    case ScalarType::Int8:
      return Make<std::int8_t>(amr, std::move(blocks), 8);
    case ScalarType::UInt8:
      return Make<std::uint8_t>(amr, std::move(blocks), 8);
    case ScalarType::Int16:
      return Make<std::int16_t>(amr, std::move(blocks), 16);
    case ScalarType::UInt16:
      return Make<std::uint16_t>(amr, std::move(blocks), 16);
    case ScalarType::Int32:
      return Make<std::int32_t>(amr, std::move(blocks), 32);
    case ScalarType::UInt32:
      return Make<std::uint32_t>(amr, std::move(blocks), 32);
    case ScalarType::Int64:
      return Make<std::int64_t>(amr, std::move(blocks), 64);
    case ScalarType::UInt64:
      return Make<std::uint64_t>(amr, std::move(blocks), 64);
    case ScalarType::Float32:
      return Make<float>(amr, std::move(blocks), 0);
    case ScalarType::Float64:
      return Make<double>(amr, std::move(blocks), 0);
  }
  error = "unsupported scalar type";
  return nullptr;
}

} // namespace savr

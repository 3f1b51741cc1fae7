// The unstructured sampler's setup (the cells kept, the value range, the tetrahedra's lines, the
// hull sides), where a walk's first cell is tried first, and MakeUnstructuredSampler, which
// checks the mesh first.
#include "mesh/UnstructuredWalk.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <string>
#include <vector>

namespace savr
{
namespace unstructured
{
namespace
{
// The first cell of the last walk this thread began: the next ray, usually its neighbour in
// the image, most often enters the mesh by the same cell or one across its sides. Only a
// guess: see UnstructuredSampler::FirstCell.
struct EntrySeed
{
  const UnstructuredSampler* Mesh = nullptr;
  std::uint32_t Cell = kNone;
};
thread_local EntrySeed Seed;
} // namespace

void UnstructuredSampler::ScanValues()
{
  double lo = kInfinity;
  double hi = -kInfinity;
  auto scan = [&](float v)
  {
    if (std::isfinite(v))
    {
      lo = std::min(lo, static_cast<double>(v));
      hi = std::max(hi, static_cast<double>(v));
    }
  };
  if (this->CellValues)
  {
    for (float v : this->Values)
    {
      scan(v);
    }
  }
  else
  {
    // Only the points of the cells kept.
    std::vector<std::uint8_t> used(this->Values.size(), 0);
    for (std::uint32_t id : this->Faces.AllCellPoints())
    {
      if (id != kNone)
      {
        used[id] = 1;
      }
    }
    for (std::size_t i = 0; i < used.size(); ++i)
    {
      if (used[i])
      {
        scan(this->Values[i]);
      }
    }
  }
  this->Range = lo <= hi ? std::array<double, 2>{ lo, hi } : std::array<double, 2>{ 0.0, 0.0 };
}

void UnstructuredSampler::BuildTetraLines(const CellOrder& order)
{
  for (int a = 0; a < 3; ++a)
  {
    this->Centre[a] = 0.5 * (order.Lo[a] + order.Hi[a]);
  }
  const std::uint32_t cells = this->Faces.CellCount();
  bool any = false;
  for (std::uint32_t c = 0; c < cells && !any; ++c)
  {
    any = this->Faces.Kind(c) == CellKind::Tetra;
  }
  if (this->CellValues || !any)
  {
    return;
  }
  this->TetraLines.resize(cells);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, cells, 1024),
    [&](const tbb::blocked_range<std::uint32_t>& range)
    {
      for (std::uint32_t c = range.begin(); c != range.end(); ++c)
      {
        this->TetraLines[c] = this->TetraLineOf(c);
      }
    });
}

void UnstructuredSampler::BuildCellMaps()
{
  if (this->CellValues)
  {
    return;
  }
  const std::uint32_t cells = this->Faces.CellCount();
  std::vector<std::uint32_t> slots(cells, kNone);
  std::uint32_t curved = 0;
  for (std::uint32_t c = 0; c < cells; ++c)
  {
    if (this->Faces.Kind(c) != CellKind::Tetra && !this->Faces.IsDirect(c))
    {
      slots[c] = curved++;
    }
  }
  if (curved == 0)
  {
    return;
  }
  this->CellMaps.resize(curved);
  const Eigen::Vector3d centre(this->Centre[0], this->Centre[1], this->Centre[2]);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, cells, 1024),
    [&](const tbb::blocked_range<std::uint32_t>& range)
    {
      for (std::uint32_t c = range.begin(); c != range.end(); ++c)
      {
        if (slots[c] == kNone)
        {
          continue;
        }
        CellVertices data = this->Gather(c);
        for (int k = 0; k < data.Points; ++k)
        {
          data.X[k] -= centre;
        }
        const Polynomial polynomial(data);
        CellMap& map = this->CellMaps[slots[c]];
        for (int m = 0; m < 8; ++m)
        {
          for (int a = 0; a < 3; ++a)
          {
            map.A[m][a] = static_cast<float>(polynomial.A[m][a]);
          }
          map.B[m] = static_cast<float>(polynomial.B[m]);
        }
        // Newton's first step from the centre, as an affine map of p (none where the map is
        // singular there: the guess is then the centre).
        const double* r = ShapeOf(data.Kind).Centre;
        Eigen::Vector3d x;
        Eigen::Matrix3d jacobian;
        polynomial.Map(r, x, jacobian);
        Eigen::Matrix3d inverse;
        double det;
        bool invertible;
        jacobian.computeInverseAndDetWithCheck(inverse, det, invertible, 0.0);
        if (!invertible || !inverse.allFinite())
        {
          inverse.setZero();
        }
        const Eigen::Vector3d shift = Eigen::Vector3d(r[0], r[1], r[2]) - inverse * x;
        for (int a = 0; a < 3; ++a)
        {
          for (int b = 0; b < 3; ++b)
          {
            map.Guess[a][b] = static_cast<float>(inverse(a, b));
          }
          map.Shift[a] = static_cast<float>(shift[a]);
        }
      }
    });
  this->MapSlots = std::move(slots);
}

// A seed is taken only where the line enters by a hull side well inside its triangle: no cell
// comes before that side or ties with the seed there, so the hierarchy would find the same cell
// at the same parameter, and images do not depend on which ray ran before which.
bool UnstructuredSampler::FirstCell(
  const Line& line, double tMin, double tMax, std::uint32_t& cell, double& tIn) const
{
  EntrySeed& seed = Seed;
  if (seed.Mesh == this && this->NearSeed(seed.Cell, line, tMin, tMax, cell, tIn))
  {
    seed.Cell = cell;
    return true;
  }
  if (!this->FindFirst(line, tMin, tMax, false, cell, tIn))
  {
    return false;
  }
  seed.Mesh = this;
  seed.Cell = cell;
  return true;
}

bool UnstructuredSampler::NearSeed(std::uint32_t seed, const Line& line, double tMin, double tMax,
  std::uint32_t& cell, double& tIn) const
{
  if (seed >= this->Faces.CellCount())
  {
    return false;
  }
  const Side* side = this->Faces.FirstSide(seed);
  const Side* end = this->Faces.FirstSide(seed + 1);
  for (std::int32_t c = static_cast<std::int32_t>(seed);; c = (side++)->Neighbour)
  {
    if (c >= 0 && this->Faces.EntersByHull(static_cast<std::uint32_t>(c), line, tMin, tIn) &&
        tIn <= tMax)
    {
      cell = static_cast<std::uint32_t>(c);
      return true;
    }
    if (side == end)
    {
      return false;
    }
  }
}

void UnstructuredSampler::FindHullSides()
{
  // Boxes hold their cells grown by the tolerance: a node whose box reaches at most this far
  // beyond a plane holds no point beyond it by more than the tolerance. On a box-shaped mesh
  // the root already answers for every side of the box.
  constexpr int kBudget = 512; // nodes per side; past it the side is left open
  const double tolerance = this->Tolerance;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->Faces.SideCount(), 1024),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t k = range.begin(); k < range.end(); ++k)
      {
        const Side& side = this->Faces.SideAt(static_cast<std::uint32_t>(k));
        const double spread = std::abs(side.N[0]) + std::abs(side.N[1]) + std::abs(side.N[2]);
        if (side.Neighbour != kOpenSide || !(spread > 0.0))
        {
          continue;
        }
        const bool past =
          this->Hierarchy.AnyPast(side.N, side.D, tolerance * (1.0 + spread), kBudget,
            [&](std::uint32_t cell)
            {
              const std::uint32_t* ids = this->Faces.PointIds(cell);
              const int n = ShapeOf(this->Faces.Kind(cell)).Points;
              for (int i = 0; i < n; ++i)
              {
                const Eigen::Vector3d x = this->Faces.Point(ids[i]);
                const double p[3] = { x[0], x[1], x[2] };
                if (!(Dot(side.N, p) - side.D <= tolerance))
                {
                  return true;
                }
              }
              return false;
            });
        if (!past)
        {
          this->Faces.SetHullSide(static_cast<std::uint32_t>(k));
        }
      }
    });
}

UnstructuredSampler::TetraLine UnstructuredSampler::TetraLineOf(std::uint32_t cell) const
{
  TetraLine line = { { 0, 0, 0 }, std::numeric_limits<float>::quiet_NaN(), { 0, 0, 0 } };
  if (this->Faces.Kind(cell) != CellKind::Tetra || this->Faces.IsDegenerate(cell))
  {
    return line;
  }
  const CellVertices data = this->Gather(cell);
  const Eigen::Vector3d e1 = data.X[1] - data.X[0];
  const Eigen::Vector3d e2 = data.X[2] - data.X[0];
  const Eigen::Vector3d e3 = data.X[3] - data.X[0];
  const double det = e1.dot(e2.cross(e3));
  // Cramer's rule for G . e_i = f_i - f_0.
  const Eigen::Vector3d g =
    ((data.F[1] - data.F[0]) * e2.cross(e3) + (data.F[2] - data.F[0]) * e3.cross(e1) +
      (data.F[3] - data.F[0]) * e1.cross(e2)) /
    det;
  const Eigen::Vector3d c = 0.25 * (data.X[0] + data.X[1] + data.X[2] + data.X[3]);
  const double f = 0.25 * (data.F[0] + data.F[1] + data.F[2] + data.F[3]);
  if (!(std::abs(det) > 0.0) || !g.allFinite() || !std::isfinite(f))
  {
    return line;
  }
  for (int a = 0; a < 3; ++a)
  {
    line.C[a] = static_cast<float>(c[a] - this->Centre[a]);
    line.G[a] = static_cast<float>(g[a]);
  }
  line.F = static_cast<float>(f);
  return line;
}

} // namespace unstructured

using unstructured::KindOf;
using unstructured::kMaxCells;
using unstructured::kNone;
using unstructured::kShapes;

std::shared_ptr<const Sampler> MakeUnstructuredSampler(
  const UnstructuredDescription& mesh, std::string& error, std::size_t* skippedCells)
{
  if (skippedCells)
  {
    *skippedCells = 0;
  }
  if (!mesh.Points || mesh.NumberOfPoints == 0)
  {
    error = "the mesh has no points";
    return nullptr;
  }
  if (mesh.NumberOfPoints >= kNone)
  {
    error = "the mesh has too many points (at most 2^32 - 2)";
    return nullptr;
  }
  if (!mesh.Offsets || !mesh.Connectivity || !mesh.Types || mesh.NumberOfCells == 0)
  {
    error = "the mesh has no cells (offsets, connectivity or types missing)";
    return nullptr;
  }
  if (!mesh.Values)
  {
    error = "the mesh has no scalar values";
    return nullptr;
  }
  if (mesh.Offsets[0] < 0)
  {
    error = "the mesh's cell offsets start below 0";
    return nullptr;
  }
  std::vector<std::size_t> kept;
  std::size_t skipped = 0;
  const auto points = static_cast<std::int64_t>(mesh.NumberOfPoints);
  for (std::size_t c = 0; c < mesh.NumberOfCells; ++c)
  {
    const std::int64_t begin = mesh.Offsets[c];
    const std::int64_t end = mesh.Offsets[c + 1];
    if (end < begin)
    {
      error = "the mesh's cell offsets decrease at cell " + std::to_string(c);
      return nullptr;
    }
    const int kind = KindOf(mesh.Types[c]);
    if (kind < 0)
    {
      ++skipped;
      continue;
    }
    if (end - begin != kShapes[kind].Points)
    {
      error = "cell " + std::to_string(c) + " (VTK type " + std::to_string(mesh.Types[c]) +
              ") has " + std::to_string(end - begin) + " points instead of " +
              std::to_string(kShapes[kind].Points);
      return nullptr;
    }
    bool finite = true;
    for (std::int64_t k = begin; k < end; ++k)
    {
      const std::int64_t id = mesh.Connectivity[k];
      if (id < 0 || id >= points)
      {
        error = "cell " + std::to_string(c) + " refers to point " + std::to_string(id) +
                ", outside [0, " + std::to_string(points) + ")";
        return nullptr;
      }
      const double* x = mesh.Points + 3 * id;
      finite = finite && std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
    }
    if (!finite)
    {
      ++skipped;
      continue;
    }
    kept.push_back(c);
  }
  if (skippedCells)
  {
    *skippedCells = skipped;
  }
  if (kept.empty())
  {
    error = "the mesh has no supported cells (tetrahedra, hexahedra, voxels, wedges or pyramids "
            "with finite points); " +
            std::to_string(skipped) + " cells skipped";
    return nullptr;
  }
  if (kept.size() > kMaxCells)
  {
    error = "the mesh has too many cells (at most " + std::to_string(kMaxCells) + ")";
    return nullptr;
  }
  try
  {
    return std::make_shared<unstructured::UnstructuredSampler>(mesh, kept);
  }
  catch (const std::bad_alloc&)
  {
    error = "not enough memory for the mesh's faces and index";
    return nullptr;
  }
}

} // namespace savr

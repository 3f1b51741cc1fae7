#include "mesh/MeshFaces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>

namespace savr
{
namespace unstructured
{
namespace
{

// Cells whose volume is below this fraction of their bounding box's largest edge cubed are
// degenerate: rays never walk through them (they look for the next cell instead).
constexpr double kDegenerateVolume = 1e-10;

// 21 bits of each coordinate interleaved.
std::uint64_t Morton(const std::uint32_t q[3])
{
  std::uint64_t code = 0;
  for (int b = 20; b >= 0; --b)
  {
    for (int a = 0; a < 3; ++a)
    {
      code = (code << 1) | ((q[a] >> b) & 1u);
    }
  }
  return code;
}

} // namespace

CellOrder OrderCells(const UnstructuredDescription& mesh, const std::vector<std::size_t>& kept)
{
  const std::size_t cells = kept.size();
  std::vector<double> centres(3 * cells);
  CellOrder result;
  double* lo = result.Lo;
  double* hi = result.Hi;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = kInfinity;
    hi[a] = -kInfinity;
  }
  for (std::size_t c = 0; c < cells; ++c)
  {
    const std::int64_t* ids = mesh.Connectivity + mesh.Offsets[kept[c]];
    const int n = kShapes[KindOf(mesh.Types[kept[c]])].Points;
    double sum[3] = { 0.0, 0.0, 0.0 };
    for (int k = 0; k < n; ++k)
    {
      const double* x = mesh.Points + 3 * ids[k];
      for (int a = 0; a < 3; ++a)
      {
        sum[a] += x[a];
        lo[a] = std::min(lo[a], x[a]);
        hi[a] = std::max(hi[a], x[a]);
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      centres[3 * c + a] = sum[a] / n;
    }
  }

  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(cells);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c < range.end(); ++c)
      {
        std::uint32_t q[3];
        for (int a = 0; a < 3; ++a)
        {
          const double extent = hi[a] - lo[a];
          const double u = extent > 0.0 ? (centres[3 * c + a] - lo[a]) / extent : 0.0;
          q[a] = static_cast<std::uint32_t>(std::min(std::max(u, 0.0), 1.0) * 2097151.0);
        }
        order[c] = { Morton(q), static_cast<std::uint32_t>(c) };
      }
    });
  tbb::parallel_sort(order.begin(), order.end());
  result.Cells.resize(cells);
  for (std::size_t c = 0; c < cells; ++c)
  {
    result.Cells[c] = kept[order[c].second];
  }
  return result;
}

MeshFaces::MeshFaces(
  const UnstructuredDescription& mesh, const std::vector<std::size_t>& cells, double tolerance)
  : NumberOfCells(static_cast<std::uint32_t>(cells.size()))
  , Tolerance(tolerance)
{
  this->Points.assign(mesh.Points, mesh.Points + 3 * mesh.NumberOfPoints);
  this->Kinds.resize(cells.size());
  this->CellPoints.assign(8 * cells.size(), kNone);
  for (std::size_t c = 0; c < cells.size(); ++c)
  {
    const int kind = KindOf(mesh.Types[cells[c]]);
    this->Kinds[c] = static_cast<CellKind>(kind);
    const std::int64_t* ids = mesh.Connectivity + mesh.Offsets[cells[c]];
    for (int k = 0; k < kShapes[kind].Points; ++k)
    {
      this->CellPoints[8 * c + k] = static_cast<std::uint32_t>(ids[k]);
    }
  }
  this->FindDegenerateCells();
  this->BuildFaces();
  this->FindNonConvexCells();
}

// A cell is degenerate when its volume (tetrahedra from its centre to its faces' triangles,
// each counted positive) is negligible beside its size.
void MeshFaces::FindDegenerateCells()
{
  this->Flags.assign(this->NumberOfCells, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->NumberOfCells, 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c < range.end(); ++c)
      {
        const auto cell = static_cast<std::uint32_t>(c);
        const CellShape& shape = ShapeOf(this->Kinds[cell]);
        const Eigen::Vector3d centre = this->Centre(cell);
        Eigen::Vector3d x[8];
        for (int k = 0; k < shape.Points; ++k)
        {
          x[k] = this->Point(this->CellPoints[8 * c + k]);
        }
        Eigen::Vector3d lo = centre;
        Eigen::Vector3d hi = centre;
        double volume = 0.0;
        for (int f = 0; f < shape.Faces; ++f)
        {
          const int* face = shape.Face[f];
          const Eigen::Vector3d a = x[face[0]] - centre;
          for (int k = 1; k + 1 < shape.FaceSize[f]; ++k)
          {
            const Eigen::Vector3d b = x[face[k]] - centre;
            const Eigen::Vector3d d = x[face[k + 1]] - centre;
            volume += std::abs(a.dot(b.cross(d))) / 6.0;
          }
        }
        for (int k = 0; k < shape.Points; ++k)
        {
          lo = lo.cwiseMin(x[k]);
          hi = hi.cwiseMax(x[k]);
        }
        const double size = (hi - lo).maxCoeff();
        this->Flags[c] = volume > kDegenerateVolume * size * size * size ? 0 : kDegenerate;
        this->Flags[c] |= HasDirectMap(this->Kinds[cell], x, 1e-10 * size) ? kDirect : 0;
      }
    });
}

// Pairs the cells' faces by their sorted vertex ids, computes each face's planes once, and
// gives each cell its sides. Two cells pair up only from opposite sides of a face: overlapping
// (duplicated, tangled) cells stay unpaired, and rays crossing such faces ask the index for the
// next cell. Degenerate cells get no sides: rays never walk into them.
void MeshFaces::BuildFaces()
{
  const std::vector<FaceEntry> entries = this->ListFaces();
  const FacePairs pairs = PairFaces(entries);
  this->Sides.resize(this->SideBegin[this->NumberOfCells]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t k = range.begin(); k < range.end(); ++k)
      {
        const FaceEntry& owner = entries[pairs[k].first];
        if (pairs[k].second == kNone)
        {
          this->AddFace(owner.Cell, owner.Local, owner.Face, owner.Offset, -1, 0, kNoFace, 0);
          continue;
        }
        const FaceEntry& other = entries[pairs[k].second];
        this->AddFace(owner.Cell, owner.Local, owner.Face, owner.Offset,
          static_cast<std::int32_t>(other.Cell), other.Local, other.Face, other.Offset);
      }
    });
}

// The faces of the cells that are not degenerate, sorted by their vertex ids (so that the cells
// of a face are neighbours in the list), and where each cell's sides begin.
std::vector<MeshFaces::FaceEntry> MeshFaces::ListFaces()
{
  const std::size_t cells = this->NumberOfCells;
  // Faces collapsed by repeated points to fewer than 3 distinct vertices are dropped.
  std::vector<std::uint32_t> faces(cells + 1, 0);
  this->SideBegin.assign(cells + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c < range.end(); ++c)
      {
        const auto cell = static_cast<std::uint32_t>(c);
        if (this->IsDegenerate(cell))
        {
          continue;
        }
        const CellShape& shape = ShapeOf(this->Kinds[c]);
        for (int f = 0; f < shape.Faces; ++f)
        {
          std::uint32_t v[4] = { 0, 0, 0, 0 };
          const int n = this->FaceVertices(cell, f, v);
          faces[c + 1] += n >= 3 ? 1 : 0;
          this->SideBegin[c + 1] += n == 4 ? 2 : (n == 3 ? 1 : 0);
        }
      }
    });
  for (std::size_t c = 0; c < cells; ++c)
  {
    faces[c + 1] += faces[c];
    this->SideBegin[c + 1] += this->SideBegin[c];
  }
  std::vector<FaceEntry> entries(faces[cells]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c < range.end(); ++c)
      {
        if (faces[c + 1] == faces[c])
        {
          continue;
        }
        const auto cell = static_cast<std::uint32_t>(c);
        const CellShape& shape = ShapeOf(this->Kinds[c]);
        const Eigen::Vector3d centre = this->Centre(cell);
        std::uint32_t face = 0;
        int offset = 0;
        for (int f = 0; f < shape.Faces; ++f)
        {
          FaceEntry& e = entries[faces[c] + face];
          const int n = this->FaceVertices(cell, f, e.Key);
          if (n < 3)
          {
            continue;
          }
          // The face's normal for its vertices in a cyclic order that every cell with the face
          // agrees on: from the smallest id, towards the smaller of its two neighbours.
          int m = 0;
          for (int k = 1; k < n; ++k)
          {
            m = e.Key[k] < e.Key[m] ? k : m;
          }
          const int step = e.Key[(m + 1) % n] < e.Key[(m + n - 1) % n] ? 1 : n - 1;
          Eigen::Vector3d q[4];
          Eigen::Vector3d middle = Eigen::Vector3d::Zero();
          for (int k = 0; k < n; ++k)
          {
            q[k] = this->Point(e.Key[(m + k * step) % n]);
            middle += q[k] / n;
          }
          const Eigen::Vector3d normal =
            n == 3 ? (q[1] - q[0]).cross(q[2] - q[0]) : (q[2] - q[0]).cross(q[3] - q[1]);
          e.Above = normal.dot(centre - middle) > 0.0;
          if (n == 3)
          {
            e.Key[3] = kNone;
          }
          std::sort(e.Key, e.Key + n);
          e.Cell = cell;
          e.Local = static_cast<std::uint8_t>(f);
          e.Face = static_cast<std::uint8_t>(face++);
          e.Offset = static_cast<std::uint8_t>(offset);
          offset += n == 4 ? 2 : 1;
        }
      }
    });
  tbb::parallel_sort(entries.begin(), entries.end(),
    [](const FaceEntry& a, const FaceEntry& b)
    {
      for (int k = 0; k < 4; ++k)
      {
        if (a.Key[k] != b.Key[k])
        {
          return a.Key[k] < b.Key[k];
        }
      }
      return a.Cell != b.Cell ? a.Cell < b.Cell : a.Local < b.Local;
    });
  return entries;
}

// Faces as pairs of sorted entries, the second kNone on the boundary.
MeshFaces::FacePairs MeshFaces::PairFaces(const std::vector<FaceEntry>& entries)
{
  FacePairs pairs;
  pairs.reserve(entries.size() / 2 + 16);
  std::vector<std::uint8_t> paired;
  for (std::size_t g = 0; g < entries.size();)
  {
    std::size_t end = g + 1;
    while (end < entries.size() && std::equal(entries[g].Key, entries[g].Key + 4, entries[end].Key))
    {
      ++end;
    }
    const auto first = static_cast<std::uint32_t>(g);
    if (end - g == 1)
    {
      pairs.emplace_back(first, kNone);
    }
    else if (end - g == 2 && entries[g].Above != entries[g + 1].Above)
    {
      pairs.emplace_back(first, first + 1); // the usual case: two cells, one on each side
    }
    else
    {
      // Pairs of cells from opposite sides, in order; the others alone.
      paired.assign(end - g, 0);
      std::size_t above = g;
      std::size_t below = g;
      for (;;)
      {
        while (above < end && !entries[above].Above)
        {
          ++above;
        }
        while (below < end && entries[below].Above)
        {
          ++below;
        }
        if (above == end || below == end)
        {
          break;
        }
        pairs.emplace_back(static_cast<std::uint32_t>(std::min(above, below)),
          static_cast<std::uint32_t>(std::max(above, below)));
        paired[above - g] = paired[below - g] = 1;
        ++above;
        ++below;
      }
      for (std::size_t k = g; k < end; ++k)
      {
        if (!paired[k - g])
        {
          pairs.emplace_back(static_cast<std::uint32_t>(k), kNone);
        }
      }
    }
    g = end;
  }
  return pairs;
}

// Computes the planes of face `local` of `cell` (the cell's face number `face`, its sides from
// `offset` on) once, pointing away from the cell's centre (towards the neighbour's when the
// cell's centre is too close to the face to tell), and gives them to both cells.
void MeshFaces::AddFace(std::uint32_t cell, int local, std::uint8_t face, int offset,
  std::int32_t neighbour, int neighbourLocal, std::uint8_t neighbourFace, int neighbourOffset)
{
  std::uint32_t v[4] = { 0, 0, 0, 0 };
  const int n = this->FaceVertices(cell, local, v);
  const int triangles = n == 4 ? 2 : 1;
  Eigen::Vector3d normals[2];
  Eigen::Vector3d anchors[2];
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (int k = 0; k < triangles; ++k)
  {
    Eigen::Vector3d t[3];
    this->Triangle(cell, local, k, t);
    normals[k] = (t[1] - t[0]).cross(t[2] - t[0]);
    anchors[k] = t[0];
    total += normals[k];
  }
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k)
  {
    middle += this->Point(v[k]) / n;
  }
  double side = total.dot(this->Centre(cell) - middle);
  if (!(std::abs(side) > 1e-9 * total.norm() * this->CellSize(cell)) && neighbour >= 0)
  {
    side = -total.dot(this->Centre(static_cast<std::uint32_t>(neighbour)) - middle);
  }
  const double orientation = side > 0.0 ? -1.0 : 1.0;
  for (int k = 0; k < triangles; ++k)
  {
    Side& mine = this->Sides[this->SideBegin[cell] + offset + k];
    const double length = normals[k].norm();
    if (length > 0.0 && std::isfinite(length))
    {
      const Eigen::Vector3d unit = (orientation / length) * normals[k];
      for (int a = 0; a < 3; ++a)
      {
        mine.N[a] = unit[a];
      }
      mine.D = unit.dot(anchors[k]);
    }
    else
    {
      mine.N[0] = mine.N[1] = mine.N[2] = mine.D = 0.0;
    }
    mine.Neighbour = neighbour;
    mine.NeighbourFace = neighbourFace;
    mine.Face = face;
    mine.Local = static_cast<std::uint8_t>(local);
    mine.Triangle = static_cast<std::uint8_t>(k);
    if (neighbour >= 0)
    {
      Side& theirs = this->Sides[this->SideBegin[neighbour] + neighbourOffset + k];
      for (int a = 0; a < 3; ++a)
      {
        theirs.N[a] = -mine.N[a];
      }
      theirs.D = -mine.D;
      theirs.Neighbour = static_cast<std::int32_t>(cell);
      theirs.NeighbourFace = face;
      theirs.Face = neighbourFace;
      theirs.Local = static_cast<std::uint8_t>(neighbourLocal);
      theirs.Triangle = static_cast<std::uint8_t>(k);
    }
  }
}

// Cells whose faces are not all planar may be non-convex: some vertex lies outside the plane
// of one of the cell's triangles. The walk tests such cells' triangles themselves.
void MeshFaces::FindNonConvexCells()
{
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->NumberOfCells, 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t c = range.begin(); c < range.end(); ++c)
      {
        const auto cell = static_cast<std::uint32_t>(c);
        const int n = ShapeOf(this->Kinds[cell]).Points;
        const double tolerance = 1e-9 * this->CellSize(cell);
        bool convex = true;
        for (std::uint32_t k = this->SideBegin[c]; k < this->SideBegin[c + 1] && convex; ++k)
        {
          const Side& side = this->Sides[k];
          for (int i = 0; i < n; ++i)
          {
            const double* x = this->Points.data() + 3 * this->CellPoints[8 * c + i];
            if (Dot(side.N, x) - side.D > tolerance)
            {
              convex = false;
              break;
            }
          }
        }
        if (!convex)
        {
          this->Flags[c] |= kNonConvex;
        }
      }
    });
}

} // namespace unstructured
} // namespace savr

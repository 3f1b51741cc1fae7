#pragma once
// The cells of an unstructured mesh and their faces: which cells share a face, each face's
// planes, which cells are degenerate or non-convex, and where a line enters and leaves a cell.
// The per-cell queries are inline: the walk asks them at every step from cell to cell.

#include "mesh/CellShapes.h"
#include "mesh/MeshLine.h"
#include "mesh/UnstructuredDescription.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace savr
{
namespace unstructured
{

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr std::uint8_t kNoFace = 0xff;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// A side with no cell across.
constexpr std::int32_t kOpenSide = -1;
// A side with no cell across whose plane has every point of the mesh's cells behind it (within
// the mesh's tolerance): a line that leaves the mesh by it meets no cell after it, and a line
// that enters by it met none before.
constexpr std::int32_t kHullSide = -2;

// One triangle of a cell's faces (a quad face has two), as the cell sees it: the plane
// n . x = d with n of unit length pointing out of the cell (zero for a degenerate triangle), and
// the cell across it. A face's planes are computed once, and its second cell holds their exact
// negations: the parameter where a ray leaves one cell is the one where it enters the next.
struct Side
{
  double N[3];
  double D;
  std::int32_t Neighbour;     // the cell across, or kOpenSide or kHullSide for none
  std::uint8_t NeighbourFace; // the face of the neighbour that this face is
  std::uint8_t Face;          // the cell's face this triangle belongs to (its faces in order)
  std::uint8_t Local;         // that face in the kind's table
  std::uint8_t Triangle;      // 0 or 1
};

// The description's cells to use, in an order along a Morton curve of their centres (neighbours
// in space are neighbours in memory), and the bounds of their points.
struct CellOrder
{
  std::vector<std::size_t> Cells;
  double Lo[3];
  double Hi[3];
};

CellOrder OrderCells(const UnstructuredDescription& mesh, const std::vector<std::size_t>& kept);

class MeshFaces
{
public:
  // `cells` lists the description's cells in the order to keep them. Points within `tolerance`
  // of a cell count as inside it.
  MeshFaces(
    const UnstructuredDescription& mesh, const std::vector<std::size_t>& cells, double tolerance);

  std::uint32_t CellCount() const { return this->NumberOfCells; }
  std::size_t PointCount() const { return this->Points.size() / 3; }
  CellKind Kind(std::uint32_t cell) const { return this->Kinds[cell]; }
  // 8 per cell, kNone past the cell's points.
  const std::vector<std::uint32_t>& AllCellPoints() const { return this->CellPoints; }
  const std::uint32_t* PointIds(std::uint32_t cell) const
  {
    return this->CellPoints.data() + 8 * static_cast<std::size_t>(cell);
  }

  Eigen::Vector3d Point(std::uint32_t id) const
  {
    const double* x = this->Points.data() + 3 * static_cast<std::size_t>(id);
    return Eigen::Vector3d(x[0], x[1], x[2]);
  }

  Eigen::Vector3d Centre(std::uint32_t cell) const
  {
    const int n = ShapeOf(this->Kinds[cell]).Points;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
    {
      sum += this->Point(this->CellPoints[8 * static_cast<std::size_t>(cell) + k]);
    }
    return sum / n;
  }

  // The cell's bounding box.
  void Bounds(std::uint32_t cell, Eigen::Vector3d& lo, Eigen::Vector3d& hi) const
  {
    const int n = ShapeOf(this->Kinds[cell]).Points;
    lo = this->Point(this->CellPoints[8 * static_cast<std::size_t>(cell)]);
    hi = lo;
    for (int k = 1; k < n; ++k)
    {
      const Eigen::Vector3d x =
        this->Point(this->CellPoints[8 * static_cast<std::size_t>(cell) + k]);
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
  }

  // Largest edge of the cell's bounding box.
  double CellSize(std::uint32_t cell) const
  {
    Eigen::Vector3d lo;
    Eigen::Vector3d hi;
    this->Bounds(cell, lo, hi);
    return (hi - lo).maxCoeff();
  }

  // The cell's vertices with `pointValues` at them (zeros without).
  CellVertices Vertices(std::uint32_t cell, const float* pointValues) const
  {
    CellVertices data;
    data.Kind = this->Kinds[cell];
    data.Points = ShapeOf(data.Kind).Points;
    data.Direct = (this->Flags[cell] & kDirect) != 0;
    const std::uint32_t* ids = this->PointIds(cell);
    for (int k = 0; k < data.Points; ++k)
    {
      data.X[k] = this->Point(ids[k]);
      data.F[k] = pointValues ? static_cast<double>(pointValues[ids[k]]) : 0.0;
    }
    return data;
  }

  bool IsDegenerate(std::uint32_t cell) const { return (this->Flags[cell] & kDegenerate) != 0; }
  // Whether a line from outside the mesh can enter the cell first: some side of it has no cell
  // across, or a degenerate one (which rays never walk into).
  bool OnBoundary(std::uint32_t cell) const
  {
    for (std::uint32_t k = this->SideBegin[cell]; k < this->SideBegin[cell + 1]; ++k)
    {
      const std::int32_t across = this->Sides[k].Neighbour;
      if (across < 0 || this->IsDegenerate(static_cast<std::uint32_t>(across)))
      {
        return true;
      }
    }
    return false;
  }
  // Whether the cell's parametric coordinates have a closed form (CellVertices::Direct).
  bool IsDirect(std::uint32_t cell) const { return (this->Flags[cell] & kDirect) != 0; }
  bool IsNonConvex(std::uint32_t cell) const { return (this->Flags[cell] & kNonConvex) != 0; }

  const Side& SideAt(std::uint32_t k) const { return this->Sides[k]; }
  std::size_t SideCount() const { return this->Sides.size(); }
  // Marks side k, which has no cell across, as on the mesh's convex hull (see kHullSide).
  void SetHullSide(std::uint32_t k) { this->Sides[k].Neighbour = kHullSide; }
  // Where the cell's sides start, to fetch them ahead of the walk.
  const Side* FirstSide(std::uint32_t cell) const
  {
    return this->Sides.data() + this->SideBegin[cell];
  }

  // The parameter where the line leaves `cell` through the first of its faces other than
  // `skip` (the face it came in by), and the side it leaves by (kNone when no side faces
  // forward). Convex cells: the nearest plane the line leaves by. Non-convex cells: the nearest
  // triangle the line leaves by, after tIn.
  double Exit(std::uint32_t cell, const Line& line, std::uint8_t skip, double tIn,
    std::uint32_t& exitSide) const
  {
    const std::uint32_t begin = this->SideBegin[cell];
    const std::uint32_t end = this->SideBegin[cell + 1];
    if (this->IsNonConvex(cell))
    {
      // The sides' forward crossings from tIn on, nearest first (ties in the sides' order):
      // the first whose triangle the line hits is the exit, usually the first one tried.
      double ts[kMostSides];
      std::uint32_t ks[kMostSides];
      int n = 0;
      for (std::uint32_t k = begin; k < end; ++k)
      {
        const Side& side = this->Sides[k];
        const double denominator = Dot(side.N, line.D);
        if (denominator > 0.0 && side.Face != skip)
        {
          const double t = Crossing(side, line, denominator);
          if (t >= tIn - this->Tolerance && t < kInfinity)
          {
            int at = n++;
            for (; at > 0 && ts[at - 1] > t; --at)
            {
              ts[at] = ts[at - 1];
              ks[at] = ks[at - 1];
            }
            ts[at] = t;
            ks[at] = k;
          }
        }
      }
      for (int i = 0; i < n; ++i)
      {
        if (this->Hits(cell, this->Sides[ks[i]], line, ts[i]))
        {
          exitSide = ks[i];
          return ts[i];
        }
      }
    }
    // Convex cells, and non-convex ones whose triangles the line misses: the nearest plane.
    double best = kInfinity;
    exitSide = kNone;
    for (std::uint32_t k = begin; k < end; ++k)
    {
      const Side& side = this->Sides[k];
      const double denominator = Dot(side.N, line.D);
      if (denominator > 0.0 && side.Face != skip)
      {
        const double t = Crossing(side, line, denominator);
        if (t < best)
        {
          best = t;
          exitSide = k;
        }
      }
    }
    return exitSide != kNone ? best : kInfinity;
  }

  // The interval [a, b] of the line inside `cell` that holds tMin or comes first after it;
  // false when there is none. Convex cells: the intersection of the sides' half-spaces.
  // Non-convex cells: the first triangle the line leaves by after tMin (strictly after, with
  // `strict`) and the last it enters by before that.
  bool Interval(
    std::uint32_t cell, const Line& line, double tMin, bool strict, double& a, double& b) const
  {
    if (this->IsNonConvex(cell) && this->TriangleInterval(cell, line, tMin, strict, a, b))
    {
      return true;
    }
    std::uint32_t entry;
    return this->HalfSpaces(cell, line, a, b, entry) &&
           this->SideBegin[cell] < this->SideBegin[cell + 1] && a <= b;
  }

  // The interval [a, b] of the line inside the intersection of the cell's sides' half-spaces,
  // and the side whose plane gives a (kNone when no side faces the line); false when the line
  // runs parallel to a side outside it.
  bool HalfSpaces(
    std::uint32_t cell, const Line& line, double& a, double& b, std::uint32_t& entry) const
  {
    a = -kInfinity;
    b = kInfinity;
    entry = kNone;
    for (std::uint32_t k = this->SideBegin[cell]; k < this->SideBegin[cell + 1]; ++k)
    {
      const Side& side = this->Sides[k];
      const double denominator = Dot(side.N, line.D);
      if (denominator == 0.0)
      {
        if (Dot(side.N, line.O) - side.D > 0.0)
        {
          return false;
        }
        continue;
      }
      const double t = Crossing(side, line, denominator);
      if (denominator > 0.0)
      {
        b = std::min(b, t);
      }
      else if (t > a)
      {
        a = t;
        entry = k;
      }
    }
    return true;
  }

  // Whether the line, from outside the mesh at tMin, enters it first by the convex `cell`, and
  // where: through a hull side, after tMin, well inside that side's triangle (not near its edges,
  // where another cell could tie). The parameter is Interval's, so the walk from here is the one
  // from the cell the hierarchy finds.
  bool EntersByHull(std::uint32_t cell, const Line& line, double tMin, double& tIn) const
  {
    if (this->Flags[cell] & (kNonConvex | kDegenerate))
    {
      return false;
    }
    double a;
    double b;
    std::uint32_t entry;
    if (!this->HalfSpaces(cell, line, a, b, entry) || entry == kNone || !(a < b) || !(a > tMin) ||
        this->Sides[entry].Neighbour != kHullSide)
    {
      return false;
    }
    tIn = a;
    return this->Inside(cell, this->Sides[entry], line, a, 1e-6);
  }

  // Whether p lies in the cell: inside its sides' half-spaces, or, for a non-convex cell and
  // with `exact`, at parametric coordinates inside its domain.
  bool Contains(std::uint32_t cell, const Eigen::Vector3d& p, bool exact) const
  {
    const double x[3] = { p[0], p[1], p[2] };
    bool inside = this->SideBegin[cell] < this->SideBegin[cell + 1];
    for (std::uint32_t k = this->SideBegin[cell]; k < this->SideBegin[cell + 1]; ++k)
    {
      const Side& side = this->Sides[k];
      if (Dot(side.N, x) - side.D > this->Tolerance)
      {
        inside = false;
        break;
      }
    }
    if (inside || !exact || !this->IsNonConvex(cell))
    {
      return inside;
    }
    const CellVertices data = this->Vertices(cell, nullptr);
    const Polynomial polynomial(data);
    double r[3];
    Parametric(data, polynomial, p, r);
    ClampToCell(data.Kind, r, 1e-6);
    Eigen::Vector3d mapped;
    Eigen::Matrix3d jacobian;
    polynomial.Map(r, mapped, jacobian);
    return (mapped - p).norm() <= this->Tolerance + 1e-6 * this->CellSize(cell);
  }

private:
  // Per-cell flags. Non-convex: some vertex lies outside one of its faces' triangles. Direct:
  // parametric coordinates have a closed form (see DirectMap).
  static constexpr std::uint8_t kDegenerate = 1;
  static constexpr std::uint8_t kNonConvex = 2;
  static constexpr std::uint8_t kDirect = 4;
  // Sides of the cell with the most: a kind has at most six faces (CellShape), each at most
  // two triangles.
  static constexpr std::uint32_t kMostSides = 12;

  // What BuildFaces knows of one face of one cell.
  struct FaceEntry
  {
    std::uint32_t Key[4]; // its distinct vertex ids, sorted (kNone for a triangle's fourth)
    std::uint32_t Cell;
    std::uint8_t Local;  // the face in the kind's table
    std::uint8_t Face;   // its place among the cell's faces
    std::uint8_t Offset; // its first side among the cell's sides
    std::uint8_t Above;  // the cell's centre on the positive side of the face
  };
  using FacePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

  void FindDegenerateCells();
  void BuildFaces();
  std::vector<FaceEntry> ListFaces();
  static FacePairs PairFaces(const std::vector<FaceEntry>& entries);
  void AddFace(std::uint32_t cell, int local, std::uint8_t face, int offset, std::int32_t neighbour,
    int neighbourLocal, std::uint8_t neighbourFace, int neighbourOffset);
  void FindNonConvexCells();

  // The distinct vertices of face `local` of `cell` in cyclic order; how many (3 or 4, or fewer
  // for a face collapsed by repeated points).
  int FaceVertices(std::uint32_t cell, int local, std::uint32_t v[4]) const
  {
    const CellShape& shape = ShapeOf(this->Kinds[cell]);
    const std::uint32_t* ids = this->PointIds(cell);
    int n = 0;
    for (int k = 0; k < shape.FaceSize[local]; ++k)
    {
      const std::uint32_t id = ids[shape.Face[local][k]];
      if (std::find(v, v + n, id) == v + n)
      {
        v[n++] = id;
      }
    }
    return n;
  }

  // Vertices of triangle k of face `local` of `cell`. A quad is cut along the diagonal from its
  // smallest vertex id, and its triangles are numbered by their third vertex, the smaller id
  // first: both cells of a face see the same triangles, in the same order.
  void Triangle(std::uint32_t cell, int local, int k, Eigen::Vector3d triangle[3]) const
  {
    std::uint32_t v[4] = { 0, 0, 0, 0 };
    const int n = this->FaceVertices(cell, local, v);
    int m = 0;
    for (int i = 1; i < n; ++i)
    {
      m = v[i] < v[m] ? i : m;
    }
    triangle[0] = this->Point(v[m]);
    if (n == 3)
    {
      triangle[1] = this->Point(v[(m + 1) % 3]);
      triangle[2] = this->Point(v[(m + 2) % 3]);
      return;
    }
    // (m, m + 1, m + 2) or (m, m + 2, m + 3): both wound as the quad.
    const bool next = (k == 0) == (v[(m + 1) % 4] < v[(m + 3) % 4]);
    triangle[1] = this->Point(v[(m + (next ? 1 : 2)) % 4]);
    triangle[2] = this->Point(v[(m + (next ? 2 : 3)) % 4]);
  }

  // Where the line crosses a side's plane. Its neighbour's side holds the exact negations of
  // its numbers, so the parameter where a ray leaves a cell is the one where it enters the next.
  static double Crossing(const Side& side, const Line& line, double denominator)
  {
    return (side.D - Dot(side.N, line.O)) / denominator;
  }

  // Whether the line's crossing at t of the plane of a side of `cell` lies in its triangle (grown
  // by a hair, so that a line through an edge hits one of its triangles).
  bool Hits(std::uint32_t cell, const Side& side, const Line& line, double t) const
  {
    return this->Inside(cell, side, line, t, -1e-7);
  }

  // Whether the line's crossing at t lies in the side's triangle shrunk by `margin` (grown by
  // -margin), in barycentric coordinates.
  bool Inside(std::uint32_t cell, const Side& side, const Line& line, double t, double margin) const
  {
    Eigen::Vector3d v[3];
    this->Triangle(cell, side.Local, side.Triangle, v);
    const Eigen::Vector3d p(
      line.O[0] + t * line.D[0], line.O[1] + t * line.D[1], line.O[2] + t * line.D[2]);
    const Eigen::Vector3d e0 = v[1] - v[0];
    const Eigen::Vector3d e1 = v[2] - v[0];
    const Eigen::Vector3d n = e0.cross(e1);
    const double area = n.squaredNorm();
    if (!(area > 0.0))
    {
      return false;
    }
    const Eigen::Vector3d q = p - v[0];
    const double u = n.dot(q.cross(e1)) / area;
    const double w = n.dot(e0.cross(q)) / area;
    return u >= margin && w >= margin && u + w <= 1.0 - margin;
  }

  // Interval's answer for a non-convex cell from its triangles: the first the line leaves by
  // after tMin and the last it enters by before that; false when the line hits none (the
  // half-spaces decide then).
  bool TriangleInterval(
    std::uint32_t cell, const Line& line, double tMin, bool strict, double& a, double& b) const
  {
    const std::uint32_t begin = this->SideBegin[cell];
    const std::uint32_t end = this->SideBegin[cell + 1];
    a = -kInfinity;
    b = kInfinity;
    for (int pass = 0; pass < 2; ++pass) // leaving, then entering
    {
      for (std::uint32_t k = begin; k < end; ++k)
      {
        const Side& side = this->Sides[k];
        const double denominator = Dot(side.N, line.D);
        if (denominator == 0.0)
        {
          continue;
        }
        const double t = Crossing(side, line, denominator);
        if (pass == 0 && denominator > 0.0 && (strict ? t > tMin : t >= tMin) && t < b &&
            this->Hits(cell, side, line, t))
        {
          b = t;
        }
        else if (pass == 1 && denominator < 0.0 && t <= b && t > a &&
                 this->Hits(cell, side, line, t))
        {
          a = t;
        }
      }
      if (b == kInfinity)
      {
        break;
      }
    }
    return b < kInfinity;
  }

  std::uint32_t NumberOfCells = 0;
  double Tolerance = 0.0;
  std::vector<double> Points;            // 3 per point
  std::vector<CellKind> Kinds;           // per cell
  std::vector<std::uint32_t> CellPoints; // 8 per cell, kNone past the cell's points
  std::vector<std::uint32_t> SideBegin;  // per cell and one: its first side
  std::vector<Side> Sides;               // per cell, in order
  std::vector<std::uint8_t> Flags;       // per cell: kDegenerate, kNonConvex, kDirect
};

} // namespace unstructured
} // namespace savr

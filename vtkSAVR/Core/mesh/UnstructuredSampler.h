#pragma once
// The unstructured sampler's class, private to the engine: the walk of a ray from cell to cell
// across shared faces, the samples it reads on the way and the paths it records for later frames.
// The walk is defined in UnstructuredWalk.h (which includes this), its setup
// (UnstructuredSampler.cxx) and gradients (UnstructuredGradients.cxx) apart; the cells' shapes, the mesh's faces and the cell hierarchy that finds where a walk
// starts are rooms of their own (CellShapes.h, MeshFaces.h, CellHierarchy.h).

#include "mesh/UnstructuredDescription.h"

#include "mesh/CellHierarchy.h"
#include "mesh/CellShapes.h"
#include "mesh/MeshFaces.h"
#include "mesh/PathPieces.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

namespace savr
{
namespace unstructured
{

// Cells and their sides (triangles of their faces, at most 12 per cell) are indexed by 32-bit
// integers.
constexpr std::size_t kMaxCells = 0xfffffffeu / 12;
// Samples this close (a fraction of the mesh's diagonal) outside the mesh still read the nearest
// cell: entry and exit points are computed with round-off and must not read as NaN.
constexpr double kBoundaryTolerance = 1e-7;
// Zero-length steps in a row (a ray through an edge or a vertex) before the walk gives up on
// adjacency and asks the spatial index for the next cell.
constexpr int kMaxStall = 64;

// Asks for the cache lines from p on.
inline void Prefetch(const void* p, int lines)
{
#if defined(__GNUC__) || defined(__clang__)
  for (int k = 0; k < lines; ++k)
  {
    __builtin_prefetch(static_cast<const char*>(p) + 64 * k);
  }
#else
  (void)p;
  (void)lines;
#endif
}

inline double Diagonal(const CellOrder& order)
{
  double sum = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    sum += (order.Hi[a] - order.Lo[a]) * (order.Hi[a] - order.Lo[a]);
  }
  return std::sqrt(sum);
}

class UnstructuredSampler final : public Sampler
{
public:
  // `kept` lists the description's cells to use (supported, valid).
  UnstructuredSampler(const UnstructuredDescription& mesh, const std::vector<std::size_t>& kept)
    : UnstructuredSampler(mesh, OrderCells(mesh, kept))
  {
  }

  UnstructuredSampler(const UnstructuredDescription& mesh, const CellOrder& order)
    : CellValues(mesh.CellData)
    , Tolerance(kBoundaryTolerance * Diagonal(order))
    , Faces(mesh, order.Cells, this->Tolerance)
    , Hierarchy(this->Faces.CellCount(), this->Tolerance,
        [this](std::uint32_t cell, Eigen::Vector3d& lo, Eigen::Vector3d& hi)
        {
          // Degenerate cells are left out: rays never walk into them.
          if (this->Faces.IsDegenerate(cell))
          {
            return false;
          }
          this->Faces.Bounds(cell, lo, hi);
          return true;
        })
    // A line from outside the mesh enters it first by one of the cells on its boundary: a
    // hierarchy of those alone finds a ray's first cell in a fraction of the time.
    , Boundary(this->Faces.CellCount(), this->Tolerance,
        [this](std::uint32_t cell, Eigen::Vector3d& lo, Eigen::Vector3d& hi)
        {
          if (this->Faces.IsDegenerate(cell) || !this->Faces.OnBoundary(cell))
          {
            return false;
          }
          this->Faces.Bounds(cell, lo, hi);
          return true;
        })
  {
    for (int a = 0; a < 3; ++a)
    {
      // Clip's box: grown well beyond the tolerance so that no sample that may read a cell is
      // clipped away.
      this->ClipLo[a] = order.Lo[a] - 10.0 * this->Tolerance;
      this->ClipHi[a] = order.Hi[a] + 10.0 * this->Tolerance;
    }
    if (this->CellValues)
    {
      this->Values.resize(order.Cells.size());
      for (std::size_t c = 0; c < order.Cells.size(); ++c)
      {
        this->Values[c] = mesh.Values[order.Cells[c]];
      }
    }
    else
    {
      this->Values.assign(mesh.Values, mesh.Values + mesh.NumberOfPoints);
    }
    this->ScanValues();
    this->BuildTetraLines(order);
    this->BuildCellMaps();
    this->FindHullSides();
  }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    const Line line(ray.Origin, ray.Direction);
    return this->ClipLine(line, tEnter, tExit) && tEnter < tExit;
  }

  std::array<double, 2> ValueRange() const override { return this->Range; }
  int ExactBits() const override { return 0; }
  // Rays may pass through holes, concavities and gaps between cells.
  bool MayReturnNaN() const override { return true; }

  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip) const override
  {
    (void)skip; // no blocks
    this->Sample(ray, t0, dt, count, out, nullptr);
  }

  void SampleRays(const RayPiece* pieces, int n, double dt) const override;

  // The gradients come from the cell each sample is found in by the walk.
  void SampleRayGradients(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const override
  {
    if (count > 0)
    {
      std::fill(gradients, gradients + 3 * static_cast<std::size_t>(count), 0.0f);
    }
    this->Sample(ray, t0, dt, count, out, gradients);
  }

  // Point data: the analytic gradient of the containing cell's interpolant. Cell data: central
  // differences one cell size apart, one-sided where a side is outside the mesh.
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override
  {
    gradient[0] = gradient[1] = gradient[2] = 0.0f;
    const Eigen::Vector3d p = ray.At(t);
    if (!p.allFinite())
    {
      return;
    }
    const std::uint32_t cell = this->FindContaining(p);
    if (cell != kNone)
    {
      Store(this->GradientIn(cell, p), gradient);
    }
  }

private:
  static void Store(const Eigen::Vector3d& g, float* gradient)
  {
    for (int a = 0; a < 3; ++a)
    {
      gradient[a] = std::isfinite(g[a]) ? static_cast<float>(g[a]) : 0.0f;
    }
  }

  // The samples as SampleRay gives them, and their gradients when `gradients` is given, found
  // by a walk (UnstructuredWalk.h).
  void Sample(const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const;

  // Samples t0 + i dt (i < count) as the walk meets them: samples before a cell the index
  // found read the cell left last or that one when within the tolerance of it, and NaN
  // otherwise; samples up to where the walk leaves a cell read that cell.
  struct SampleVisit
  {
    const UnstructuredSampler& Mesh;
    const Line& Along;
    double T0;
    double Dt;
    int Count;
    float* Out;
    float* Gradients;
    int I = 0;

    bool Found(std::uint32_t previous, double previousExit, std::uint32_t cell, double tIn)
    {
      const double tolerance = this->Mesh.Tolerance;
      for (; this->I < this->Count && this->T0 + this->I * this->Dt < tIn; ++this->I)
      {
        const double t = this->T0 + this->I * this->Dt;
        if (previous != kNone && t <= previousExit + tolerance)
        {
          this->Read(previous, this->I + 1);
        }
        else if (cell != kNone && t >= tIn - tolerance)
        {
          this->Read(cell, this->I + 1);
        }
      }
      return this->I < this->Count;
    }

    bool Crossed(std::uint32_t cell, double tOut)
    {
      int end = this->I;
      while (end < this->Count && this->T0 + end * this->Dt <= tOut)
      {
        ++end;
      }
      if (end > this->I)
      {
        this->Read(cell, end);
        this->I = end;
      }
      return this->I < this->Count;
    }

    void Read(std::uint32_t cell, int end)
    {
      this->Mesh.Interpolate(
        cell, this->Along, this->T0, this->Dt, this->I, end, this->Out, this->Gradients);
    }
  };

  // Records the pieces the walk meets, by the rules SampleVisit samples by.
  struct TraceVisit
  {
    const UnstructuredSampler& Mesh;
    const Line& Along;
    PathRecorder& Path;
    double Hi;

    bool Found(std::uint32_t previous, double previousExit, std::uint32_t cell, double tIn)
    {
      const double tolerance = this->Mesh.Tolerance;
      if (previous != kNone)
      {
        this->Piece(previous, std::min(previousExit + tolerance, tIn));
      }
      if (cell == kNone)
      {
        return false;
      }
      this->Path.Gap(tIn - tolerance);
      return !this->Path.Full();
    }

    bool Crossed(std::uint32_t cell, double tOut)
    {
      this->Piece(cell, tOut);
      return tOut < this->Hi && !this->Path.Full();
    }

    // Only cells that hold a sample are kept. A tetrahedron's field along the ray is found
    // now, while the walk has the cell at hand, and read by every frame as a line.
    void Piece(std::uint32_t cell, double end)
    {
      float relative;
      if (!this->Path.Holds(end, relative))
      {
        return;
      }
      double alpha;
      double beta;
      if (this->Mesh.LinearAlong(cell, this->Along, alpha, beta))
      {
        this->Path.Linear(relative, alpha + beta * this->Path.Start(), beta);
      }
      else
      {
        this->Path.Cell(relative, cell);
      }
    }
  };

  bool TracesPaths() const override { return true; }

  bool TracePath(const Ray& ray, double t0, double t1, double spacing, std::size_t maxPieces,
    std::vector<PathPiece>& path) const override
  {
    const Line line(ray.Origin, ray.Direction);
    double lo;
    double hi;
    if (!std::isfinite(t0) || !std::isfinite(t1) || !ray.Origin.allFinite() ||
        !ray.Direction.allFinite() || !this->ClipLine(line, lo, hi))
    {
      return true; // nothing on the ray: no pieces, every sample NaN
    }
    lo = std::max(lo, t0 - this->Tolerance);
    hi = std::min(hi, t1 + this->Tolerance);
    PathRecorder recorder(path, t0, spacing, maxPieces);
    recorder.Gap(lo);
    if (lo <= hi)
    {
      TraceVisit visit{ *this, line, recorder, hi };
      this->WalkCells(line, lo, hi, visit, lo);
    }
    return recorder.Finish();
  }

  void SampleAlongPath(const Ray& ray, const PathPiece* path, std::size_t pieces, double traceStart,
    double t0, double dt, int count, float* out) const override
  {
    if (!(dt > 0.0))
    {
      this->SampleRay(ray, t0, dt, count, out, nullptr);
      return;
    }
    std::fill(out, out + std::max(count, 0), std::numeric_limits<float>::quiet_NaN());
    const Line line(ray.Origin, ray.Direction);
    const double r0 = t0 - traceStart;
    ForEachPiece(path, pieces, traceStart, t0, dt, count,
      [&](const PathPiece& piece, double start, int begin, int end)
      {
        if (IsLinear(piece))
        {
          const double value = piece.Value;
          const double slope = piece.Slope;
          for (int i = begin; i < end; ++i)
          {
            out[i] = static_cast<float>(value + slope * (r0 + i * dt - start));
          }
        }
        else if (CellOf(piece) != kGapPiece)
        {
          this->Interpolate(CellOf(piece), line, t0, dt, begin, end, out, nullptr);
        }
      });
  }

  // The gradient in `cell` (which contains p). Point data: the points' gradients (each the mean
  // of its cells' interpolant gradients there) interpolated like the values, so that shading is
  // smooth across cells (the interpolant's own gradient jumps from cell to cell). Cell data:
  // central differences one cell size apart, one-sided where a side is outside the mesh.
  Eigen::Vector3d GradientIn(std::uint32_t cell, const Eigen::Vector3d& p) const;

  void ScanValues();

  bool ClipLine(const Line& line, double& tEnter, double& tExit) const
  {
    tEnter = -kInfinity;
    tExit = kInfinity;
    for (int a = 0; a < 3; ++a)
    {
      if (line.Parallel[a])
      {
        if (!(line.O[a] >= this->ClipLo[a] && line.O[a] <= this->ClipHi[a]))
        {
          return false;
        }
        continue;
      }
      const double ta = (this->ClipLo[a] - line.O[a]) * line.Inverse[a];
      const double tb = (this->ClipHi[a] - line.O[a]) * line.Inverse[a];
      tEnter = std::max(tEnter, std::min(ta, tb));
      tExit = std::min(tExit, std::max(ta, tb));
    }
    return tEnter <= tExit;
  }

  std::uint32_t FindContaining(const Eigen::Vector3d& p) const
  {
    for (int pass = 0; pass < 2; ++pass)
    {
      const std::uint32_t cell = this->Hierarchy.FirstContaining(p,
        [&](std::uint32_t c) {
          return (pass == 0 || this->Faces.IsNonConvex(c)) && this->Faces.Contains(c, p, pass == 1);
        });
      if (cell != CellHierarchy::kNoCell)
      {
        return cell;
      }
    }
    return kNone;
  }

  // The first cell that the line is inside at tMin or enters after it, up to tMax, and where.
  // With `strict`, only cells that the line leaves after tMin (not at it) count: after a ray
  // leaves a cell at tMin, the cell itself must not be found again.
  bool FindFirst(const Line& line, double tMin, double tMax, bool strict, std::uint32_t& cell,
    double& tEnter) const
  {
    // From outside, the first cell the line meets is on the mesh's boundary.
    return (this->Outside(line, tMin) ? this->Boundary : this->Hierarchy)
      .FirstHit(
        line, tMin, tMax, strict,
        [&](std::uint32_t c, double& a, double& b)
        { return this->Faces.Interval(c, line, tMin, strict, a, b); },
        cell, tEnter);
  }

  // Whether the line's point at t lies outside the cells' bounds, by more than any cell's
  // interval along a line strays out of its box.
  bool Outside(const Line& line, double t) const
  {
    bool outside = false;
    for (int a = 0; a < 3; ++a)
    {
      const double x = line.O[a] + t * line.D[a];
      outside = outside || !(x >= this->ClipLo[a] + 5.0 * this->Tolerance &&
                             x <= this->ClipHi[a] - 5.0 * this->Tolerance);
    }
    return outside;
  }

  // The field at p (NaN outside the mesh).
  double ValueAt(const Eigen::Vector3d& p) const
  {
    const std::uint32_t cell = this->FindContaining(p);
    if (cell == kNone)
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (this->CellValues)
    {
      return this->Values[cell];
    }
    const CellVertices data = this->Gather(cell);
    const Polynomial polynomial(data);
    double r[3];
    Parametric(data, polynomial, p, r);
    ClampToCell(data.Kind, r, kParametricMargin);
    return polynomial.Value(r);
  }

  // Point data: the point gradients are built now, in parallel, not by the first sample that
  // needs them.
  void PrepareGradients() const override
  {
    if (!this->CellValues)
    {
      this->PointGradients();
    }
  }

  // Per point (3 floats): the mean of the gradients of its cells' interpolants at the point,
  // computed the first time gradients are asked for (a scene without shading never pays).
  const std::vector<float>& PointGradients() const;

  void ComputePointGradients() const;

  // The gradients of the point data's interpolant in `cell` at each of its corners, taken just
  // inside the corner (a pyramid's map is singular at its apex), from one gathering of the cell.
  void CornerGradients(std::uint32_t cell, Eigen::Vector3d* gradients) const;

  // Gradient of the interpolant of `data` at p: the parametric gradient turned into world space
  // by the inverse transposed Jacobian; zero where the map is singular.
  static Eigen::Vector3d InterpolantGradient(
    const CellVertices& data, const Polynomial& polynomial, const Eigen::Vector3d& p);

  CellVertices Gather(std::uint32_t cell) const
  {
    return this->Faces.Vertices(cell, this->CellValues ? nullptr : this->Values.data());
  }

  // A tetrahedron's point field as f(x) = F + G . (x - C), with C its centre relative to the
  // mesh's (so that floats keep their precision far from the origin); F NaN for tetrahedra too
  // flat to have one. One cache line per cell, where gathering its points and values reads many.
  struct TetraLine
  {
    float C[3];
    float F;
    float G[3];
  };

  void BuildTetraLines(const CellOrder& order);

  // A curved cell's (point data, not a tetrahedron, no closed-form map) Polynomial in floats,
  // the map's constant term relative to the mesh's centre, and the guess Newton's iteration
  // starts from: 176 bytes read, where gathering its points and values reads many cache lines
  // and building the polynomial takes 64 products.
  struct CellMap
  {
    float A[8][3];
    float B[8];
    // The affine map's inverse at the parametric centre, r ~ Guess p + Shift: where Newton's
    // first step from the centre goes, without the step.
    float Guess[3][3];
    float Shift[3];

    unstructured::Polynomial Polynomial() const
    {
      unstructured::Polynomial p;
      for (int m = 0; m < 8; ++m)
      {
        p.A[m] = Eigen::Vector3d(this->A[m][0], this->A[m][1], this->A[m][2]);
        p.B[m] = this->B[m];
      }
      return p;
    }
  };

  void BuildCellMaps();
  // Marks the open sides whose planes have every cell's points behind them (kHullSide).
  void FindHullSides();

  // FindFirst for a walk's first cell, tried first next to the cell the thread's previous walk
  // began in (UnstructuredSampler.cxx).
  bool FirstCell(
    const Line& line, double tMin, double tMax, std::uint32_t& cell, double& tIn) const;
  // Whether the line enters the mesh first by `seed` or a cell across one of its sides (see
  // MeshFaces::EntersByHull), and which.
  bool NearSeed(std::uint32_t seed, const Line& line, double tMin, double tMax, std::uint32_t& cell,
    double& tIn) const;

  TetraLine TetraLineOf(std::uint32_t cell) const;

  // Whether the field in `cell` is linear along the line (cell data, or a tetrahedron that is
  // not degenerate): alpha + beta t.
  bool LinearAlong(std::uint32_t cell, const Line& line, double& alpha, double& beta) const
  {
    if (this->CellValues)
    {
      alpha = this->Values[cell];
      beta = 0.0;
      return true;
    }
    if (this->TetraLines.empty() || !(this->TetraLines[cell].F == this->TetraLines[cell].F))
    {
      return false;
    }
    const TetraLine& t = this->TetraLines[cell];
    alpha = t.F;
    beta = 0.0;
    for (int a = 0; a < 3; ++a)
    {
      alpha += t.G[a] * ((line.O[a] - this->Centre[a]) - t.C[a]);
      beta += t.G[a] * line.D[a];
    }
    return true;
  }

  // Samples [begin, end) of the ray, all inside `cell` (or within the tolerance of it), and, when
  // `gradients` is given, their gradients in the same cell.
  void Interpolate(std::uint32_t cell, const Line& line, double t0, double dt, int begin, int end,
    float* out, float* gradients) const
  {
    if (gradients && begin < end)
    {
      const Eigen::Vector3d o(line.O[0], line.O[1], line.O[2]);
      const Eigen::Vector3d d(line.D[0], line.D[1], line.D[2]);
      for (int i = begin; i < end; ++i)
      {
        Store(this->GradientIn(cell, o + (t0 + i * dt) * d),
          gradients + 3 * static_cast<std::size_t>(i));
      }
    }
    double alpha;
    double beta;
    if (this->LinearAlong(cell, line, alpha, beta))
    {
      // Cell data, or a tetrahedron: the field is linear along the ray.
      for (int i = begin; i < end; ++i)
      {
        out[i] = static_cast<float>(alpha + beta * (t0 + i * dt));
      }
      return;
    }
    const Eigen::Vector3d o(line.O[0], line.O[1], line.O[2]);
    const Eigen::Vector3d d(line.D[0], line.D[1], line.D[2]);
    const std::uint32_t slot = this->MapSlots.empty() ? kNone : this->MapSlots[cell];
    if (slot != kNone)
    {
      // A curved cell: Newton's iteration on its kept polynomial, relative to the mesh's
      // centre, from the affine guess for the first sample.
      const CellMap& map = this->CellMaps[slot];
      const Eigen::Vector3d oc =
        o - Eigen::Vector3d(this->Centre[0], this->Centre[1], this->Centre[2]);
      const Eigen::Vector3d p = oc + (t0 + begin * dt) * d;
      double r[3];
      for (int a = 0; a < 3; ++a)
      {
        const double guess =
          map.Shift[a] + map.Guess[a][0] * p[0] + map.Guess[a][1] * p[1] + map.Guess[a][2] * p[2];
        r[a] = std::min(std::max(guess, -1.0), 2.0);
      }
      NewtonSamples(map.Polynomial(), this->Faces.Kind(cell), oc, d, t0, dt, begin, end, r, out);
      return;
    }
    const CellVertices data = this->Gather(cell);
    DirectMap direct;
    if (data.Direct && direct.Set(data))
    {
      // Inverted once: q is affine along the ray.
      const Eigen::Vector3d q0 = direct.Q(o);
      const Eigen::Vector3d qd = direct.Inverse * d;
      const Polynomial polynomial(data);
      for (int i = begin; i < end; ++i)
      {
        double r[3];
        direct.Parametric(q0 + (t0 + i * dt) * qd, r);
        ClampToCell(data.Kind, r, 0.0); // planar faces: only round-off and the tolerance out
        out[i] = static_cast<float>(polynomial.Value(r));
      }
      return;
    }
    // Newton's iteration, from the cell's centre for the first sample and from the previous
    // sample's coordinates for the next.
    const double* centre = ShapeOf(data.Kind).Centre;
    double r[3] = { centre[0], centre[1], centre[2] };
    NewtonSamples(Polynomial(data), data.Kind, o, d, t0, dt, begin, end, r, out);
  }

  // Samples [begin, end) at o + (t0 + i dt) d in a cell of `kind` with map and field
  // `polynomial` (in o's frame), each by Newton's iteration from the previous sample's
  // coordinates, the first from `r`.
  static void NewtonSamples(const Polynomial& polynomial, CellKind kind, const Eigen::Vector3d& o,
    const Eigen::Vector3d& d, double t0, double dt, int begin, int end, double r[3], float* out)
  {
    for (int i = begin; i < end; ++i)
    {
      polynomial.Invert(o + (t0 + i * dt) * d, r);
      double clamped[3] = { r[0], r[1], r[2] };
      ClampToCell(kind, clamped, kParametricMargin);
      out[i] = static_cast<float>(polynomial.Value(clamped));
    }
  }

  // Finds the first cell with the index, then walks across shared faces; after a boundary face
  // (a hole, a concavity), a degenerate cell or a stall, asks the index for the next cell along
  // the ray. Each index query moves strictly forward, and the walk's steps are bounded. Tells
  // `visit` each cell the index finds (Found: the cell, or kNone past the last, where the line
  // enters it, and the cell the walk left last) and each cell the walk leaves (Crossed: where);
  // stops when either returns false.
  // The walk may start at `start` (at most lo) instead, where the line is outside the mesh.
  // (UnstructuredWalk.h)
  template <typename Visitor>
  void WalkCells(const Line& line, double lo, double hi, Visitor& visit, double start) const;
  // WalkCells in steps, so that a thread can take two walks' steps in turn.
  template <typename Visitor>
  class Walker;
  // Sample's walk for one ray, in steps.
  class SampleWalk;
  // Asks for the cache lines of `cell` that the walk reads next (its sides, its field).
  void FetchCell(std::uint32_t cell) const
  {
    Prefetch(this->Faces.FirstSide(cell), 3);
    if (!this->TetraLines.empty() && this->Faces.Kind(cell) == CellKind::Tetra)
    {
      Prefetch(&this->TetraLines[cell], 1);
    }
    else if (!this->MapSlots.empty() && this->MapSlots[cell] != kNone)
    {
      Prefetch(&this->CellMaps[this->MapSlots[cell]], 2);
    }
    else
    {
      Prefetch(this->Faces.PointIds(cell), 1);
    }
  }

  bool CellValues;
  double Tolerance;
  MeshFaces Faces;
  CellHierarchy Hierarchy;
  CellHierarchy Boundary;    // of the cells a line from outside can enter first
  std::vector<float> Values; // per point, or per cell (in the cells' order)
  // Clip's box: the bounds of the cells' points, grown.
  double ClipLo[3] = { 0, 0, 0 };
  double ClipHi[3] = { 0, 0, 0 };
  std::array<double, 2> Range = { 0.0, 0.0 };
  std::vector<TetraLine> TetraLines;   // per cell, when the mesh has tetrahedra with point data
  double Centre[3] = { 0, 0, 0 };      // of the mesh's bounds, where TetraLine's centres are from
  std::vector<std::uint32_t> MapSlots; // per cell: its CellMap, or kNone (empty: none has one)
  std::vector<CellMap> CellMaps;
  mutable std::once_flag PointGradientsOnce;
  mutable std::vector<float> PointGradientData; // see PointGradients
};

} // namespace unstructured
} // namespace savr

#pragma once
// The unstructured sampler's walk from cell to cell (its class is UnstructuredSampler.h), in
// steps: a step is one search of the hierarchy or one cell crossed. A thread can take two walks'
// steps in turn (SampleRays): each step waits on memory for its next cell's sides, and the
// other walk's step runs meanwhile. Either way every walk takes the same steps, so the samples
// are the same bits.

#include "mesh/UnstructuredSampler.h"

#include <optional>

// A walk's step is inlined into the loop that takes it: called, its state lives in memory and a
// walk takes about 7% longer (the tetrahedral wavelet's walking frames).
#if defined(__GNUC__)
#define SAVR_WALK_STEP __attribute__((always_inline)) inline
#else
#define SAVR_WALK_STEP inline
#endif

namespace savr
{
namespace unstructured
{

template <typename Visitor>
class UnstructuredSampler::Walker
{
public:
  Walker(const UnstructuredSampler& mesh, const Line& line, Visitor& visit)
    : Mesh(mesh)
    , Along(line)
    , Visit(visit)
    , MaxSteps(4 * static_cast<std::size_t>(mesh.Faces.CellCount()) + 1024)
  {
  }

  /// Sets the walk over [lo, hi] of the line, from `start` (see WalkCells).
  void Begin(double lo, double hi, double start)
  {
    this->Hi = hi;
    this->TSearch = start < lo && this->Mesh.Outside(this->Along, start) ? start : lo;
  }

  /// A search for the next cell, or the crossing of the current one; false once the walk has
  /// ended.
  SAVR_WALK_STEP bool Step() { return this->Walking ? this->Cross() : this->Search(); }

private:
  bool Search()
  {
    std::uint32_t cell = kNone;
    double tIn = kInfinity;
    if (++this->Steps > this->MaxSteps ||
        !(this->Previous == kNone
            ? this->Mesh.FirstCell(this->Along, this->TSearch, this->Hi, cell, tIn)
            : this->Mesh.FindFirst(this->Along, this->TSearch, this->Hi, this->Strict, cell, tIn)))
    {
      cell = kNone;
      tIn = kInfinity;
    }
    if (!this->Visit.Found(this->Previous, this->PreviousExit, cell, tIn) || cell == kNone)
    {
      return false;
    }
    this->Cell = cell;
    this->TIn = tIn;
    this->EntryFace = kNoFace;
    this->Stall = 0;
    this->Walking = true;
    return true;
  }

  SAVR_WALK_STEP bool Cross()
  {
    const MeshFaces& faces = this->Mesh.Faces;
    std::uint32_t exitSide;
    double tOut = faces.Exit(this->Cell, this->Along, this->EntryFace, this->TIn, exitSide);
    if (exitSide == kNone || !(tOut >= this->TIn))
    {
      tOut = this->TIn; // clipped a corner (round-off), or a broken cell: no progress here
    }
    const std::int32_t next = exitSide == kNone ? -1 : faces.SideAt(exitSide).Neighbour;
    if (next >= 0)
    {
      // The walk is bound by memory latency: fetch the next cell while sampling this one.
      this->Mesh.FetchCell(static_cast<std::uint32_t>(next));
    }
    if (!this->Visit.Crossed(this->Cell, tOut))
    {
      return false;
    }
    if (next == kHullSide)
    {
      // Out of the mesh for good: what the index would answer, without asking it.
      this->Visit.Found(this->Cell, tOut, kNone, kInfinity);
      return false;
    }
    this->Stall = tOut > this->TIn ? 0 : this->Stall + 1;
    if (next < 0 || faces.IsDegenerate(static_cast<std::uint32_t>(next)) ||
        this->Stall > kMaxStall || ++this->Steps > this->MaxSteps)
    {
      this->Previous = this->Cell;
      this->PreviousExit = tOut;
      // The index finds a cell the ray leaves after TSearch; should the walk from it not move
      // on (a non-convex cell's triangles disagreeing by round-off), step past the point.
      this->TSearch = tOut > this->TSearch
                        ? tOut
                        : std::nextafter(this->TSearch + this->Mesh.Tolerance * 1e-3, kInfinity);
      this->Strict = true;
      this->Walking = false;
      return true;
    }
    this->Cell = static_cast<std::uint32_t>(next);
    this->TIn = tOut;
    this->EntryFace = faces.SideAt(exitSide).NeighbourFace;
    return true;
  }

  const UnstructuredSampler& Mesh;
  const Line& Along;
  Visitor& Visit;
  const std::size_t MaxSteps;
  double Hi = 0.0;
  std::size_t Steps = 0;
  double TSearch = 0.0;
  bool Strict = false;
  std::uint32_t Previous = kNone;
  double PreviousExit = -kInfinity;
  // Between a search and the next: the cell the walk is in, where it entered and by which face.
  bool Walking = false;
  std::uint32_t Cell = kNone;
  double TIn = kInfinity;
  std::uint8_t EntryFace = kNoFace;
  int Stall = 0;
};

template <typename Visitor>
void UnstructuredSampler::WalkCells(
  const Line& line, double lo, double hi, Visitor& visit, double start) const
{
  Walker<Visitor> walk(*this, line, visit);
  walk.Begin(lo, hi, start);
  while (walk.Step())
  {
  }
}

class UnstructuredSampler::SampleWalk
{
public:
  // Writes NaN to every sample; the steps then read the ones in cells.
  SampleWalk(const UnstructuredSampler& mesh, const Ray& ray, double t0, double dt, int count,
    float* out, float* gradients)
    // Walked forward: samples at decreasing parameters are the same points on the reversed ray.
    : Along(ray.Origin, Forward(dt) * ray.Direction)
    , Visit{ mesh, this->Along, Forward(dt) * t0, Forward(dt) * dt, count, out, gradients }
    , Walk(mesh, this->Along, this->Visit)
  {
    if (count <= 0)
    {
      return;
    }
    std::fill(out, out + count, std::numeric_limits<float>::quiet_NaN());
    if (!std::isfinite(t0) || !std::isfinite(dt) || !ray.Origin.allFinite() ||
        !ray.Direction.allFinite())
    {
      return;
    }
    t0 = this->Visit.T0;
    dt = this->Visit.Dt;
    double lo;
    double hi;
    if (!mesh.ClipLine(this->Along, lo, hi))
    {
      return;
    }
    hi = std::min(hi, t0 + (count - 1) * dt + mesh.Tolerance);
    // A ray's first samples lie within a step or two of where it enters the bounds: the walk
    // starts there, from the first boundary cell, rather than asking the whole hierarchy for
    // the cell at the first sample (the samples before it are NaN either way).
    const double entry = lo;
    lo = std::max(lo, t0 - mesh.Tolerance);
    if (lo <= hi)
    {
      this->Walk.Begin(lo, hi, lo - entry <= 2.0 * dt ? entry : lo);
      this->Going = true;
    }
  }

  /// One step of the walk; false once it has ended (or there was none).
  bool Step() { return this->Going && (this->Going = this->Walk.Step()); }

private:
  static double Forward(double dt) { return dt < 0.0 ? -1.0 : 1.0; }

  const Line Along;
  SampleVisit Visit;
  Walker<SampleVisit> Walk;
  bool Going = false;
};

inline void UnstructuredSampler::Sample(
  const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const
{
  SampleWalk walk(*this, ray, t0, dt, count, out, gradients);
  while (walk.Step())
  {
  }
}

inline void UnstructuredSampler::SampleRays(const RayPiece* pieces, int n, double dt) const
{
  for (int first = 0; first < n; first += kMostPieces)
  {
    const int group = std::min(n - first, kMostPieces);
    std::optional<SampleWalk> walks[kMostPieces];
    for (int i = 0; i < group; ++i)
    {
      const RayPiece& piece = pieces[first + i];
      walks[i].emplace(*this, *piece.R, piece.T0, dt, piece.Count, piece.Out, nullptr);
    }
    // A walk that has ended answers false at once.
    for (bool going = true; going;)
    {
      going = false;
      for (int i = 0; i < group; ++i)
      {
        going = walks[i]->Step() || going;
      }
    }
  }
}

} // namespace unstructured
} // namespace savr

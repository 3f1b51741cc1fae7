#pragma once
// The pieces of a ray's path through an unstructured mesh (Sampler::TracePath): pieces whose field
// is linear along the ray (tetrahedra with point data, any cell with cell data), pieces that name
// a cell to interpolate again (the other cells), and gaps (outside the mesh). Later frames on the
// ray read these instead of walking from cell to cell.

#include "sampler/Sampler.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace savr
{
namespace unstructured
{

// A piece that names no cell: its samples are NaN.
constexpr std::uint32_t kGapPiece = 0xFFFFFFFFu;

// A piece whose samples the cell interpolates again: the cell's index in Value's bits, Slope NaN.
inline PathPiece CellPiece(float end, std::uint32_t cell)
{
  PathPiece piece;
  piece.End = end;
  std::memcpy(&piece.Value, &cell, sizeof cell);
  piece.Slope = std::numeric_limits<float>::quiet_NaN();
  return piece;
}

inline bool IsLinear(const PathPiece& piece)
{
  return piece.Slope == piece.Slope;
}

inline std::uint32_t CellOf(const PathPiece& piece)
{
  std::uint32_t cell;
  std::memcpy(&cell, &piece.Value, sizeof cell);
  return cell;
}

// Appends a ray's pieces, each starting where the one before ended (parameters relative to the
// trace's start, as floats), and leaves out those that hold no sample of the lattice.
class PathRecorder
{
public:
  PathRecorder(
    std::vector<PathPiece>& path, double traceStart, double spacing, std::size_t maxPieces)
    : Path(path)
    , First(path.size())
    , TraceStart(traceStart)
    , Spacing(spacing)
    , MaxPieces(maxPieces)
  {
  }

  // Where the next piece starts, as a ray parameter.
  double Start() const { return this->TraceStart + this->LastEnd; }
  bool Full() const { return this->Path.size() - this->First > this->MaxPieces; }

  // Whether a piece from Start() to the ray parameter `end` would be kept: it holds a sample
  // of the lattice (after rounding its end to a float).
  bool Holds(double end, float& relative) const
  {
    relative = static_cast<float>(end - this->TraceStart);
    if (!(relative > this->LastEnd) || this->Full())
    {
      return false;
    }
    if (!(this->Spacing > 0.0))
    {
      return true;
    }
    // The last lattice sample at or before the end lies after the start.
    return std::floor(relative / this->Spacing) * this->Spacing > this->LastEnd;
  }

  // A piece ending at `relative` (from Holds) whose field along the ray is value + slope * (t -
  // Start()).
  void Linear(float relative, double value, double slope)
  {
    this->Push({ relative, static_cast<float>(value), static_cast<float>(slope) });
  }
  // A piece that `cell` interpolates again.
  void Cell(float relative, std::uint32_t cell) { this->Push(CellPiece(relative, cell)); }
  // A piece up to `end` outside the mesh.
  void Gap(double end)
  {
    float relative;
    if (this->Holds(end, relative))
    {
      this->Cell(relative, kGapPiece);
    }
  }

  // Drops what was appended; false when the path held too many pieces.
  bool Finish()
  {
    if (this->Full())
    {
      this->Path.resize(this->First);
      return false;
    }
    return true;
  }

private:
  void Push(const PathPiece& piece)
  {
    this->Path.push_back(piece);
    this->LastEnd = piece.End;
  }

  std::vector<PathPiece>& Path;
  std::size_t First;
  double TraceStart;
  double Spacing;
  std::size_t MaxPieces;
  float LastEnd = -std::numeric_limits<float>::infinity();
};

// Calls evaluate(piece, pieceStart, begin, end) for the samples [begin, end) at increasing
// parameters t0 + i dt (i < count) that each piece of `path` holds; pieceStart is where the piece
// starts, relative to the trace's start.
template <typename Evaluate>
void ForEachPiece(const PathPiece* path, std::size_t pieces, double traceStart, double t0,
  double dt, int count, Evaluate&& evaluate)
{
  const double r0 = t0 - traceStart;
  double start = -std::numeric_limits<double>::infinity();
  int i = 0;
  for (std::size_t k = 0; k < pieces && i < count; ++k)
  {
    const double end = path[k].End;
    int e = i;
    while (e < count && r0 + e * dt <= end)
    {
      ++e;
    }
    if (e > i)
    {
      evaluate(path[k], start, i, e);
      i = e;
    }
    start = end;
  }
}

} // namespace unstructured
} // namespace savr

#pragma once
// The grid's blocks of cells as rays pass through them: the skip distances that say how many
// rings of skipped blocks lie around each one, and the walk that follows a ray from block to
// block, leaping as far as those distances promise, to the first block that is not skipped.

#include "image/GridAVX2.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace savr
{
namespace detail
{

/// The block grid of a grid sampler: blocks along each axis, cells per block edge (1 << Shift),
/// and the point-index coordinate of the first block faces (0.5 for cell data, whose values lie
/// at cell centres).
struct BlockLattice
{
  long long Blocks[3] = { 1, 1, 1 };
  int Shift = 3;
  double CellShift = 0.0;

  std::size_t Index(const long long b[3]) const
  {
    return static_cast<std::size_t>(b[0] + this->Blocks[0] * (b[1] + this->Blocks[1] * b[2]));
  }
};

/// Turns per-block skip flags (non-zero: skipped) into chessboard distances to the nearest block
/// that is not skipped (1 for a skipped block beside one, at most 255; 0 stays 0), by a forward
/// and a backward raster sweep over each block's 26 neighbours (exact for this metric). `skip`
/// holds one flag per block of `lattice`; any other size leaves it as it is.
void ChessboardSkipDistances(const BlockLattice& lattice, std::vector<std::uint8_t>& skip);

/// The first ray parameter in [t0, t1] whose point lies in a block `skipped` does not flag
/// (t1 when there is none), for a ray o + t d in point-index coordinates. The walk starts in the
/// block `locate(t, b)` puts the point at t in (b: block coordinates; points outside the grid lie
/// in its border blocks) and crosses blocks one face after another, the nearest face first;
/// from a block whose distance promises rings of skipped blocks around it, it leaps as far as
/// they reach (SkipReach; `perCell` is the ray parameter of one cell along the fastest axis) and
/// locates the point there afresh. Face parameters are computed afresh from each face, so that
/// every walk reaching a face finds the same t.
template <typename Locate>
double FirstUnskippedBlock(const BlockLattice& lattice, const Eigen::Vector3d& o,
  const Eigen::Vector3d& d, double perCell, double t0, double t1, const std::uint8_t* skipped,
  Locate&& locate)
{
  if (!skipped || !(t1 > t0) || !std::isfinite(perCell))
  {
    return t0;
  }
  const double size = static_cast<double>(1LL << lattice.Shift);
  double inverse[3];
  for (int a = 0; a < 3; ++a)
  {
    inverse[a] = d[a] != 0.0 ? 1.0 / d[a] : 0.0;
  }
  // Where the ray enters the next block along axis a from block coordinate `b`; infinity past
  // the border blocks, which hold every point beyond them.
  const auto nextFace = [&](int a, long long b)
  {
    const bool up = d[a] > 0.0 && b + 1 < lattice.Blocks[a];
    const bool down = d[a] < 0.0 && b > 0;
    const double face = static_cast<double>(up ? b + 1 : b) * size + lattice.CellShift;
    return up || down ? (face - o[a]) * inverse[a] : std::numeric_limits<double>::infinity();
  };
  double t = t0;
  // Each leap or face crossing moves on by a block at least: the walk ends within these (were
  // it not to, it ends where it stands, every point before that found skipped).
  const long long most = 2 * (lattice.Blocks[0] + lattice.Blocks[1] + lattice.Blocks[2]) + 8;
  long long steps = 0;
  while (t < t1 && steps++ < most)
  {
    long long b[3];
    locate(t, b);
    double next[3];
    for (int a = 0; a < 3; ++a)
    {
      next[a] = nextFace(a, b[a]);
    }
    std::size_t block = lattice.Index(b);
    // Through blocks face by face until one is not skipped or one leaps.
    while (true)
    {
      const std::uint8_t flag = skipped[block];
      if (!flag)
      {
        return std::max(t0, std::min(t, t1));
      }
      const double reach = t + SkipReach(flag, lattice.Shift) * perCell;
      const int a =
        next[0] <= next[1] ? (next[0] <= next[2] ? 0 : 2) : (next[1] <= next[2] ? 1 : 2);
      if (!std::isfinite(next[a]))
      {
        return t1; // in the border blocks to the end
      }
      if (reach > next[a])
      {
        t = reach; // leap, and find the block there afresh
        break;
      }
      t = std::max(t, next[a]);
      if (!(t < t1) || steps++ >= most)
      {
        return std::min(t, t1); // (out of steps: every point before t is skipped)
      }
      b[a] += d[a] > 0.0 ? 1 : -1;
      next[a] = nextFace(a, b[a]);
      block = lattice.Index(b);
    }
  }
  return std::min(t, t1);
}

} // namespace detail
} // namespace savr

#pragma once
// A ray in world coordinates, and the clip of a line to a box that samplers share.

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace savr
{

/// A ray in world coordinates; `Direction` has unit length so ray parameters are world distances.
struct Ray
{
  Eigen::Vector3d Origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d Direction = Eigen::Vector3d::UnitZ();

  Eigen::Vector3d At(double t) const { return Origin + t * Direction; }
};

/// Parameter interval [tEnter, tExit] of the line o + t d inside the box [lo, hi] (slabs); false
/// when the line misses it or o or d is not finite.
inline bool ClipToBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
  const Eigen::Vector3d& hi, double& tEnter, double& tExit)
{
  if (!o.allFinite() || !d.allFinite())
  {
    return false;
  }
  tEnter = -std::numeric_limits<double>::infinity();
  tExit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < lo[a] || o[a] > hi[a])
      {
        return false;
      }
      continue;
    }
    const double inverse = 1.0 / d[a]; // one division, not two: this runs for every pixel
    double t0 = (lo[a] - o[a]) * inverse;
    double t1 = (hi[a] - o[a]) * inverse;
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    tEnter = std::max(tEnter, t0);
    tExit = std::min(tExit, t1);
  }
  return tEnter < tExit;
}

} // namespace savr

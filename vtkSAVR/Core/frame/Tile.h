#pragma once
// A tile of the frame loop's image: its rays, the stores that keep their samples, and how far it
// has refined. Tiles are the unit of work: one thread at a time works on a tile, and each
// tile's pixels are a function of its own rays' samples only.

#include "frame/RayStores.h"
#include "frame/TilePaths.h"

#include <cstddef>
#include <vector>

namespace savr
{

struct Tile
{
  int X0 = 0, Y0 = 0, X1 = 0, Y1 = 0;
  std::vector<RayInfo> Rays;
  RayStores Stores;
  TilePaths Paths;        // while accumulating, for samplers that trace paths
  int Frames = 0;         // frames its rays have taken (see TileSchedule::Settled)
  int SnapshotFrames = 0; // frames of its pixels in the error snapshot (0: none valid)
  double ErrorSum = 0.0;  // its share of the error estimate's sum of squares
  bool Resume = false;    // a ray's blend is not opaque at its horizon: sample it whole

  /// Units of work of one frame of the tile: its rays and their samples per frame (an empty
  /// tile costs next to nothing, one the data fills the most).
  double Work() const
  {
    double samples = 1.0 + double(this->Rays.size());
    for (const RayInfo& ray : this->Rays)
    {
      samples += ray.SamplesPerFrame;
    }
    return samples;
  }
};

} // namespace savr

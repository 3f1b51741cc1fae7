#pragma once
// A tile of the frame loop's image: its rays, the stores that keep their samples, and how far it
// has refined. Tiles are the unit of work: one thread at a time works on a tile, and each
// tile's pixels are a function of its own rays' samples only.

#include "frame/SampleStore.h"
#include "frame/TilePaths.h"

#include <cstddef>
#include <vector>

namespace savr
{

/// What a ray keeps between frames; its direction is recomputed from the pixel (cheaply, and
/// identically) so that large images do not pay for it in memory.
struct RayInfo
{
  int Pixel;
  int SamplesPerFrame;
  double TEnter;
  double Length;
  std::size_t FirstRow;
  /// Rows every frame has sampled: SamplesPerFrame, or fewer once the first frame found the
  /// ray opaque there (its opacity horizon); frames after the first sample these rows only.
  int Horizon;
  /// Rows before it are not sampled: the first frame's transfer function makes every block they
  /// pass through transparent (its front; FrameLoop::FrontsHold). Frames sample rows
  /// [Front, Horizon).
  int Front;
  /// FrameLoop::RotationOf its pixel at the loop's step: its frames' offsets are rotated by it.
  double Rotation;
  /// Rows from it on are not sampled either: past the last block the ray meets that the first
  /// frame's function does not make transparent (its back; SamplesPerFrame when none). The
  /// horizon lies at the back or before it.
  int Back;

  /// Whether the ray keeps no rows: the first frame's function makes every block it meets
  /// transparent, and its composite is empty.
  bool KeepsNoRows() const { return this->Horizon <= this->Front; }
};

struct Tile
{
  int X0 = 0, Y0 = 0, X1 = 0, Y1 = 0;
  std::vector<RayInfo> Rays;
  SampleStore Store;
  SampleStore Normals;             // used only when shading
  SampleStore Magnitudes;          // used only with gradient opacity
  SampleStore ComponentNormals;    // used only when shading independent components
  SampleStore ComponentMagnitudes; // used only with independent components' gradient opacity
  SampleStore SecondCodes;         // used only when the sampler has second codes
  TilePaths Paths;                 // while accumulating, for samplers that trace paths
  int Frames = 0;                  // frames its rays have taken (see TileSchedule::Settled)
  int SnapshotFrames = 0;          // frames of its pixels in the error snapshot (0: none valid)
  double ErrorSum = 0.0;           // its share of the error estimate's sum of squares
  bool Resume = false;             // a ray's blend is not opaque at its horizon: sample it whole

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

  /// Calls f(store, its counterpart in `other`) for each store.
  template <typename F>
  void EachStore(Tile& other, F&& f)
  {
    f(this->Store, other.Store);
    f(this->Normals, other.Normals);
    f(this->Magnitudes, other.Magnitudes);
    f(this->ComponentNormals, other.ComponentNormals);
    f(this->ComponentMagnitudes, other.ComponentMagnitudes);
    f(this->SecondCodes, other.SecondCodes);
  }
};

} // namespace savr

#pragma once
// The error estimate of a progressive image: each tile compares its pixels now with its own
// at the power of two of frames below its count (its snapshot), and the root mean square of
// those changes over the pixels whose rays meet the data estimates the error left. With first-
// or higher-order convergence that change is about the remaining error, or more.

#include "blend/BlendTypes.h"
#include "frame/Tile.h"
#include "frame/TileSchedule.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace savr
{

/// What an image was blended with: the transfer function's generation, the mode, and the
/// generation of the other tables the blend reads.
struct BlendIdentity
{
  std::uint64_t TransferFunction = 0;
  BlendMode Mode = BlendMode::Composite;
  std::uint64_t Inputs = 0;

  bool operator==(const BlendIdentity& other) const
  {
    return this->TransferFunction == other.TransferFunction && this->Mode == other.Mode &&
           this->Inputs == other.Inputs;
  }
  bool operator!=(const BlendIdentity& other) const { return !(*this == other); }
};

class ErrorEstimator
{
public:
  /// Blends the first `frames` stored frames of `tiles` (indices) into `target`, an image of
  /// the view's size.
  using BlendFrames =
    std::function<void(int frames, float* target, const std::vector<std::size_t>& tiles)>;

  /// Estimates the error of `tiles`, which the caller owns, running on `schedule`.
  ErrorEstimator(std::vector<Tile>& tiles, TileSchedule& schedule);

  /// Forgets every snapshot and the estimate (a new view).
  void Reset();
  /// Frees the snapshots' memory too.
  void Release();

  /// The estimate: negative until every tile with rays has two frames and none waits to resume
  /// rays.
  double Value() const { return this->Estimate; }
  /// The image is exact (one frame of a slice).
  void SetExact() { this->Estimate = 0.0; }

  /// After `image` (`width` pixels to a row; zero outside the `covered` pixels whose rays meet
  /// the data) changed in `tiles` (indices; all when null), blended as `blend` says: each
  /// such tile's share of the estimate (Tile::ErrorSum) against its snapshot, blended anew by
  /// `blendEarlier` where the snapshot is not at the power of two of frames below the tile's
  /// (or was blended otherwise); tiles at a power of two of frames then become the next
  /// snapshot, unless the image is a re-blend (`reblended`: their frames were not new). Then
  /// the whole estimate, the tiles' sums added in order: the same bits whatever the thread
  /// count.
  void Update(const std::vector<float>& image, int width, std::size_t covered,
    const BlendIdentity& blend, const std::vector<std::size_t>* tiles, bool reblended,
    const BlendFrames& blendEarlier);

  /// The largest power of two below `frames`, which a tile with `frames` frames (at least 2)
  /// compares with.
  static int EarlierFrames(int frames);

private:
  std::vector<Tile>& Tiles;
  TileSchedule& Schedule;
  std::vector<float> Image; // each tile's pixels at its snapshot's frames
  BlendIdentity Blended;    // what the snapshots were blended with
  double Estimate = -1.0;
};

} // namespace savr

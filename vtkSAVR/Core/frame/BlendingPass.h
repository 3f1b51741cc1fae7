#pragma once
// The blending pass of a frame: each ray of a tile blended from its stored frames in depth
// order, through the composite's fast paths where the blend allows them (per-code interval
// tables, four rays at a time with AVX2), else through the blends of Integrator.h; and blends
// over parts of the rays bounded by window depths.

#include "blend/StoredAVX2.h"
#include "frame/CompositeTables.h"
#include "frame/FrameState.h"
#include "frame/StoredRows.h"

#include <cstddef>
#include <vector>

namespace savr
{

/// A part of every pixel's ray, bounded by window depths in [0, 1] (as View::Depth, one per
/// pixel, rows from the bottom): pixel i's part lies between depths Near[i] and Far[i] (none
/// where Near[i] >= Far[i]). Its blend goes into Image (premultiplied RGBA, 4 floats per
/// pixel of the view, which the caller sized and zeroed).
struct DepthWindow
{
  const float* Near = nullptr;
  const float* Far = nullptr;
  float* Image = nullptr;
};

/// What the blending pass of every tile of a frame shares.
template <typename Code>
struct TileBlend
{
  const TransferFunctionTable& TF;
  BlendMode Mode;
  int Frames;
  StoredAttributes Attrs;
  bool HasSecondCodes;
  // Plain composite: each sorted offset's interval table, and whether rays are composited four
  // at a time (AVX2; every offset has a table and the rays are unlit).
  const std::vector<const double*>& SortedTables;
  bool Plain;
  bool GroupsOfFour;
  const detail::RowScan<Code>& Scan;
  float* Pixels;
};

class BlendingPass
{
public:
  /// Blends the view of `state`, which outlives the pass.
  explicit BlendingPass(FrameState& state)
    : State(state)
  {
  }

  /// Sizes the offsets for `frames` frames and the opacity cache for their gaps.
  void Prepare(const TransferFunctionTable& tf, int frames);
  /// The plain stored composite's interval tables for `frames` frames: each sorted offset's
  /// (null when it has none). False, with no tables, when the blend is not plain (composite
  /// without gradient opacity, second codes or component terms; lit or not).
  bool PlainIntervalTables(const TransferFunctionTable& tf, BlendMode mode, int frames,
    const StoredAttributes& attributes, std::vector<const double*>& sortedTables);
  /// The blending pass of a tile: the first Frames stored frames of each of its rays into the
  /// pixels.
  template <typename Code>
  void BlendTile(Tile& tile, ThreadBuffers& buffers, const TileBlend<Code>& blend) const;
  /// The first `frames` stored frames of every ray of `tiles` (all when null), blended over
  /// each window's part of the ray into the window's image.
  template <typename Code>
  void BlendWindows(const TransferFunctionTable& tf, BlendMode mode, const DepthWindow* windows,
    int count, int frames, const std::vector<std::size_t>* tiles);

private:
  FrameState& State;
  AlphaCache Alphas;
  AlphaCache WindowAlphas; // for blends of parts of rays, whose intervals are not tabulated
  CompositeTables Tables;  // the composite's fast paths' interval tables
};

} // namespace savr

#pragma once
// The single pass: plain ray casting at a given step and offset that stores nothing and stops
// rays early, for frames while the camera moves and the reference a complete store must match;
// and the slice, exact in one pass.

#include "blend/TransferFunctionTable.h"
#include "frame/CompositeTables.h"
#include "frame/FrameState.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace savr
{

/// How a single pass may cut corners that an accumulated image must not.
struct PassOptions
{
  /// Skip blocks of the data that the transfer function makes transparent (composite and
  /// additive blending only).
  bool SkipTransparent = false;
  /// Stop a composite ray once its transmittance falls below this; 0 for
  /// FrameSettings::Termination.
  double Termination = 0.0;
  /// Cast one ray for each block of PixelStride x PixelStride pixels (a power of two that
  /// divides the tile size; others read as 1), and give its colour to the block's pixels that
  /// have rays: fewer rays, a coarser image.
  int PixelStride = 1;

  /// A pass for a moment's image (while the camera moves, or until a frame reaches a tile):
  /// transparent blocks skipped, rays stopped once what lies behind could change a pixel by
  /// less than one 8-bit level, one ray per `stride` x `stride` pixels.
  static PassOptions Fast(int stride)
  {
    PassOptions fast;
    fast.SkipTransparent = true;
    fast.Termination = 1.0 / 256.0;
    fast.PixelStride = stride;
    return fast;
  }
};

class SinglePass
{
public:
  /// Renders the view of `state`, which outlives the pass, into its image.
  explicit SinglePass(FrameState& state)
    : State(state)
  {
  }

  /// Plain ray casting at `step` from the (rotated) offset `offset` over the tiles from `first`
  /// on (of `tiles`, all when null) into the image.
  void Render(const TransferFunctionTable& tf, BlendMode mode, double step, double offset,
    const PassOptions& options, std::size_t first = 0,
    const std::vector<std::size_t>* tiles = nullptr);
  /// BlendMode::Slice: each ray's value where it crosses the slice plane inside the data (and
  /// in front of opaque geometry), coloured by the transfer function with its opacity as given,
  /// lit by the gradient there when shading. Exact in one pass; nothing is stored.
  void RenderSlice(const TransferFunctionTable& tf);

private:
  // A chunk of `count` samples of a pass from t0 on, sampled into the buffers' Values (and
  // SecondCodes, with second codes): their codes into Codes, and into Attributes each one's
  // normal and magnitude codes where the pass sees it (kNoNormal elsewhere), from the
  // gradients of the run between the first sample it sees and the last, asked for at once.
  void Chunk(const TransferFunctionTable& tf, BlendMode mode, const StoredAttributes& attributes,
    const Ray& r, double t0, double step, int count, std::uint32_t nanCode,
    ThreadBuffers& buffers) const;

  FrameState& State;
  AlphaCache Alphas;
  CompositeTables Tables; // the lean composite's table of a step
};

} // namespace savr

#pragma once
// The progressive frame loop: per camera, every frame samples each pixel's ray at one new offset,
// keeps the samples, and re-blends all of them. It is the front of the frame's parts: the view's
// state (FrameState), the tile schedule, the sampling, blending and single passes, and the error
// estimate, and says in order what a frame does. Every pixel is a function of its own samples
// only, so images do not depend on the thread count.

#include "frame/BlendingPass.h"
#include "frame/ErrorEstimator.h"
#include "frame/FrameState.h"
#include "frame/SamplingPass.h"
#include "frame/SinglePass.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace savr
{

enum class Phase
{
  Interacting,  // one pass per frame, nothing stored
  Accumulating, // one new offset per frame
  Complete      // every frame taken; re-blend only when the transfer function changes
};

class FrameLoop
{
public:
  FrameLoop() = default;
  FrameLoop(const FrameLoop&) = delete;
  FrameLoop& operator=(const FrameLoop&) = delete;

  /// Forgets all samples and sets up rays for a new view of `sampler`.
  void Reset(
    const View& view, std::shared_ptr<const Sampler> sampler, const FrameSettings& settings);

  /// Samples the next frame's offset along every ray of the frame's tiles (every tile, unless
  /// SetTileTolerance has settled some, or rays cut at their opacity horizon wait to be sampled
  /// whole, which such a call does first), stores it and re-blends those rays. Where the image
  /// shows other tables or mode than these (an edit before completion, or a single pass) and the
  /// frame is not every tile's, every tile is re-blended first (as Reblend; not bounded by
  /// `seconds`, of which the frame gets what is left), so that tiles the frame does not reach
  /// show them too. Samples nothing once the frame limit is reached. With `seconds` > 0 the call
  /// returns once the tiles it has done took that long (or more: by up to the time of one tile on
  /// each thread; or less: when the next tile is estimated to pass it by more than a quarter,
  /// from the costs measured so far), and the next call goes on with the next tile: tiles are done
  /// in a fixed order, and each tile's pixels show its own frames, so the image after the frame's
  /// last tile is the same whatever the bound, the threads or the timing. Frames() counts a frame
  /// once its last tile is done. Returns whether the frame is done (true also when there is nothing
  /// to do).
  bool AccumulateFrame(const TransferFunctionTable& tf, BlendMode mode, double seconds = 0.0);

  /// The fraction of the tiles of a frame under way that AccumulateFrame has done (0 when no
  /// frame is under way).
  double FrameProgress() const;

  /// Seconds since some fixed point, as a time bound reads them (AccumulateFrame's `seconds`).
  /// Called from several threads at once.
  using Clock = TileSchedule::Clock;
  /// The clock that time bounds read; by default std::chrono::steady_clock. Tests of a bound set
  /// one of their own, so that what they check does not depend on the machine's load. (Null
  /// restores the default.)
  void SetClock(Clock clock) { this->State.Schedule.SetClock(std::move(clock)); }

  /// With a tolerance > 0, a tile whose own error estimate (as ErrorEstimate, over its pixels)
  /// is below it takes no more frames while the others go on (its share of ErrorEstimate stays
  /// what it was when it stopped); a re-blend that raises a tile's estimate to the tolerance or
  /// above resumes it, and tiles behind take frames first until they catch up. Each tile's
  /// pixels are always the blend of its own frames. 0 (the default): every tile takes every
  /// frame. Takes effect at the next frame.
  void SetTileTolerance(double tolerance) { this->State.Schedule.SetTolerance(tolerance); }
  /// Tiles with rays that take no more frames (SetTileTolerance) before the frame limit.
  std::size_t SettledTiles() const
  {
    return this->State.Schedule.SettledTiles(this->State.FrameLimitCount);
  }

  /// Lighting for the blends that follow (composite and single passes); null blends unshaded.
  /// The table must outlive its use. Has effect only with FrameSettings::Shade.
  void SetShading(const ShadingTable* shading) { this->State.Inputs.Shading = shading; }

  /// Gradient opacity for the composite blends that follow; null for none. Has effect only with
  /// FrameSettings::GradientMagnitudes (the table's scale must be MagnitudeScale) or
  /// ComponentMagnitudes (a set per component, each set's scale its ComponentMagnitudeScales).
  void SetGradientOpacity(const GradientOpacityTable* table)
  {
    this->State.Inputs.GradientOpacity = table;
  }

  /// Isosurfaces for BlendMode::Isosurface; null draws nothing in that mode.
  void SetIsoSurfaces(const IsoSurfaces* isos) { this->State.Inputs.Isos = isos; }

  /// The plane BlendMode::Slice draws: a point on it and its normal (not zero), world space.
  void SetSlicePlane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal)
  {
    this->State.Inputs.SliceOrigin = origin;
    this->State.Inputs.SliceNormal = normal;
  }

  /// Re-blends the stored samples, e.g. with a new transfer function.
  void Reblend(const TransferFunctionTable& tf, BlendMode mode);

  /// Plain ray casting at `step` from the (rotated) offset `offset`: stores nothing, stops rays
  /// early. Used while the camera moves, and as the reference a complete store must match.
  void RenderSinglePass(const TransferFunctionTable& tf, BlendMode mode, double step, double offset,
    const PassOptions& options = PassOptions());

  /// While the first frame after a Reset is under way (FrameProgress() above 0 and below 1),
  /// gives the tiles it has not reached a single pass at its step, one ray per `stride` x
  /// `stride` pixels (see PassOptions::PixelStride): an image to show there until the frame
  /// reaches them, which then replaces it. Nothing is stored; the frame goes on as before. Does
  /// nothing otherwise.
  void PreviewRemainingTiles(const TransferFunctionTable& tf, BlendMode mode, int stride);

  /// Premultiplied RGBA, 4 floats per pixel, rows from the bottom.
  const std::vector<float>& Image() const { return this->State.Pixels; }

  /// Interacting after a single pass; otherwise Accumulating until the frame limit, then Complete.
  Phase CurrentPhase() const
  {
    return this->ShowingSinglePass ? Phase::Interacting
                                   : (this->Complete() ? Phase::Complete : Phase::Accumulating);
  }

  /// The image as 8-bit premultiplied RGBA (rounded, clamped to [0, 1]), converted in parallel.
  void ImageBytes(std::vector<std::uint8_t>& bytes) { this->ImageBytes(this->State.Pixels, bytes); }
  /// The same of another image of the view's size that is zero outside ImageRectangle.
  void ImageBytes(const std::vector<float>& image, std::vector<std::uint8_t>& bytes);

  /// A part of every pixel's ray, bounded by window depths in [0, 1] (as View::Depth, one per
  /// pixel, rows from the bottom): pixel i's part lies between depths Near[i] and Far[i] (none
  /// where Near[i] >= Far[i]). Its blend goes into Image (premultiplied RGBA, 4 floats per
  /// pixel of the view, which the caller sized and zeroed).
  using DepthWindow = savr::DepthWindow;

  /// Whether BlendDepthWindows can blend the image shown now by parts of its rays: samples are
  /// stored, and the mode blends intervals (WindowedBlend).
  bool CanBlendDepthWindows(BlendMode mode) const;

  /// Blends the stored samples (no new ones) over each window's part of every ray, as the
  /// image is blended over whole rays: blends over adjacent parts composite to the image (up
  /// to rounding). Does nothing when CanBlendDepthWindows is false.
  void BlendDepthWindows(
    const TransferFunctionTable& tf, BlendMode mode, const DepthWindow* windows, int count);

  /// Pixels [x0, x1) x [y0, y1) (`r` = x0, y0, x1, y1) hold every pixel of the image that may
  /// not be zero: those whose rays can meet the data.
  void ImageRectangle(int r[4]) const
  {
    std::copy(this->State.Rectangle, this->State.Rectangle + 4, r);
  }

  /// The base step in effect: FrameSettings::SampleDistance, or coarser to keep within
  /// MaximumSamplesPerFrame.
  double SampleDistance() const { return this->State.Settings.SampleDistance; }
  /// Bytes of the budget that are not stored samples, as counted at the last Reset: the images,
  /// the ray tables, the per-thread scratch and the caller's reserved bytes.
  std::size_t FixedBytes() const { return this->State.Fixed; }
  /// Whether FixedBytes() exceed the budget: then nothing is allocated and nothing drawn.
  bool OverBudget() const { return this->State.OverBudget(); }

  /// Frames of the tiles that have taken the most.
  int Frames() const { return this->FrameCount; }
  /// Frames that fit the settings and the memory budget (0 when not even one frame fits).
  int FrameLimit() const { return this->State.FrameLimitCount; }
  /// Whether every tile has taken every frame of the limit (one, a single pass, when none
  /// fits), or is settled (SetTileTolerance).
  bool Complete() const
  {
    const FramePass& pass = this->State.Schedule.Pass();
    return !pass.Resume && pass.Frames >= std::max(this->State.FrameLimitCount, 1);
  }
  std::size_t MemoryInUse() const { return this->State.MemoryInUse(); }
  /// Root mean square, over the premultiplied RGBA of the pixels whose rays meet the data, of the
  /// change to the current image from the image at an earlier power of two of frames (the
  /// largest below the count), blended with the current transfer function; negative until two
  /// frames exist. With first- or higher-order convergence this is about the remaining error of
  /// those pixels, or more; it does not depend on how much of the window the data covers.
  double ErrorEstimate() const { return this->Errors.Value(); }

  /// Pixels whose rays meet the data (those the error estimate is taken over).
  std::size_t PixelsCovered() const { return this->State.CoveredPixels; }
  /// Samples one frame takes over all rays, whole.
  std::size_t SamplesPerFrame() const { return this->State.TotalSamplesPerFrame; }
  /// Samples the frames taken so far keep: each tile's rows (from each ray's front to its
  /// horizon, a few rows before the first front) times its frames.
  std::uint64_t StoredSamples() const { return this->State.StoredSamples(); }
  /// Samples read from the sampler since construction (frames and single passes; not reset).
  std::uint64_t SamplesTaken() const { return this->State.Taken; }
  const SampleEncoding& Encoding() const { return this->State.Encoder; }
  const View& CurrentView() const { return this->State.CurrentViewData; }

private:
  // Identifies the tables and mode a blend reads (the transfer function's, the Set* inputs').
  std::uint64_t BlendKey(const TransferFunctionTable& tf, BlendMode mode) const
  {
    return (tf.Generation() * 1000003u + this->State.Inputs.Generation()) * 16u +
           static_cast<unsigned>(mode);
  }
  // Samples frame Frames of the schedule's pass (from its tile NextTile on, within `seconds`
  // if > 0; see AccumulateFrame) into its slot, then blends their frames [0, Frames] into
  // the image. Returns the next tile.
  std::size_t SampleAndBlend(const TransferFunctionTable& tf, BlendMode mode, double seconds);
  // Blends the first `frames` stored frames of every ray (of `tiles`) into `target`.
  void BlendStored(const TransferFunctionTable& tf, BlendMode mode, int frames, float* target,
    const std::vector<std::size_t>* tiles = nullptr);
  // Blends every tile's own frames into `target`.
  void BlendOwnFrames(const TransferFunctionTable& tf, BlendMode mode, float* target);
  // The error estimate after the image changed in `tiles` (all when null): see
  // ErrorEstimator::Update.
  void UpdateErrorEstimate(const TransferFunctionTable& tf, BlendMode mode,
    const std::vector<std::size_t>* tiles, bool reblended);
  // What TilePasses does to a tile besides blending it.
  enum class TileWork
  {
    Blend,  // blend only; rays cut at a horizon the blend has not made opaque mark the tile
            // for resuming (Tile::Resume)
    Sample, // sample frame frames - 1 first; such rays are sampled whole at once
    Resume  // such rays are sampled whole, then the tile is blended again
  };
  // The two above, per code width: runs on each tile (of `tiles`) the passes `work` asks for,
  // in order: the sampling pass, the blending pass of `frames` frames of every ray into
  // `target`, and the resumption of rays cut at their horizon, then the blending pass again.
  template <typename Code>
  std::size_t TilePasses(const TransferFunctionTable& tf, BlendMode mode, TileWork work, int frames,
    float* target, std::size_t first = 0, double seconds = 0.0,
    const std::vector<std::size_t>* tiles = nullptr);

  FrameState State;
  SamplingPass Sampling{ this->State };
  BlendingPass Blending{ this->State };
  SinglePass Single{ this->State };
  ErrorEstimator Errors{ this->State.Tiles, this->State.Schedule };
  int FrameCount = 0; // see Frames
  bool ShowingSinglePass = false;
  // Whether every tile with frames shows its stored frames blended with the tables and mode of
  // ShownBlend (BlendKey); not after a single pass or a slice replaced the image.
  bool ShownBlendValid = false;
  // The frames counted were a slice or a plain pass, with no samples stored (since Reset).
  bool FramesWithoutSamples = false;
  std::uint64_t ShownBlend = 0;
};

} // namespace savr

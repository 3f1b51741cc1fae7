#pragma once
// The progressive frame loop: per camera, every frame samples each pixel's ray at one new offset,
// keeps the samples, and re-blends all of them; tiles run in parallel on TBB and every pixel is a
// function of its own samples only, so images do not depend on the thread count.

#include "blend/Integrator.h"
#include "frame/CompositeTables.h"
#include "frame/ErrorEstimator.h"
#include "frame/FrameSettings.h"
#include "frame/OffsetSequence.h"
#include "frame/SampleStore.h"
#include "frame/StoredAttributes.h"
#include "frame/Tile.h"
#include "frame/TileSchedule.h"
#include "frame/View.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace savr
{

/// Frames a view can accumulate at most.
constexpr int kMaximumFrames = 1 << 16;
/// A ray never takes more samples than this per frame: longer rays are cut (callers refuse
/// settings that would need more, see vtkSAVRVolumeMapper).
constexpr double kMaxSamplesPerRay = 1 << 22;
/// The first frame samples a ray in pieces of this many rows until it finds the horizon.
constexpr int kHorizonPiece = 32;

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

enum class Phase
{
  Interacting,  // one pass per frame, nothing stored
  Accumulating, // one new offset per frame
  Complete      // every frame taken; re-blend only when the transfer function changes
};

class TilePaths;

class FrameLoop
{
public:
  FrameLoop();
  ~FrameLoop();
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
  void SetClock(Clock clock) { this->Schedule.SetClock(std::move(clock)); }

  /// With a tolerance > 0, a tile whose own error estimate (as ErrorEstimate, over its pixels)
  /// is below it takes no more frames while the others go on (its share of ErrorEstimate stays
  /// what it was when it stopped); a re-blend that raises a tile's estimate to the tolerance or
  /// above resumes it, and tiles behind take frames first until they catch up. Each tile's
  /// pixels are always the blend of its own frames. 0 (the default): every tile takes every
  /// frame. Takes effect at the next frame.
  void SetTileTolerance(double tolerance) { this->Schedule.SetTolerance(tolerance); }
  /// Tiles with rays that take no more frames (SetTileTolerance) before the frame limit.
  std::size_t SettledTiles() const { return this->Schedule.SettledTiles(this->FrameLimitCount); }

  /// Lighting for the blends that follow (composite and single passes); null blends unshaded.
  /// The table must outlive its use. Has effect only with FrameSettings::Shade.
  void SetShading(const ShadingTable* shading) { this->Inputs.Shading = shading; }

  /// Gradient opacity for the composite blends that follow; null for none. Has effect only with
  /// FrameSettings::GradientMagnitudes (the table's scale must be MagnitudeScale) or
  /// ComponentMagnitudes (a set per component, each set's scale its ComponentMagnitudeScales).
  void SetGradientOpacity(const GradientOpacityTable* table)
  {
    this->Inputs.GradientOpacity = table;
  }

  /// Isosurfaces for BlendMode::Isosurface; null draws nothing in that mode.
  void SetIsoSurfaces(const IsoSurfaces* isos) { this->Inputs.Isos = isos; }

  /// The plane BlendMode::Slice draws: a point on it and its normal (not zero), world space.
  void SetSlicePlane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal)
  {
    this->Inputs.SliceOrigin = origin;
    this->Inputs.SliceNormal = normal;
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
  const std::vector<float>& Image() const { return this->Pixels; }

  /// Interacting after a single pass; otherwise Accumulating until the frame limit, then Complete.
  Phase CurrentPhase() const
  {
    return this->ShowingSinglePass ? Phase::Interacting
                                   : (this->Complete() ? Phase::Complete : Phase::Accumulating);
  }

  /// The image as 8-bit premultiplied RGBA (rounded, clamped to [0, 1]), converted in parallel.
  void ImageBytes(std::vector<std::uint8_t>& bytes) { this->ImageBytes(this->Pixels, bytes); }
  /// The same of another image of the view's size that is zero outside ImageRectangle.
  void ImageBytes(const std::vector<float>& image, std::vector<std::uint8_t>& bytes);

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
  void ImageRectangle(int r[4]) const { std::copy(this->Rectangle, this->Rectangle + 4, r); }

  /// The base step in effect: FrameSettings::SampleDistance, or coarser to keep within
  /// MaximumSamplesPerFrame.
  double SampleDistance() const { return this->Settings.SampleDistance; }
  /// Bytes of the budget that are not stored samples, as counted at the last Reset: the images,
  /// the ray tables, the per-thread scratch and the caller's reserved bytes.
  std::size_t FixedBytes() const { return this->Fixed; }
  /// Whether FixedBytes() exceed the budget: then nothing is allocated and nothing drawn.
  bool OverBudget() const { return this->Fixed > this->Settings.MemoryBudget; }

  /// Frames of the tiles that have taken the most.
  int Frames() const { return this->FrameCount; }
  /// Frames that fit the settings and the memory budget (0 when not even one frame fits).
  int FrameLimit() const { return this->FrameLimitCount; }
  /// Whether every tile has taken every frame of the limit (one, a single pass, when none
  /// fits), or is settled (SetTileTolerance).
  bool Complete() const
  {
    const FramePass& pass = this->Schedule.Pass();
    return !pass.Resume && pass.Frames >= std::max(this->FrameLimitCount, 1);
  }
  std::size_t MemoryInUse() const;
  /// Root mean square, over the premultiplied RGBA of the pixels whose rays meet the data, of the
  /// change to the current image from the image at an earlier power of two of frames (the
  /// largest below the count), blended with the current transfer function; negative until two
  /// frames exist. With first- or higher-order convergence this is about the remaining error of
  /// those pixels, or more; it does not depend on how much of the window the data covers.
  double ErrorEstimate() const { return this->Errors.Value(); }

  /// Pixels whose rays meet the data (those the error estimate is taken over).
  std::size_t PixelsCovered() const { return this->CoveredPixels; }
  /// Samples one frame takes over all rays, whole.
  std::size_t SamplesPerFrame() const { return this->TotalSamplesPerFrame; }
  /// Samples the frames taken so far keep: each tile's rows (from each ray's front to its
  /// horizon, a few rows before the first front) times its frames.
  std::uint64_t StoredSamples() const;
  /// Samples read from the sampler since construction (frames and single passes; not reset).
  std::uint64_t SamplesTaken() const { return this->Taken; }
  const SampleEncoding& Encoding() const { return this->Encoder; }
  const View& CurrentView() const { return this->CurrentViewData; }

private:
  // Identifies the tables and mode a blend reads (the transfer function's, the Set* inputs').
  std::uint64_t BlendKey(const TransferFunctionTable& tf, BlendMode mode) const
  {
    return (tf.Generation() * 1000003u + this->Inputs.Generation()) * 16u +
           static_cast<unsigned>(mode);
  }
  template <typename Work>
  void InArena(Work&& work) // in an arena of Settings.Threads threads, if set
  {
    this->Schedule.InArena(std::forward<Work>(work));
  }
  // Runs `body(tile, buffers)` on every tile (of `tiles`, indices, when given) from `first` on,
  // with the thread's buffers, as TileSchedule::ForEach. Returns the next tile.
  template <typename Body>
  std::size_t ForEachTile(Body&& body, std::size_t first = 0, double seconds = 0.0,
    const std::vector<std::size_t>* tiles = nullptr);
  // Samples frame PassFrames of the pass's rays (from its tile NextTile on, within `seconds`
  // if > 0; see AccumulateFrame) into its slot, then blends their frames [0, PassFrames] into
  // the image. Returns the next tile.
  std::size_t SampleAndBlend(const TransferFunctionTable& tf, BlendMode mode, double seconds);
  // Blends the first `frames` stored frames of every ray (of `tiles`) into `target`.
  void BlendStored(const TransferFunctionTable& tf, BlendMode mode, int frames, float* target,
    const std::vector<std::size_t>* tiles = nullptr);
  // What TilePasses does to a tile besides blending it.
  enum class TileWork
  {
    Blend,  // blend only; rays cut at a horizon the blend has not made opaque mark the tile
            // for resuming (Tile::Resume)
    Sample, // sample frame frames - 1 first; such rays are sampled whole at once
    Resume  // such rays are sampled whole, then the tile is blended again
  };
  // The two above, per code width: runs on each tile (of `tiles`) the passes `work` asks for,
  // in order: the sampling pass (SampleTile), the blending pass (BlendTile) of `frames` frames
  // of every ray into `target`, and the resumption of rays cut at their horizon (ResumeRays,
  // then BlendTile again).
  template <typename Code>
  std::size_t TilePasses(const TransferFunctionTable& tf, BlendMode mode, TileWork work, int frames,
    float* target, std::size_t first = 0, double seconds = 0.0,
    const std::vector<std::size_t>* tiles = nullptr);
  // Sizes the offsets for `frames` frames and the opacity cache for their gaps.
  void PrepareBlend(const TransferFunctionTable& tf, int frames);
  template <typename Code>
  void BlendWindowTiles(const TransferFunctionTable& tf, BlendMode mode, const DepthWindow* windows,
    int count, int frames, const std::vector<std::size_t>* tiles);

  using TileGroup = TileSchedule::TileGroup;
  // Blends every tile's own frames into `target`.
  void BlendOwnFrames(const TransferFunctionTable& tf, BlendMode mode, float* target);
  // The error estimate after the image changed in `tiles` (all when null): see
  // ErrorEstimator::Update.
  void UpdateErrorEstimate(const TransferFunctionTable& tf, BlendMode mode,
    const std::vector<std::size_t>* tiles, bool reblended);
  // BlendMode::Slice, whatever the phase: each ray's value where it crosses the slice plane
  // inside the data (and in front of opaque geometry), coloured by the transfer function with
  // its opacity as given, lit by the gradient there when shading. Exact in one frame; nothing
  // is stored.
  void RenderSlice(const TransferFunctionTable& tf);
  // RenderSinglePass's pass over the tiles from `first` on (of `tiles`, all when null).
  void SinglePassTiles(const TransferFunctionTable& tf, BlendMode mode, double step, double offset,
    const PassOptions& options, std::size_t first, const std::vector<std::size_t>* tiles);
  // Whether frames take gradients (shading or gradient opacity).
  bool NeedsGradients() const
  {
    return this->Source && (this->Settings.Shade || this->Settings.GradientMagnitudes ||
                             this->Settings.ComponentMagnitudes);
  }
  // Has the sampler compute what its gradients rest on, if frames take gradients: called
  // serially before a frame's or pass's tiles start, the work itself parallel with the frame's
  // threads, once per data change (see Sampler::PrepareGradients).
  void PrepareGradients();
  // Room for `capacity` slots per row in every tile's stores, keeping the frames they hold; none
  // is allocated before a tile's first frame (SampleTile lays its rows out then).
  void Grow(int capacity);
  // The stores the view's frames fill.
  StoreLayout CurrentStoreLayout() const;
  // Rays of every pixel of the rectangle that meets the data (lengths only, no samples yet).
  void FindRays();
  // Coarsens the step (and multiplies the frames) to keep within MaximumSamplesPerFrame.
  void LimitSamplesPerFrame();
  // Samples per frame, rows and stores of every ray at the step in effect; the most samples
  // any ray takes.
  int LayOutRays();
  // Bytes that do not depend on the rays' samples (images, ray tables, reserved bytes, and the
  // sampler's gradients while frames take them).
  std::size_t ViewBytes() const;
  // Frees everything held for the view.
  void Release();
  // The pixel's rotation in units of `step`, in [0, 1) (see FrameSettings::PhaseLength).
  double RotationOf(int x, int y, double step) const;

  // What a frame stores besides the codes, and the tables the blends read it with.
  using Attributes = StoredAttributes;
  Attributes CurrentAttributes() const;
  struct Buffers;
  // A chunk of `count` samples of a single pass from t0 on, sampled into the buffers' Values
  // (and SecondCodes, with second codes): their codes into Codes, and into Attributes each one's
  // normal and magnitude codes where the pass sees it (kNoNormal elsewhere), from the
  // gradients of the run between the first sample it sees and the last, asked for at once.
  void SinglePassChunk(const TransferFunctionTable& tf, BlendMode mode,
    const Attributes& attributes, const Ray& r, double t0, double step, int count,
    std::uint32_t nanCode, Buffers& buffers) const;
  template <typename Code>
  struct StoredRows; // a ray's rows in a tile's stores

  // Gives each tile its share of what the memory budget leaves for paths (Sampler::TracePath)
  // once the stored samples have theirs, or none when paths would not be read again.
  void SharePathBudget(std::size_t storedBytes);
  // Flags the sampler's blocks that `tf` makes transparent; false when nothing can be skipped.
  // `nanCode` becomes a transparent code that skipped (NaN) samples are stored as.
  bool TransparentBlocks(
    const TransferFunctionTable& tf, std::vector<std::uint8_t>& skip, std::uint32_t& nanCode) const;

  struct Scratch;

  // The sampling pass (FrameSampling.cxx).
  // Samples `count` rows of frame `slot` of `ray` (its line `r`, its offsets rotated by
  // `rotation`, this frame's `u`) from row `firstRow` on into that slot of `rows` (which start at
  // that row); along the ray's path in `paths` (the ray's index there `index`) when given,
  // traced first if the ray has not been.
  template <typename Code>
  void SampleNewFrame(const RayInfo& ray, const Ray& r, double rotation, double u,
    const StoredRows<Code>& rows, const Attributes& attributes, bool vectorEncode, TilePaths* paths,
    std::size_t index, Buffers& buffers, int slot, int count, int firstRow) const;
  // The first `count` values of a frame of `ray` (`r`, from `start`; its offsets rotated by
  // `rotation`) into buffers.Values, along its path in `paths` where it has one.
  void SampleValues(const RayInfo& ray, const Ray& r, double start, double rotation,
    TilePaths* paths, std::size_t index, Buffers& buffers, int count) const;
  // Encodes the `count` values in `buffers` (room for `padded`) into slot `slot` of `rows`.
  template <typename Code>
  void FileCodes(int count, std::size_t padded, const StoredRows<Code>& rows, bool vectorEncode,
    Buffers& buffers, int slot) const;
  // The sampling pass of a tile: frame PassFrames of each of its rays into its slot (along the
  // rays' paths when `alongPaths`), up to each ray's horizon; with `horizons` (the blend's
  // extinction per code, see HorizonsApply), the first frame samples each ray until its own
  // samples have made it opaque and sets the horizon there; with `fronts` (the blocks that
  // function makes transparent), it first sets each ray's front (FrontOf) and samples from there.
  template <typename Code>
  void SampleTile(Tile& tile, Buffers& buffers, const Attributes& attributes, bool vectorEncode,
    bool alongPaths, const TransferFunctionTable* horizons, const SkipMask* fronts);
  // The rows of `ray` (its line `r`) that hold only samples in blocks `skip` flags, less one:
  // the first row of any frame's samples that a blend may need to read.
  int FrontOf(const RayInfo& ray, const Ray& r, const SkipMask& skip) const;
  // The first row from which on every row of `ray` holds only samples in blocks `skip` flags and
  // no blend needs it (one past the last sample that may not be, and the sample after that),
  // at least `front`.
  int BackOf(const RayInfo& ray, const Ray& r, const SkipMask& skip, int front) const;
  // Whether composite frames may start rays at a front: point-sampled composites whose
  // horizons apply (a transparent sample then adds nothing, whatever its interval).
  bool FrontsApply(
    const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes) const;
  // Whether the rays' fronts hold for `tf` and `mode`: every block transparent when they were
  // set is transparent still. (True when no ray has a front.)
  bool FrontsHold(const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes);
  // Whether composite frames (point sampled or pre-integrated) may end rays at their opacity
  // horizon: the transfer function's extinction per code is the sample's (no gradient opacity,
  // no second codes).
  bool HorizonsApply(
    const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes) const;
  // After a tile's blend into `target`: whether a ray is cut at a horizon that the blend of its
  // frames has not made opaque there (or at all, when horizons do not apply), or starts at a
  // front that does not hold (`frontsHold`), and, with `sample`, each such ray samples the rest
  // of every frame it has taken (`taken`). Returns whether any ray is (was) such.
  template <typename Code>
  bool ResumeRays(Tile& tile, Buffers& buffers, const Attributes& attributes, bool vectorEncode,
    bool alongPaths, int taken, const float* target, bool horizonsApply, bool frontsHold,
    bool sample);

  // The blending pass (FrameBlending.cxx).
  // The plain stored composite's interval tables for `frames` frames: each sorted offset's
  // (null when it has none). False, with no tables, when the blend is not plain (composite
  // without gradient opacity, second codes or component terms; lit or not).
  bool PlainIntervalTables(const TransferFunctionTable& tf, BlendMode mode, int frames,
    const Attributes& attributes, std::vector<const double*>& sortedTables);
  // What the blending pass of every tile of a frame shares (see TilePasses).
  template <typename Code>
  struct TileBlend;
  // The blending pass of a tile: the first Frames stored frames of each of its rays into the
  // pixels.
  template <typename Code>
  void BlendTile(Tile& tile, Buffers& buffers, const TileBlend<Code>& blend) const;

  // What the blends read besides the codes and the transfer function (the Set* calls).
  struct BlendInputs
  {
    const ShadingTable* Shading = nullptr;
    const GradientOpacityTable* GradientOpacity = nullptr;
    const IsoSurfaces* Isos = nullptr;
    Eigen::Vector3d SliceOrigin = Eigen::Vector3d::Zero();
    Eigen::Vector3d SliceNormal = Eigen::Vector3d::UnitZ();
    // Identifies the shading, gradient-opacity and isosurface tables in use (0 for none).
    std::uint64_t Generation() const
    {
      const std::uint64_t shading = this->Shading ? this->Shading->Generation() : 0;
      const std::uint64_t opacity = this->GradientOpacity ? this->GradientOpacity->Generation() : 0;
      const std::uint64_t isos = this->Isos ? this->Isos->Generation : 0;
      return (shading * 1000003u + opacity) * 1000003u + isos;
    }
  };
  // The blocks transparent to the transfer function the rays' fronts were set with (empty when
  // none was), and whether they still are to the one last checked (FrontsHold).
  struct FrontBlocks
  {
    std::vector<std::uint8_t> Set;
    std::uint64_t Checked = 0; // that function's generation
    BlendMode CheckedMode = BlendMode::Composite;
    bool Hold = true;
  };

  View CurrentViewData;
  std::shared_ptr<const Sampler> Source;
  FrameSettings Settings;
  SampleEncoding Encoder;
  OffsetSequence Offsets;
  AlphaCache Alphas;
  AlphaCache WindowAlphas; // for blends of parts of rays, whose intervals are not tabulated
  std::vector<Tile> Tiles;
  TileSchedule Schedule{ this->Tiles }; // which tiles a frame's pass takes, and how they run
  std::vector<float> Pixels;
  int Rectangle[4] = { 0, 0, 0, 0 }; // see ImageRectangle
  std::unique_ptr<Scratch> ThreadScratch;
  std::size_t TotalSamplesPerFrame = 0;
  std::size_t CoveredPixels = 0; // pixels whose rays meet the data
  int FrameCount = 0;            // see Frames
  int FrameLimitCount = 0;       // see FrameLimit
  int Capacity = 0;
  std::size_t Fixed = 0; // see FixedBytes
  bool ShowingSinglePass = false;
  // Whether every tile with frames shows its stored frames blended with the tables and mode of
  // ShownBlend (BlendKey); not after a single pass or a slice replaced the image.
  bool ShownBlendValid = false;
  // The frames counted were a slice or a plain pass, with no samples stored (since Reset).
  bool FramesWithoutSamples = false;
  std::uint64_t ShownBlend = 0;
  std::uint64_t Taken = 0;
  BlendInputs Inputs;
  ErrorEstimator Errors{ this->Tiles, this->Schedule };
  FrontBlocks Fronts;
  CompositeTables Tables; // the composite's fast paths' tables
};

} // namespace savr

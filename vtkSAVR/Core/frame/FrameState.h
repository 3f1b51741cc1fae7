#pragma once
// What a view's frames and passes share: the view and its rays in tiles, the sampler, the
// settings in effect, the sample encoding and the frames' offsets, the image, the blend inputs
// and the per-thread scratch; laid out for each view by Reset, within the memory budget.

#include "blend/BlendTypes.h"
#include "blend/ShadingTable.h"
#include "blend/TransferFunctionTable.h"
#include "encoding/SampleEncoding.h"
#include "encoding/StoredAttributes.h"
#include "frame/FrameSettings.h"
#include "frame/OffsetSequence.h"
#include "frame/Tile.h"
#include "frame/TileSchedule.h"
#include "frame/View.h"
#include "sampler/Sampler.h"

#include <cstddef>
#include <cstdint>
#include <memory>
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

/// What the blends read besides the codes and the transfer function (FrameLoop's Set* calls).
struct BlendInputs
{
  const ShadingTable* Shading = nullptr;
  const GradientOpacityTable* GradientOpacity = nullptr;
  const IsoSurfaces* Isos = nullptr;
  Eigen::Vector3d SliceOrigin = Eigen::Vector3d::Zero();
  Eigen::Vector3d SliceNormal = Eigen::Vector3d::UnitZ();
  /// Identifies the shading, gradient-opacity and isosurface tables in use (0 for none).
  std::uint64_t Generation() const
  {
    const std::uint64_t shading = this->Shading ? this->Shading->Generation() : 0;
    const std::uint64_t opacity = this->GradientOpacity ? this->GradientOpacity->Generation() : 0;
    const std::uint64_t isos = this->Isos ? this->Isos->Generation : 0;
    return (shading * 1000003u + opacity) * 1000003u + isos;
  }
};

struct ThreadBuffers; // a thread's buffers (PassScratch.h)
struct ThreadScratch; // every thread's

class FrameState
{
public:
  FrameState();
  ~FrameState();
  FrameState(const FrameState&) = delete;
  FrameState& operator=(const FrameState&) = delete;

  /// Forgets the last view's samples and lays out the rays of `view` through `sampler`: the
  /// step in effect (coarsened to keep within MaximumSamplesPerFrame), the rays' rows, and the
  /// frames the memory budget leaves room for (FrameLimitCount). Nothing is allocated when the
  /// view's own buffers exceed the budget (OverBudget).
  void Reset(
    const View& view, std::shared_ptr<const Sampler> sampler, const FrameSettings& settings);

  /// Whether the view's buffers alone exceed the budget.
  bool OverBudget() const { return this->Fixed > this->Settings.MemoryBudget; }
  /// Whether frames take gradients (shading or gradient opacity).
  bool NeedsGradients() const
  {
    return this->Source && (this->Settings.Shade || this->Settings.GradientMagnitudes ||
                             this->Settings.ComponentMagnitudes);
  }
  /// Has the sampler compute what its gradients rest on, if frames take gradients: called
  /// serially before a frame's or pass's tiles start, the work itself parallel with the frame's
  /// threads, once per data change (see Sampler::PrepareGradients).
  void PrepareGradients();
  /// What a frame stores besides the codes, and the tables the blends read it with.
  StoredAttributes CurrentAttributes() const;
  /// The stores the view's frames fill.
  StoreLayout CurrentStoreLayout() const;
  /// The pixel's rotation in units of `step`, in [0, 1) (see FrameSettings::PhaseLength).
  double RotationOf(int x, int y, double step) const;
  /// Flags the sampler's blocks that `tf` makes transparent; false when nothing can be skipped.
  /// `nanCode` becomes a transparent code that skipped (NaN) samples are stored as.
  bool TransparentBlocks(
    const TransferFunctionTable& tf, std::vector<std::uint8_t>& skip, std::uint32_t& nanCode) const;

  /// Runs `work` in an arena of Settings.Threads threads, if set.
  template <typename Work>
  void InArena(Work&& work)
  {
    this->Schedule.InArena(std::forward<Work>(work));
  }
  /// Runs `body(tile, buffers)` on every tile (of `tiles`, indices, when given) from `first` on,
  /// with the thread's buffers, as TileSchedule::ForEach. Returns the next tile. (Defined in
  /// PassScratch.h.)
  template <typename Body>
  std::size_t ForEachTile(Body&& body, std::size_t first = 0, double seconds = 0.0,
    const std::vector<std::size_t>* tiles = nullptr);

  /// Room for `capacity` slots per row in every tile's stores, keeping the first `frames`;
  /// none is allocated before a tile's first frame (the sampling pass lays its rows out then).
  void Grow(int capacity, int frames);
  /// Bytes the tiles' stores and paths hold.
  std::size_t MemoryInUse() const;
  /// Samples the tiles' stores keep: each tile's rows times its frames.
  std::uint64_t StoredSamples() const;

  View CurrentViewData;
  std::shared_ptr<const Sampler> Source;
  FrameSettings Settings; // as in effect: the step coarsened, the frames multiplied
  SampleEncoding Encoder;
  OffsetSequence Offsets;
  std::vector<Tile> Tiles;
  TileSchedule Schedule{ this->Tiles }; // which tiles a frame's pass takes, and how they run
  std::vector<float> Pixels;            // the image: premultiplied RGBA, rows from the bottom
  int Rectangle[4] = { 0, 0, 0, 0 };    // the pixels whose rays can meet the data
  BlendInputs Inputs;
  std::unique_ptr<ThreadScratch> Scratch;
  std::size_t TotalSamplesPerFrame = 0;
  std::size_t CoveredPixels = 0; // pixels whose rays meet the data
  int FrameLimitCount = 0;       // frames that fit the settings and the budget
  int Capacity = 0;              // slots per row of the stores
  std::size_t Fixed = 0;         // bytes of the budget that are not stored samples
  std::uint64_t Taken = 0;       // samples read from the sampler since construction

private:
  // Rays of every pixel of the rectangle that meets the data (lengths only, no samples yet).
  void FindRays();
  // Coarsens the step (and multiplies the frames) to keep within MaximumSamplesPerFrame.
  void LimitSamplesPerFrame();
  // Samples per frame, rows and stores of every ray at the step in effect; the most samples
  // any ray takes.
  int LayOutRays();
  // The frames the budget leaves room for, once the per-thread scratch for rays of
  // `longestRay` samples is counted.
  void LimitFrames(std::size_t longestRay);
  // Bytes that do not depend on the rays' samples (images, ray tables, reserved bytes, and the
  // sampler's gradients while frames take them).
  std::size_t ViewBytes() const;
  // Frees everything held for the view.
  void Release();
  // Gives each tile its share of what the memory budget leaves for paths (Sampler::TracePath)
  // once the stored samples have theirs, or none when paths would not be read again.
  void SharePathBudget(std::size_t storedBytes);
};

} // namespace savr

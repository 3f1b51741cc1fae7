#pragma once
// The sampling pass of a frame: each ray of a tile sampled at the frame's offset, the values
// encoded and filed into the frame's slot of the tile's stores (along the ray's recorded path
// where it has one); the first frame up to each ray's opacity horizon, from its front to its
// back; and the rays a blend finds cut short, sampled whole again.

#include "blend/TransferFunctionTable.h"
#include "frame/FrameState.h"
#include "frame/StoredRows.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace savr
{

class SamplingPass
{
public:
  /// Samples the view of `state`, which outlives the pass.
  explicit SamplingPass(FrameState& state)
    : State(state)
  {
  }

  /// Whether composite frames (point sampled or pre-integrated) may end rays at their opacity
  /// horizon: the transfer function's extinction per code is the sample's (no gradient opacity,
  /// no second codes).
  bool HorizonsApply(
    const TransferFunctionTable& tf, BlendMode mode, const StoredAttributes& attributes) const;
  /// Whether composite frames may start rays at a front: point-sampled composites whose
  /// horizons apply (a transparent sample then adds nothing, whatever its interval).
  bool FrontsApply(
    const TransferFunctionTable& tf, BlendMode mode, const StoredAttributes& attributes) const;
  /// No ray has a front.
  void ForgetFronts() { this->Fronts = FrontBlocks(); }
  /// Before a view's first frame: the blocks `tf` makes transparent in `mode` (`blocks`, empty
  /// when none) are those the rays' fronts are set by.
  void SetFronts(
    const std::vector<std::uint8_t>& blocks, const TransferFunctionTable& tf, BlendMode mode);
  /// Whether the rays' fronts hold for `tf` and `mode`: every block transparent when they were
  /// set is transparent still. (True when no ray has a front.)
  bool FrontsHold(
    const TransferFunctionTable& tf, BlendMode mode, const StoredAttributes& attributes);

  /// The sampling pass of a tile: the frame in the schedule's pass (its Frames) of each of its
  /// rays into that slot (along the rays' paths when `alongPaths`), up to each ray's horizon;
  /// with `horizons` (the blend's extinction per code, see HorizonsApply), the first frame
  /// samples each ray until its own samples have made it opaque and sets the horizon there;
  /// with `fronts` (the blocks that function makes transparent), it first sets each ray's front
  /// (FrontOf) and samples from there.
  template <typename Code>
  void SampleTile(Tile& tile, ThreadBuffers& buffers, const StoredAttributes& attributes,
    bool vectorEncode, bool alongPaths, const TransferFunctionTable* horizons,
    const SkipMask* fronts);
  /// After a tile's blend into `target`: whether a ray is cut at a horizon that the blend of its
  /// frames has not made opaque there (or at all, when horizons do not apply), or starts at a
  /// front that does not hold (`frontsHold`), and, with `sample`, each such ray samples the rest
  /// of every frame it has taken (`taken`). Returns whether any ray is (was) such.
  template <typename Code>
  bool ResumeRays(Tile& tile, ThreadBuffers& buffers, const StoredAttributes& attributes,
    bool vectorEncode, bool alongPaths, int taken, const float* target, bool horizonsApply,
    bool frontsHold, bool sample);

private:
  using Attributes = StoredAttributes;
  using Buffers = ThreadBuffers;

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
  // The rows of `ray` (its line `r`) that hold only samples in blocks `skip` flags, less one:
  // the first row of any frame's samples that a blend may need to read.
  int FrontOf(const RayInfo& ray, const Ray& r, const SkipMask& skip) const;
  // The first row from which on every row of `ray` holds only samples in blocks `skip` flags and
  // no blend needs it (one past the last sample that may not be, and the sample after that),
  // at least `front`.
  int BackOf(const RayInfo& ray, const Ray& r, const SkipMask& skip, int front) const;

  // The blocks transparent to the transfer function the rays' fronts were set with (empty when
  // none was), and whether they still are to the one last checked (FrontsHold).
  struct FrontBlocks
  {
    std::vector<std::uint8_t> Set;
    std::uint64_t Checked = 0; // that function's generation
    BlendMode CheckedMode = BlendMode::Composite;
    bool Hold = true;
  };

  FrameState& State;
  FrontBlocks Fronts;
};

} // namespace savr

#pragma once
// The stores that keep a tile's rays' samples between frames: the codes and each attribute a
// view stores (normals, gradient magnitudes, per-component ones, second codes), rows of every
// ray one after another, a slot per frame in each row. Which rows a ray keeps (its front to its
// horizon), how the stores grow as frames accumulate, and what that costs in memory.

#include "frame/SampleStore.h"

#include <cstddef>
#include <cstdint>
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
  /// pass through transparent (its front; SamplingPass::FrontsHold). Frames sample rows
  /// [Front, Horizon).
  int Front;
  /// FrameState::RotationOf its pixel at the loop's step: its frames' offsets are rotated by it.
  double Rotation;
  /// Rows from it on are not sampled either: past the last block the ray meets that the first
  /// frame's function does not make transparent (its back; SamplesPerFrame when none). The
  /// horizon lies at the back or before it.
  int Back;

  /// Whether the ray keeps no rows: the first frame's function makes every block it meets
  /// transparent, and its composite is empty.
  bool KeepsNoRows() const { return this->Horizon <= this->Front; }
};

/// Which stores a view's frames fill, besides the codes, and the codes' bytes.
struct StoreLayout
{
  int CodeBytes = 1;
  bool Normals = false;             // 2 bytes: when shading
  bool ComponentNormals = false;    // 8 bytes: when shading independent components
  bool Magnitudes = false;          // 1 byte: with gradient opacity
  bool ComponentMagnitudes = false; // 4 bytes: with independent components' gradient opacity
  bool SecondCodes = false;         // 2 bytes: when the sampler has second codes

  /// Bytes one stored sample takes over every store.
  std::size_t BytesPerSample() const;
};

class RayStores
{
public:
  SampleStore Codes;
  SampleStore Normals;
  SampleStore Magnitudes;
  SampleStore ComponentNormals;
  SampleStore ComponentMagnitudes;
  SampleStore SecondCodes;

  /// Sets the stores `layout` uses to `rows` rows with `capacity` slots (none allocated at 0),
  /// the others to none; with `reuse`, keeping the memory they have where it is enough (for
  /// scratch stores laid out again and again).
  void Lay(const StoreLayout& layout, std::size_t rows, int capacity, bool reuse = false);
  /// Frees every store.
  void Free();
  /// Room for `capacity` slots per row in every store, keeping the first `frames` slots.
  void Grow(int capacity, int frames);
  /// Rows of the codes' store.
  std::size_t RowCount() const { return this->Codes.RowCount(); }
  /// Bytes allocated over every store.
  std::size_t MemoryInUse() const;

  /// After a first frame was sampled into `sampled` (whole rows of one slot, each ray's rows
  /// from its FirstRow): these stores laid out with `capacity` slots, each of `rays` keeping its
  /// rows from its front to its horizon only, that frame's codes in (FirstRow set anew).
  void KeepRows(
    std::vector<RayInfo>& rays, const RayStores& sampled, const StoreLayout& layout, int capacity);
  /// Lays these stores (with `capacity` slots) out anew, the rays `whole` flags with whole rows
  /// (their front at 0, their back at the end), the others keeping their rows and codes;
  /// `scratch` holds the old stores meanwhile and is freed.
  void RelayWholeRays(std::vector<RayInfo>& rays, const std::vector<char>& whole,
    RayStores& scratch, const StoreLayout& layout, int capacity);

  /// The capacity the stores grow to after `capacity` (four times, never past `limit`), and the
  /// most slots per row they hold while growing to `limit` (old and new blocks side by side).
  static int NextCapacity(int capacity, int limit);
  static std::size_t PeakSlots(int limit);

private:
  // Calls f(store, its counterpart in `other`) for each store.
  template <typename Other, typename F>
  void EachStore(Other& other, F&& f);
};

} // namespace savr

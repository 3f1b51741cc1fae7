// The sampling pass of a frame (see SamplingPass.h).

#include "frame/SamplingPass.h"

#include "blend/StoredAVX2.h"
#include "encoding/EncodeAVX2.h"
#include "frame/PassScratch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace savr
{

template <typename Code>
void SamplingPass::SampleNewFrame(const RayInfo& ray, const Ray& r, double rotation, double u,
  const StoredRows<Code>& rows, const Attributes& attributes, bool vectorEncode, TilePaths* paths,
  std::size_t index, Buffers& buffers, int slot, int count, int firstRow) const
{
  const std::size_t capacity = static_cast<std::size_t>(rows.Capacity);
  const double dt = this->State.Settings.SampleDistance;
  const Sampler& source = *this->State.Source;
#if defined(__GNUC__)
  // The ray's stored rows are about to be written, one byte of each line at a time:
  // ask for them now, so that fetching them overlaps the sampling.
  const char* bytes = reinterpret_cast<const char*>(rows.Codes);
  const std::size_t rowBytes = static_cast<std::size_t>(count) * capacity * sizeof(Code);
  for (std::size_t b = 0; b < rowBytes; b += 64)
  {
    __builtin_prefetch(bytes + b, 1, 3);
  }
#endif
  const double start = ray.TEnter + (firstRow + u) * dt;
  // Room for whole groups of four: values are encoded four at a time, and the codes of
  // the values past the ray's (whatever they hold) are not used.
  const std::size_t padded = (static_cast<std::size_t>(count) + 3) & ~std::size_t(3);
  buffers.Values.resize(padded);
  if (attributes.Normals || attributes.Magnitudes)
  {
    const bool normalsOnly = vectorEncode && rows.Normals && !rows.Magnitudes;
    if (normalsOnly)
    {
      buffers.Normals.resize(count);
    }
    if (!normalsOnly || !source.SampleRayNormals(
                          r, start, dt, count, buffers.Values.data(), buffers.Normals.data()))
    {
      buffers.Gradients.resize(3 * static_cast<std::size_t>(count));
      source.SampleRayGradients(
        r, start, dt, count, buffers.Values.data(), buffers.Gradients.data());
      if (normalsOnly)
      {
        // Encoded four at a time (the same codes as Encode).
        detail::EncodeNormalsAVX2(buffers.Gradients.data(), count, buffers.Normals.data());
      }
    }
    if (normalsOnly)
    {
      for (int j = 0; j < count; ++j)
      {
        rows.Normals[static_cast<std::size_t>(j) * capacity + slot] = buffers.Normals[j];
      }
    }
    else
    {
      for (int j = 0; j < count; ++j)
      {
        const SampleAttributes a =
          attributes.Encode(&buffers.Gradients[3 * static_cast<std::size_t>(j)]);
        const std::size_t k = static_cast<std::size_t>(j) * capacity + slot;
        if (rows.Normals)
        {
          rows.Normals[k] = NormalOf(a);
        }
        if (rows.Magnitudes)
        {
          rows.Magnitudes[k] = static_cast<std::uint8_t>(MagnitudeOf(a));
        }
      }
    }
  }
  else
  {
    this->SampleValues(ray, r, start, rotation, paths, index, buffers, count);
  }
  if (attributes.AnyComponents())
  {
    buffers.ComponentGradients.resize(12 * static_cast<std::size_t>(count));
    source.ComponentGradientsAlongRay(
      r, start, dt, 0, count - 1, buffers.Values.data(), buffers.ComponentGradients.data());
    for (int j = 0; j < count; ++j)
    {
      const std::size_t k = static_cast<std::size_t>(j) * capacity + slot;
      const float* gradients = &buffers.ComponentGradients[12 * static_cast<std::size_t>(j)];
      if (rows.ComponentNormals)
      {
        rows.ComponentNormals[k] = Attributes::ComponentNormalCodes(gradients);
      }
      if (rows.ComponentMagnitudes)
      {
        rows.ComponentMagnitudes[k] = attributes.ComponentMagnitudeCodes(gradients);
      }
    }
  }
  if (rows.SecondCodes)
  {
    buffers.SecondCodes.resize(count);
    source.SampleRaySecond(r, start, dt, count, buffers.SecondCodes.data());
    for (int j = 0; j < count; ++j)
    {
      const std::uint16_t second = buffers.SecondCodes[j];
      rows.SecondCodes[static_cast<std::size_t>(j) * capacity + slot] = second;
      if (second == kNoSecondCode)
      {
        buffers.Values[j] = std::numeric_limits<float>::quiet_NaN();
      }
    }
  }
  this->FileCodes(count, padded, rows, vectorEncode, buffers, slot);
}

void SamplingPass::SampleValues(const RayInfo& ray, const Ray& r, double start, double rotation,
  TilePaths* paths, std::size_t index, Buffers& buffers, int count) const
{
  const double dt = this->State.Settings.SampleDistance;
  const Sampler& source = *this->State.Source;
  float* values = buffers.Values.data();
  if (!paths || !paths->Active())
  {
    source.SampleRay(r, start, dt, count, values);
    return;
  }
  const double traceStart = ray.TEnter + (rotation - 1.0) * dt;
  std::size_t pieces = 0;
  const PathPiece* path = nullptr;
  if (paths->Untraced(index))
  {
    // Every frame's samples lie in [TEnter, TEnter + SamplesPerFrame dt), on the lattice of
    // the frames' rotated offsets, which starts a step before TEnter.
    buffers.Path.clear();
    const bool traced = source.TracePath(r, traceStart, ray.TEnter + ray.SamplesPerFrame * dt,
      dt * OffsetSequence::SmallestGap(this->State.FrameLimitCount), TilePaths::kMaxPieces,
      buffers.Path);
    paths->Keep(index, buffers.Path, traced);
    path = paths->Path(index, pieces);
    if (!path && traced)
    {
      // Over the tile's share: read this once, and walk again in later frames.
      path = buffers.Path.data();
      pieces = buffers.Path.size();
    }
  }
  else
  {
    path = paths->Path(index, pieces);
  }
  if (path)
  {
    source.SampleAlongPath(r, path, pieces, traceStart, start, dt, count, values);
  }
  else
  {
    source.SampleRay(r, start, dt, count, values);
  }
}

template <typename Code>
void SamplingPass::FileCodes(int count, std::size_t padded, const StoredRows<Code>& rows,
  bool vectorEncode, Buffers& buffers, int newSlot) const
{
  // Into the new slot of every row. (Locals, so that the byte stores, which may alias
  // anything, do not make the compiler read these again each time.)
  const SampleEncoding& encoding = this->State.Encoder;
  const int capacity = rows.Capacity;
  const std::size_t stride = static_cast<std::size_t>(capacity);
  Code* codes = rows.Codes;
  Code* slot = codes + newSlot;
  if (vectorEncode)
  {
    const std::uint32_t nonFinite = encoding.HasNaNCode ? encoding.NaNCode : 0u;
    buffers.Codes.resize(padded);
    const std::uint32_t* encoded = buffers.Codes.data();
    detail::EncodeAVX2(encoding.Offset, encoding.Scale, encoding.Levels, nonFinite, nonFinite,
      buffers.Values.data(), static_cast<int>(padded), buffers.Codes.data());
    if (sizeof(Code) == 1 && capacity == 4)
    {
      detail::FileInSlotOfFour(reinterpret_cast<std::uint8_t*>(codes), newSlot, encoded, count);
    }
    else if (capacity == 1)
    {
      // One slot per row: the rows are the codes, narrowed (a loop the compiler
      // vectorizes).
      for (int j = 0; j < count; ++j)
      {
        codes[j] = static_cast<Code>(encoded[j]);
      }
    }
    else
    {
      for (int j = 0; j < count; ++j)
      {
        slot[j * stride] = static_cast<Code>(encoded[j]);
      }
    }
  }
  else
  {
    const float* values = buffers.Values.data();
    for (int j = 0; j < count; ++j)
    {
      slot[j * stride] = static_cast<Code>(encoding.Encode(values[j]));
    }
  }
}

int SamplingPass::FrontOf(const RayInfo& ray, const Ray& r, const SkipMask& skip) const
{
  // Every frame's samples lie from a step before the entry on (see SampleValues), a sample at t
  // in row floor((t - TEnter) / dt). The ray's points before the entry of the first block that
  // is not skipped all lie in skipped blocks, which the transfer function makes transparent.
  const double dt = this->State.Settings.SampleDistance;
  const double entry = this->State.Source->FirstUnskippedAt(
    r, ray.TEnter - dt, ray.TEnter + (ray.SamplesPerFrame + 1.0) * dt, &skip);
  // Rows before that entry's hold only skipped samples. The row before it is kept too: its
  // samples bound the intervals of the first that may not be (and a sample a rounding away
  // from the entry lies in one of the two).
  const double row = std::floor((entry - ray.TEnter) / dt) - 1.0;
  return static_cast<int>(std::max(0.0, std::min(row, double(ray.SamplesPerFrame))));
}

int SamplingPass::BackOf(const RayInfo& ray, const Ray& r, const SkipMask& skip, int front) const
{
  // The same walk as FrontOf's, from past the last row back towards the entry: the ray's points
  // after the exit of the last block that is not skipped all lie in skipped blocks.
  if (front >= ray.SamplesPerFrame)
  {
    return front; // every row skipped: nothing to walk back from
  }
  const double dt = this->State.Settings.SampleDistance;
  const double end = ray.TEnter + (ray.SamplesPerFrame + 1.0) * dt;
  const double length = end - (ray.TEnter - dt);
  Ray back;
  back.Origin = r.At(end);
  back.Direction = -r.Direction;
  const double exit = end - this->State.Source->FirstUnskippedAt(back, 0.0, length, &skip);
  // A sample before that exit lies in row floor((exit - TEnter) / dt) or (by a rounding) the one
  // after; the sample after it, in the next row at most.
  const double row = std::floor((exit - ray.TEnter) / dt) + 3.0;
  return static_cast<int>(std::max(double(front), std::min(row, double(ray.SamplesPerFrame))));
}

bool SamplingPass::FrontsApply(
  const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes) const
{
  return mode == BlendMode::Composite && this->HorizonsApply(tf, mode, attributes);
}

void SamplingPass::SetFronts(
  const std::vector<std::uint8_t>& blocks, const TransferFunctionTable& tf, BlendMode mode)
{
  this->Fronts = FrontBlocks();
  if (!blocks.empty())
  {
    this->Fronts.Set = blocks;
    this->Fronts.Checked = tf.Generation();
    this->Fronts.CheckedMode = mode;
  }
}

bool SamplingPass::FrontsHold(
  const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes)
{
  FrontBlocks& fronts = this->Fronts;
  if (fronts.Set.empty())
  {
    return true;
  }
  if (!this->FrontsApply(tf, mode, attributes))
  {
    return false;
  }
  if (fronts.Checked != tf.Generation() || fronts.CheckedMode != mode)
  {
    std::vector<std::uint8_t> now;
    std::uint32_t nanCode = 0;
    fronts.Hold =
      this->State.TransparentBlocks(tf, now, nanCode) && now.size() == fronts.Set.size();
    for (std::size_t b = 0; fronts.Hold && b < now.size(); ++b)
    {
      fronts.Hold = fronts.Set[b] == 0 || now[b] != 0;
    }
    fronts.Checked = tf.Generation();
    fronts.CheckedMode = mode;
  }
  return fronts.Hold;
}

template <typename Code>
void SamplingPass::SampleTile(Tile& tile, Buffers& buffers, const Attributes& attributes,
  bool vectorEncode, bool alongPaths, const TransferFunctionTable* horizons, const SkipMask* fronts)
{
  const int slot = this->State.Schedule.Pass().Frames;
  const int width = this->State.CurrentViewData.Width;
  const double dt = this->State.Settings.SampleDistance;
  const double base = this->State.Offsets.Offset(slot);
  const bool hasSecondCodes = this->State.Source->HasSecondCode();
  const double horizonDepth = -std::log(0.01 * this->State.Settings.StopTransmittance());
  TilePaths* paths = alongPaths && tile.Paths.Active() ? &tile.Paths : nullptr;
  // The first frame lays the tile's rows out: whole rays; or, with horizons, whole rows of one
  // slot in scratch first, of which each ray keeps those from its front to its horizon.
  RayStores* into = &tile.Stores;
  const StoreLayout layout = this->State.CurrentStoreLayout();
  if (slot == 0)
  {
    std::size_t whole = 0;
    for (RayInfo& ray : tile.Rays)
    {
      ray.FirstRow = whole;
      whole += static_cast<std::size_t>(ray.SamplesPerFrame);
      ray.Horizon = ray.SamplesPerFrame;
      ray.Front = 0;
      ray.Back = ray.SamplesPerFrame;
    }
    if (horizons)
    {
      buffers.Relaid.Lay(layout, whole, 1, true);
      into = &buffers.Relaid;
    }
    else
    {
      tile.Stores.Lay(layout, whole, this->State.Capacity);
    }
  }
  for (std::size_t index = 0; index < tile.Rays.size(); ++index)
  {
    RayInfo& ray = tile.Rays[index];
    if (slot != 0 && ray.KeepsNoRows())
    {
      continue;
    }
    const int px = ray.Pixel % width;
    const int py = ray.Pixel / width;
    const Ray r = this->State.CurrentViewData.PixelRay(px, py);
    const double rotation = ray.Rotation;
    const double u = RotatedOffset(base, rotation);
    const StoredRows<Code> rows =
      StoredRows<Code>::Of(*into, ray.FirstRow, attributes, hasSecondCodes);
    // With horizons, the walk back from the far end waits until the first piece has left the
    // ray clear: a ray that piece makes opaque is cut at its horizon, and its back (the end of
    // its last block not skipped) is never needed. Samplers that trace paths sample a ray in
    // one piece, bounded by its back.
    bool backLater = false;
    if (slot == 0 && fronts)
    {
      ray.Front = this->FrontOf(ray, r, *fronts);
      backLater = horizons && !this->State.Source->TracesPaths();
      ray.Back = backLater ? ray.SamplesPerFrame : this->BackOf(ray, r, *fronts, ray.Front);
    }
    if (slot != 0 || !horizons)
    {
      const int count = ray.Horizon - ray.Front;
      this->SampleNewFrame(ray, r, rotation, u, rows.From(ray.Front), attributes, vectorEncode,
        paths, index, buffers, slot, count, ray.Front);
      buffers.Sampled += static_cast<std::size_t>(count);
      continue;
    }
    // The first frame, a piece at a time (whole for samplers that walk their data), until its
    // samples alone leave less than a hundredth of the light where blends stop (optical depth
    // horizonDepth); the horizon three rows further.
    const int piece = this->State.Source->TracesPaths() ? ray.SamplesPerFrame : kHorizonPiece;
    double opticalDepth = 0.0;
    int sampled = ray.Front;
    int opaqueAt = -1;
    while (sampled < ray.Back && (opaqueAt < 0 || sampled < opaqueAt + 3))
    {
      const int count = std::min(piece, ray.Back - sampled);
      this->SampleNewFrame(ray, r, rotation, u, rows.From(sampled), attributes, vectorEncode, paths,
        index, buffers, slot, count, sampled);
      for (int j = sampled; j < sampled + count && opaqueAt < 0; ++j)
      {
        opticalDepth +=
          horizons->Extinction(rows.Codes[static_cast<std::size_t>(j) * rows.Capacity]) * dt;
        opaqueAt = opticalDepth > horizonDepth ? j : -1;
      }
      sampled += count;
      if (backLater && opaqueAt < 0)
      {
        // Rows past the back lie in skipped blocks: any sampled already are transparent, and
        // the horizon below stops at the back.
        ray.Back = this->BackOf(ray, r, *fronts, ray.Front);
        backLater = false;
      }
    }
    ray.Horizon = opaqueAt < 0 ? ray.Back : std::min(opaqueAt + 3, sampled);
    buffers.Sampled += static_cast<std::size_t>(sampled - ray.Front);
  }
  if (into != &tile.Stores)
  {
    tile.Stores.KeepRows(tile.Rays, *into, layout, this->State.Capacity);
  }
}

bool SamplingPass::HorizonsApply(
  const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes) const
{
  return (mode == BlendMode::Composite || mode == BlendMode::PreIntegrated) &&
         !attributes.GradientOpacity && !tf.HasComponentTerms() && !tf.HasComponentLevels() &&
         !this->State.Source->HasSecondCode() && this->State.Settings.OpacityHorizons;
}

template <typename Code>
bool SamplingPass::ResumeRays(Tile& tile, Buffers& buffers, const Attributes& attributes,
  bool vectorEncode, bool alongPaths, int taken, const float* target, bool horizonsApply,
  bool frontsHold, bool sample)
{
  const int width = this->State.CurrentViewData.Width;
  const double dt = this->State.Settings.SampleDistance;
  const bool hasSecondCodes = this->State.Source->HasSecondCode();
  // Alpha at which a blend has stopped the ray. A ray left exactly Termination's light (opacities
  // such as 0.5 per step make that common) reads as stopped too: cut there, it misses at most
  // that light.
  const float endedAlpha = static_cast<float>(1.0 - this->State.Settings.StopTransmittance());
  TilePaths* paths = alongPaths && tile.Paths.Active() ? &tile.Paths : nullptr;
  std::vector<char>& whole = buffers.Flags;
  whole.assign(tile.Rays.size(), 0);
  bool resumed = false;
  for (std::size_t index = 0; index < tile.Rays.size(); ++index)
  {
    const RayInfo& ray = tile.Rays[index];
    // Rays cut at a front or a back while those blocks stay transparent, and at a horizon while
    // the blend stops them there, are kept; the others are sampled whole.
    whole[index] =
      !((frontsHold || (ray.Front == 0 && ray.Back >= ray.SamplesPerFrame)) &&
        (ray.Horizon >= ray.Back ||
          (horizonsApply && target[4 * static_cast<std::size_t>(ray.Pixel) + 3] >= endedAlpha)));
    resumed = resumed || whole[index];
    if (resumed && !sample)
    {
      return true;
    }
  }
  if (!resumed)
  {
    return false;
  }
  // Whole rays again, in whole rows (the rows they had come out the same).
  tile.Stores.RelayWholeRays(
    tile.Rays, whole, buffers.Relaid, this->State.CurrentStoreLayout(), this->State.Capacity);
  for (std::size_t index = 0; index < tile.Rays.size(); ++index)
  {
    RayInfo& ray = tile.Rays[index];
    if (!whole[index])
    {
      continue;
    }
    const int px = ray.Pixel % width;
    const int py = ray.Pixel / width;
    const StoredRows<Code> rows =
      StoredRows<Code>::Of(tile.Stores, ray.FirstRow, attributes, hasSecondCodes);
    const double rotation = ray.Rotation;
    const Ray r = this->State.CurrentViewData.PixelRay(px, py);
    for (int slot = 0; slot < taken; ++slot)
    {
      const double u = RotatedOffset(RadicalInverse2(static_cast<std::uint32_t>(slot)), rotation);
      this->SampleNewFrame(ray, r, rotation, u, rows, attributes, vectorEncode, paths, index,
        buffers, slot, ray.SamplesPerFrame, 0);
      buffers.Sampled += static_cast<std::size_t>(ray.SamplesPerFrame);
    }
    ray.Horizon = ray.SamplesPerFrame;
  }
  return true;
}

// The code widths SamplingPass::TilePasses runs.
template void SamplingPass::SampleTile<std::uint8_t>(
  Tile&, Buffers&, const Attributes&, bool, bool, const TransferFunctionTable*, const SkipMask*);
template void SamplingPass::SampleTile<std::uint16_t>(
  Tile&, Buffers&, const Attributes&, bool, bool, const TransferFunctionTable*, const SkipMask*);
template bool SamplingPass::ResumeRays<std::uint8_t>(
  Tile&, Buffers&, const Attributes&, bool, bool, int, const float*, bool, bool, bool);
template bool SamplingPass::ResumeRays<std::uint16_t>(
  Tile&, Buffers&, const Attributes&, bool, bool, int, const float*, bool, bool, bool);

} // namespace savr

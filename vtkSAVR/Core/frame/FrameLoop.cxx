#include "frame/FrameLoop.h"

#include "blend/PlainComposite.h"
#include "frame/FrameLoopTiles.h"
#include "grid/GridAVX2.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace savr
{

FrameLoop::FrameLoop()
  : ThreadScratch(new Scratch)
{
}

FrameLoop::~FrameLoop() = default;

void FrameLoop::ImageBytes(const std::vector<float>& image, std::vector<std::uint8_t>& bytes)
{
  if (bytes.capacity() > image.size())
  {
    std::vector<std::uint8_t>().swap(bytes); // counted at the image's size, not a larger one's
  }
  bytes.resize(image.size());
  const std::size_t rowFloats = static_cast<std::size_t>(this->CurrentViewData.Width) * 4;
  const std::size_t rows = rowFloats > 0 ? image.size() / rowFloats : 0;
  // Plain pointers: through the vectors, each byte stored (which may alias anything) would
  // make the compiler read their data pointers again.
  const float* in = image.data();
  std::uint8_t* out = bytes.data();
  // Only the rectangle can hold pixels that are not zero.
  const std::size_t x0 = 4 * static_cast<std::size_t>(this->Rectangle[0]);
  const std::size_t x1 = 4 * static_cast<std::size_t>(this->Rectangle[2]);
  const std::size_t y0 = static_cast<std::size_t>(this->Rectangle[1]);
  const std::size_t y1 = static_cast<std::size_t>(this->Rectangle[3]);
  this->InArena(
    [&]()
    {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 16),
        [=](const tbb::blocked_range<std::size_t>& range)
        {
          for (std::size_t y = range.begin(); y < range.end(); ++y)
          {
            std::uint8_t* row = out + y * rowFloats;
            if (y < y0 || y >= y1 || x1 <= x0)
            {
              std::fill(row, row + rowFloats, std::uint8_t(0));
              continue;
            }
            std::fill(row, row + x0, std::uint8_t(0));
            std::fill(row + x1, row + rowFloats, std::uint8_t(0));
            const float* source = in + y * rowFloats;
            for (std::size_t i = x0; i < x1; ++i)
            {
              const float v = std::min(std::max(source[i], 0.0f), 1.0f);
              row[i] = static_cast<std::uint8_t>(v * 255.0f + 0.5f);
            }
          }
        });
    });
}

FrameLoop::Attributes FrameLoop::CurrentAttributes() const
{
  Attributes a;
  a.ComponentNormals = this->Settings.Shade && this->Settings.ComponentNormals;
  a.Normals = this->Settings.Shade && !a.ComponentNormals;
  a.Magnitudes = this->Settings.GradientMagnitudes;
  a.MagnitudeScale = this->Settings.MagnitudeScale;
  a.ComponentMagnitudes = this->Settings.ComponentMagnitudes;
  a.ComponentScales = this->Settings.ComponentMagnitudeScales;
  a.Shading = this->Settings.Shade ? this->Inputs.Shading : nullptr;
  a.GradientOpacity =
    a.Magnitudes || a.ComponentMagnitudes ? this->Inputs.GradientOpacity : nullptr;
  a.Isos = this->Inputs.Isos;
  return a;
}

double FrameLoop::RotationOf(int x, int y, double step) const
{
  if (!this->Settings.RotateOffsets)
  {
    return 0.0;
  }
  const double phaseLength = this->Settings.PhaseLength;
  const double turns = phaseLength > 0.0
                         ? PixelPhase(x, y) * (phaseLength / step)
                         : PixelRotation(x, y) * (this->Settings.SampleDistance / step);
  return turns - std::floor(turns);
}

void FrameLoop::PrepareGradients()
{
  if (this->NeedsGradients())
  {
    this->InArena([this]() { this->Source->PrepareGradients(); });
  }
}

std::size_t FrameLoop::MemoryInUse() const
{
  std::size_t bytes = 0;
  for (const Tile& tile : this->Tiles)
  {
    bytes += tile.Store.MemoryInUse() + tile.Normals.MemoryInUse() + tile.Magnitudes.MemoryInUse() +
             tile.ComponentNormals.MemoryInUse() + tile.ComponentMagnitudes.MemoryInUse() +
             tile.SecondCodes.MemoryInUse() + tile.Paths.Bytes();
  }
  return bytes;
}

void FrameLoop::Grow(int capacity)
{
  const int frames = this->FrameCount;
  this->ForEachTile(
    [&](Tile& tile, Buffers&)
    {
      tile.Store.Grow(capacity, frames);
      tile.Normals.Grow(capacity, frames);
      tile.Magnitudes.Grow(capacity, frames);
      tile.ComponentNormals.Grow(capacity, frames);
      tile.ComponentMagnitudes.Grow(capacity, frames);
      tile.SecondCodes.Grow(capacity, frames);
    });
  this->Capacity = capacity;
}

bool FrameLoop::AccumulateFrame(const TransferFunctionTable& tf, BlendMode mode, double seconds)
{
  if (this->Pass.NextTile == 0 && !this->Tiles.empty())
  {
    this->ChoosePass();
  }
  if (this->Complete() || this->Tiles.empty())
  {
    return true;
  }
  if (mode == BlendMode::Slice || this->FrameLimitCount == 0)
  {
    if (mode == BlendMode::Slice)
    {
      // One frame is the exact image: the refinement is complete at once.
      this->RenderSlice(tf);
      this->Errors.Estimate = 0.0;
    }
    else
    {
      // Not even one frame fits the budget: draw plain ray casting and call it final.
      this->RenderSinglePass(tf, mode, this->Settings.SampleDistance, 0.0);
    }
    this->FrameCount = std::max(this->FrameLimitCount, 1);
    for (Tile& tile : this->Tiles)
    {
      tile.Frames = this->FrameCount;
    }
    this->Pass.Frames = this->FrameCount;
    this->ShowingSinglePass = false;
    return true;
  }
  // A frame under way whose tables or mode changed starts over: its tiles done so far were
  // blended with the others (their samples, taken again, stay the same).
  const std::uint64_t blend =
    (tf.Generation() * 1000003u + this->Inputs.Generation()) * 16u + static_cast<unsigned>(mode);
  if (this->Pass.NextTile > 0 && blend != this->Pass.NextTileBlend)
  {
    this->Pass.NextTile = 0;
  }
  this->Pass.NextTileBlend = blend;
  if (this->Pass.NextTile == 0)
  {
    this->PrepareGradients();
    if (this->Pass.Frames + 1 > this->Capacity)
    {
      // Room for four times the frames (never past the limit), the first time for four:
      // growing copies every sample kept, so it should happen seldom.
      this->Grow(NextCapacity(this->Capacity, this->FrameLimitCount));
    }
  }
  this->ShowingSinglePass = false;
  const std::vector<std::size_t>* pass = this->Pass.All ? nullptr : &this->Pass.Tiles;
  this->Pass.NextTile = this->SampleAndBlend(tf, mode, seconds);
  if (this->Pass.NextTile < (pass ? pass->size() : this->Tiles.size()))
  {
    return false;
  }
  this->Pass.NextTile = 0;
  if (!this->Pass.Resume)
  {
    const int frames = this->Pass.Frames + 1;
    this->ForEachTile([frames](Tile& tile, Buffers&) { tile.Frames = frames; }, 0, 0.0, pass);
    this->FrameCount = std::max(this->FrameCount, frames);
  }
  this->UpdateErrorEstimate(tf, mode, pass, false);
  this->ChoosePass();
  if (this->Complete())
  {
    // No frame reads them again.
    for (Tile& tile : this->Tiles)
    {
      tile.Paths.Release();
    }
  }
  return true;
}

double FrameLoop::FrameProgress() const
{
  const std::size_t tiles = this->Pass.All ? this->Tiles.size() : this->Pass.Tiles.size();
  return tiles == 0 ? 0.0 : double(this->Pass.NextTile) / double(tiles);
}

std::size_t FrameLoop::SampleAndBlend(
  const TransferFunctionTable& tf, BlendMode mode, double seconds)
{
  // A resuming pass blends the frames its tiles have; any other samples the next.
  const int frames = this->Pass.Resume ? this->Pass.Frames : this->Pass.Frames + 1;
  const TileWork work = this->Pass.Resume ? TileWork::Resume : TileWork::Sample;
  const std::vector<std::size_t>* pass = this->Pass.All ? nullptr : &this->Pass.Tiles;
  if (this->Encoder.Bytes == 1)
  {
    return this->TilePasses<std::uint8_t>(
      tf, mode, work, frames, this->Pixels.data(), this->Pass.NextTile, seconds, pass);
  }
  return this->TilePasses<std::uint16_t>(
    tf, mode, work, frames, this->Pixels.data(), this->Pass.NextTile, seconds, pass);
}

void FrameLoop::BlendStored(const TransferFunctionTable& tf, BlendMode mode, int frames,
  float* target, const std::vector<std::size_t>* tiles)
{
  if (this->Encoder.Bytes == 1)
  {
    this->TilePasses<std::uint8_t>(tf, mode, TileWork::Blend, frames, target, 0, 0.0, tiles);
  }
  else
  {
    this->TilePasses<std::uint16_t>(tf, mode, TileWork::Blend, frames, target, 0, 0.0, tiles);
  }
}

void FrameLoop::Reblend(const TransferFunctionTable& tf, BlendMode mode)
{
  // A frame under way starts over (its tiles done so far are blended without it now); its
  // tiles sample the same offsets again, so its samples do not change.
  this->Pass.NextTile = 0;
  if (this->FrameCount == 0 || this->Tiles.empty())
  {
    return;
  }
  if (mode == BlendMode::Slice)
  {
    this->RenderSlice(tf);
    this->ShowingSinglePass = false;
    return;
  }
  if (this->FrameLimitCount == 0)
  {
    // Nothing is stored: the plain pass is the image.
    this->RenderSinglePass(tf, mode, this->Settings.SampleDistance, 0.0);
    this->ShowingSinglePass = false;
    return;
  }
  this->BlendOwnFrames(tf, mode, this->Pixels.data());
  this->ShowingSinglePass = false;
  this->UpdateErrorEstimate(tf, mode, nullptr, true);
  this->ChoosePass();
}

bool FrameLoop::PlainIntervalTables(const TransferFunctionTable& tf, BlendMode mode, int frames,
  const Attributes& attributes, std::vector<const double*>& sortedTables)
{
  sortedTables.assign(frames, nullptr);
  // Composite without gradient opacity or second codes, lit or not: each interior interval
  // has its table. Independent components shaded light each component with its own coefficients:
  // not plain.
  const bool plain = this->Settings.FastPaths && mode == BlendMode::Composite &&
                     !attributes.GradientOpacity && !this->Source->HasSecondCode() &&
                     !tf.HasComponentTerms() && !(attributes.Shading && tf.HasComponentLevels());
  if (!plain)
  {
    return false;
  }
  this->Tables.Intervals(tf, this->Offsets, frames, this->Settings.SampleDistance, sortedTables);
  return true;
}

template <typename Code>
void FrameLoop::SampleNewFrame(const RayInfo& ray, int px, int py, double u,
  const StoredRows<Code>& rows, const Attributes& attributes, bool vectorEncode, TilePaths* paths,
  std::size_t index, Buffers& buffers, int slot, int count, int firstRow) const
{
  const std::size_t capacity = static_cast<std::size_t>(rows.Capacity);
  const double dt = this->Settings.SampleDistance;
  const Sampler& source = *this->Source;
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
  const Ray r = this->CurrentViewData.PixelRay(px, py);
  const double start = ray.TEnter + (firstRow + u) * dt;
  // Room for whole groups of four: values are encoded four at a time, and the codes of
  // the values past the ray's (whatever they hold) are not used.
  const std::size_t padded = (static_cast<std::size_t>(count) + 3) & ~std::size_t(3);
  buffers.Values.resize(padded);
  if (attributes.Normals || attributes.Magnitudes)
  {
    buffers.Gradients.resize(3 * static_cast<std::size_t>(count));
    source.SampleRayGradients(r, start, dt, count, buffers.Values.data(), buffers.Gradients.data());
    if (vectorEncode && rows.Normals && !rows.Magnitudes)
    {
      // Normals alone: encoded four at a time (the same codes as Encode).
      buffers.Normals.resize(count);
      detail::EncodeNormalsAVX2(buffers.Gradients.data(), count, buffers.Normals.data());
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
    this->SampleValues(ray, r, start, this->RotationOf(px, py, dt), paths, index, buffers, count);
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

void FrameLoop::SampleValues(const RayInfo& ray, const Ray& r, double start, double rotation,
  TilePaths* paths, std::size_t index, Buffers& buffers, int count) const
{
  const double dt = this->Settings.SampleDistance;
  const Sampler& source = *this->Source;
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
      dt * OffsetSequence::SmallestGap(this->FrameLimitCount), TilePaths::kMaxPieces, buffers.Path);
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
void FrameLoop::FileCodes(int count, std::size_t padded, const StoredRows<Code>& rows,
  bool vectorEncode, Buffers& buffers, int newSlot) const
{
  // Into the new slot of every row. (Locals, so that the byte stores, which may alias
  // anything, do not make the compiler read these again each time.)
  const SampleEncoding& encoding = this->Encoder;
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

void FrameLoop::PrepareBlend(const TransferFunctionTable& tf, int frames)
{
  if (this->Offsets.Frames() != frames)
  {
    this->Offsets.Resize(frames);
  }
  const double gap = OffsetSequence::SmallestGap(frames) * this->Settings.SampleDistance;
  this->Alphas.Prepare(tf, gap, 2.0 * gap);
}

template <typename Code>
void FrameLoop::SampleTile(Tile& tile, Buffers& buffers, const Attributes& attributes,
  bool vectorEncode, bool alongPaths, const TransferFunctionTable* horizons)
{
  const int slot = this->Pass.Frames;
  const int width = this->CurrentViewData.Width;
  const double dt = this->Settings.SampleDistance;
  const double base = this->Offsets.Offset(slot);
  const bool hasSecondCodes = this->Source->HasSecondCode();
  TilePaths* paths = alongPaths && tile.Paths.Active() ? &tile.Paths : nullptr;
  for (std::size_t index = 0; index < tile.Rays.size(); ++index)
  {
    RayInfo& ray = tile.Rays[index];
    const int px = ray.Pixel % width;
    const int py = ray.Pixel / width;
    const double u = RotatedOffset(base, this->RotationOf(px, py, dt));
    const StoredRows<Code> rows =
      StoredRows<Code>::Of(tile, ray.FirstRow, attributes, hasSecondCodes);
    if (slot != 0 || !horizons)
    {
      this->SampleNewFrame(ray, px, py, u, rows, attributes, vectorEncode, paths, index, buffers,
        slot, ray.Horizon, 0);
      buffers.Sampled += static_cast<std::size_t>(ray.Horizon);
      continue;
    }
    // The first frame, a piece at a time (whole for samplers that walk their data), until its
    // samples alone leave less than 1e-8 of the light; the horizon three rows further.
    const int piece = this->Source->TracesPaths() ? ray.SamplesPerFrame : kHorizonPiece;
    double opticalDepth = 0.0;
    int sampled = 0;
    int opaqueAt = -1;
    while (sampled < ray.SamplesPerFrame && (opaqueAt < 0 || sampled < opaqueAt + 3))
    {
      const int count = std::min(piece, ray.SamplesPerFrame - sampled);
      this->SampleNewFrame(ray, px, py, u, rows.From(sampled), attributes, vectorEncode, paths,
        index, buffers, slot, count, sampled);
      for (int j = sampled; j < sampled + count && opaqueAt < 0; ++j)
      {
        opticalDepth +=
          horizons->Extinction(rows.Codes[static_cast<std::size_t>(j) * rows.Capacity]) * dt;
        opaqueAt = opticalDepth > kHorizonDepth ? j : -1;
      }
      sampled += count;
    }
    ray.Horizon = opaqueAt < 0 ? ray.SamplesPerFrame : std::min(opaqueAt + 3, sampled);
    buffers.Sampled += static_cast<std::size_t>(sampled);
  }
}

bool FrameLoop::HorizonsApply(
  const TransferFunctionTable& tf, BlendMode mode, const Attributes& attributes) const
{
  return (mode == BlendMode::Composite || mode == BlendMode::PreIntegrated) &&
         !attributes.GradientOpacity && !tf.HasComponentTerms() && !tf.HasComponentLevels() &&
         !this->Source->HasSecondCode() && this->Settings.OpacityHorizons;
}

template <typename Code>
bool FrameLoop::ResumeRays(Tile& tile, Buffers& buffers, const Attributes& attributes,
  bool vectorEncode, bool alongPaths, int taken, const float* target, bool horizonsApply,
  bool sample)
{
  const int width = this->CurrentViewData.Width;
  const double dt = this->Settings.SampleDistance;
  const bool hasSecondCodes = this->Source->HasSecondCode();
  TilePaths* paths = alongPaths && tile.Paths.Active() ? &tile.Paths : nullptr;
  bool resumed = false;
  for (std::size_t index = 0; index < tile.Rays.size(); ++index)
  {
    RayInfo& ray = tile.Rays[index];
    if (ray.Horizon >= ray.SamplesPerFrame ||
        (horizonsApply && target[4 * static_cast<std::size_t>(ray.Pixel) + 3] >= kHorizonAlpha))
    {
      continue;
    }
    resumed = true;
    if (!sample)
    {
      break;
    }
    // Whole rays again (the rows before the horizon come out the same).
    const int px = ray.Pixel % width;
    const int py = ray.Pixel / width;
    const StoredRows<Code> rows =
      StoredRows<Code>::Of(tile, ray.FirstRow, attributes, hasSecondCodes);
    const double rotation = this->RotationOf(px, py, dt);
    for (int slot = 0; slot < taken; ++slot)
    {
      const double u = RotatedOffset(RadicalInverse2(static_cast<std::uint32_t>(slot)), rotation);
      this->SampleNewFrame(ray, px, py, u, rows, attributes, vectorEncode, paths, index, buffers,
        slot, ray.SamplesPerFrame, 0);
      buffers.Sampled += static_cast<std::size_t>(ray.SamplesPerFrame);
    }
    ray.Horizon = ray.SamplesPerFrame;
  }
  return resumed;
}

template <typename Code>
struct FrameLoop::TileBlend
{
  const TransferFunctionTable& TF;
  BlendMode Mode;
  int Frames;
  Attributes Attrs;
  bool HasSecondCodes;
  // Plain composite: each sorted offset's interval table, and whether rays are composited four
  // at a time (AVX2; every offset has a table and the rays are unlit).
  const std::vector<const double*>& SortedTables;
  bool Plain;
  bool GroupsOfFour;
  const detail::RowScan<Code>& Scan;
  float* Pixels;
};

template <typename Code>
void FrameLoop::BlendTile(Tile& tile, Buffers& buffers, const TileBlend<Code>& b) const
{
  const int frames = b.Frames;
  const int width = this->CurrentViewData.Width;
  const double dt = this->Settings.SampleDistance;
  const OffsetSequence& offsets = this->Offsets;
  // Room for four rays' offsets and tables: plain rays are composited four at a time.
  buffers.U.resize(4 * static_cast<std::size_t>(frames));
  buffers.Order.resize(4 * static_cast<std::size_t>(frames));
  buffers.Tables.resize(4 * static_cast<std::size_t>(frames));
  RayLayout<Code> group[4];
  int groupPixels[4] = { 0, 0, 0, 0 };
  int pending = 0;
  const auto compositeOne = [&](const RayLayout<Code>& layout, const double* const* tables)
  {
    return detail::PlainComposite<Code>(
      layout, b.TF, this->Alphas, tables, &b.Scan, kNegligibleTransmittance, b.Attrs.Shading)
      .Blend();
  };
  const auto tablesOf = [&](int g) { return buffers.Tables.data() + g * frames; };
  const auto put = [&](const Pixel& p, int pixel)
  { std::copy(p.data(), p.data() + 4, b.Pixels + 4 * static_cast<std::size_t>(pixel)); };
  for (const RayInfo& ray : tile.Rays)
  {
    const std::size_t g = static_cast<std::size_t>(pending) * frames;
    double* const u = buffers.U.data() + g;
    int* const order = buffers.Order.data() + g;
    const double** const tables = buffers.Tables.data() + g;
    const int shift =
      offsets.Rotate(this->RotationOf(ray.Pixel % width, ray.Pixel / width, dt), u, order);
    const StoredRows<Code> rows =
      StoredRows<Code>::Of(tile, ray.FirstRow, b.Attrs, b.HasSecondCodes);
    const RayLayout<Code> layout = rows.Layout(ray, frames, u, order, dt);
    if (!b.Plain)
    {
      put(BlendRay(layout, b.TF, this->Alphas, b.Mode, kNegligibleTransmittance, b.Attrs.Shading,
            b.Attrs.GradientOpacity, b.Attrs.Isos),
        ray.Pixel);
      continue;
    }
    // Rank s is the offset SortedTables[s + shift] stands for, rotated.
    for (int s = 0; s < frames; ++s)
    {
      tables[s] = b.SortedTables[s + shift < frames ? s + shift : s + shift - frames];
    }
    if (b.GroupsOfFour)
    {
      group[pending] = layout;
      groupPixels[pending] = ray.Pixel;
      if (++pending == 4)
      {
        detail::CompositeFour(group, tablesOf, &b.Scan, b.TF, this->Alphas, b.Pixels, groupPixels);
        pending = 0;
      }
      continue;
    }
    put(compositeOne(layout, tables), ray.Pixel);
  }
  for (int g = 0; g < pending; ++g)
  {
    put(compositeOne(group[g], tablesOf(g)), groupPixels[g]);
  }
}

template <typename Code>
std::size_t FrameLoop::TilePasses(const TransferFunctionTable& tf, BlendMode mode, TileWork work,
  int frames, float* target, std::size_t first, double seconds,
  const std::vector<std::size_t>* tiles)
{
  this->PrepareBlend(tf, frames);
  const Attributes attributes = this->CurrentAttributes();
  // Samples are encoded eight at a time where the CPU can (the same codes as Encode).
  const bool vectorEncode = this->Settings.Vectorize && detail::HaveAVX2();
  std::vector<const double*> sortedTables;
  const bool plain = this->PlainIntervalTables(tf, mode, frames, attributes, sortedTables);
  // Codes below `transparent` are (codes past the table's are not looked at).
  std::uint32_t transparent = 0;
  while (plain && this->Settings.PassOverTransparentRows && transparent < tf.Size() &&
         tf.Extinction(transparent) == 0.0)
  {
    ++transparent;
  }
  const detail::RowScan<Code> scan(
    transparent, this->Capacity, frames, this->Settings.Vectorize && detail::HaveAVX2());
  const bool allTabled =
    std::find(sortedTables.begin(), sortedTables.end(), nullptr) == sortedTables.end();
  const TileBlend<Code> blend{ tf, mode, frames, attributes, this->Source->HasSecondCode(),
    sortedTables, plain, plain && allTabled && vectorEncode && !attributes.Shading, scan, target };
  // Paths hold values only.
  const bool alongPaths = work != TileWork::Blend && !attributes.Any() && !blend.HasSecondCodes;
  const bool horizonsApply = this->HorizonsApply(tf, mode, attributes);
  // Each tile: the new frame's samples of its rays first (the sampling pass), then every stored
  // frame of its rays blended (the blending pass), while the tile's rows are still in cache;
  // rays that the blend did not make opaque at their horizon are sampled whole and the tile
  // blended again (a blend alone marks the tile for that).
  std::atomic<std::uint64_t> sampled{ 0 };
  const std::size_t next = this->ForEachTile(
    [&](Tile& tile, Buffers& buffers)
    {
      buffers.Sampled = 0;
      if (work == TileWork::Sample)
      {
        this->SampleTile<Code>(
          tile, buffers, attributes, vectorEncode, alongPaths, horizonsApply ? &tf : nullptr);
      }
      this->BlendTile(tile, buffers, blend);
      const bool sample = work != TileWork::Blend;
      const int taken = std::max(work == TileWork::Sample ? frames : 0, tile.Frames);
      if (this->ResumeRays<Code>(tile, buffers, attributes, vectorEncode, alongPaths, taken, target,
            horizonsApply, sample))
      {
        if (sample)
        {
          this->BlendTile(tile, buffers, blend);
          tile.SnapshotFrames = 0; // blended with the rays cut
        }
        tile.Resume = !sample;
      }
      else if (sample)
      {
        tile.Resume = false;
      }
      sampled += buffers.Sampled;
    },
    first, seconds, tiles);
  this->Taken += sampled;
  return next;
}

} // namespace savr

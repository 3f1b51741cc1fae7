// The frame loop: a frame accumulated tile by tile through its passes, re-blends, single
// passes, depth windows and the image as bytes.

#include "frame/FrameLoop.h"

#include "encoding/EncodeAVX2.h"
#include "frame/PassScratch.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

namespace savr
{

void FrameLoop::Reset(
  const View& view, std::shared_ptr<const Sampler> sampler, const FrameSettings& settings)
{
  const std::size_t imageRoom = this->State.Pixels.capacity();
  this->State.Reset(view, std::move(sampler), settings);
  this->FrameCount = 0;
  this->ShowingSinglePass = false;
  this->ShownBlendValid = false;
  this->FramesWithoutSamples = false;
  this->Sampling.ForgetFronts(); // no ray has a front yet
  this->Errors.Reset();
  // A smaller view, or none within the budget, frees the estimate's image with the image.
  if (this->State.Pixels.capacity() < imageRoom)
  {
    this->Errors.Release();
  }
}

void FrameLoop::ImageBytes(const std::vector<float>& image, std::vector<std::uint8_t>& bytes)
{
  if (bytes.capacity() > image.size())
  {
    std::vector<std::uint8_t>().swap(bytes); // counted at the image's size, not a larger one's
  }
  bytes.resize(image.size());
  const std::size_t rowFloats = static_cast<std::size_t>(this->State.CurrentViewData.Width) * 4;
  const std::size_t rows = rowFloats > 0 ? image.size() / rowFloats : 0;
  // Plain pointers: through the vectors, each byte stored (which may alias anything) would
  // make the compiler read their data pointers again.
  const float* in = image.data();
  std::uint8_t* out = bytes.data();
  // Only the rectangle can hold pixels that are not zero.
  const std::size_t x0 = 4 * static_cast<std::size_t>(this->State.Rectangle[0]);
  const std::size_t x1 = 4 * static_cast<std::size_t>(this->State.Rectangle[2]);
  const std::size_t y0 = static_cast<std::size_t>(this->State.Rectangle[1]);
  const std::size_t y1 = static_cast<std::size_t>(this->State.Rectangle[3]);
  this->State.InArena(
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

bool FrameLoop::AccumulateFrame(const TransferFunctionTable& tf, BlendMode mode, double seconds)
{
  if (this->State.Schedule.Pass().NextTile == 0 && !this->State.Tiles.empty())
  {
    this->State.Schedule.ChoosePass(this->State.FrameLimitCount);
  }
  const FramePass& pass = this->State.Schedule.Pass();
  // A pass blends its own tiles only. Where the image shows other tables or a single pass and the
  // pass is not every tile's, every tile is blended again first (as Reblend; the pass gets what
  // is left of the bound, if any), so that the tiles the pass does not reach (settled ones, ones
  // with more frames, ones whose rays wait to be resumed) show these tables too. (A frame of
  // every tile reaches each one, over several calls under a bound; as it would in one call, it
  // decides which rays to resume from its own blend, so that its image has the same bits.)
  const std::uint64_t blend = this->BlendKey(tf, mode);
  const bool everyTile = pass.All && !pass.Resume;
  if (this->FrameCount > 0 && !this->State.Tiles.empty() && this->State.FrameLimitCount > 0 &&
      !this->FramesWithoutSamples && mode != BlendMode::Slice && !everyTile &&
      !(this->ShownBlendValid && this->ShownBlend == blend))
  {
    const double start = this->State.Schedule.Now();
    this->Reblend(tf, mode);
    if (seconds > 0.0)
    {
      seconds = std::max(seconds - (this->State.Schedule.Now() - start), 1e-9);
    }
  }
  this->ShownBlend = blend;
  this->ShownBlendValid = true;
  if (this->Complete() || this->State.Tiles.empty())
  {
    return true;
  }
  if (mode == BlendMode::Slice || this->State.FrameLimitCount == 0)
  {
    if (mode == BlendMode::Slice)
    {
      // One frame is the exact image: the refinement is complete at once.
      this->Single.RenderSlice(tf);
      this->Errors.SetExact();
    }
    else
    {
      // Not even one frame fits the budget: draw plain ray casting and call it final.
      this->RenderSinglePass(tf, mode, this->State.Settings.SampleDistance, 0.0);
    }
    this->FrameCount = std::max(this->State.FrameLimitCount, 1);
    for (Tile& tile : this->State.Tiles)
    {
      tile.Frames = this->FrameCount;
    }
    this->State.Schedule.Conclude(this->FrameCount);
    this->FramesWithoutSamples = true; // nothing stored to blend again
    this->ShownBlendValid = false;
    this->ShowingSinglePass = false;
    return true;
  }
  // A frame under way whose tables or mode changed starts over: its tiles done so far were
  // blended with the others (their samples, taken again, stay the same).
  if (pass.NextTile > 0 && blend != pass.NextTileBlend)
  {
    this->State.Schedule.ContinueAt(0);
  }
  this->State.Schedule.BlendWith(blend);
  if (pass.NextTile == 0)
  {
    this->State.PrepareGradients();
    if (pass.Frames + 1 > this->State.Capacity)
    {
      // Room for four times the frames (never past the limit), the first time for four:
      // growing copies every sample kept, so it should happen seldom.
      this->State.Grow(RayStores::NextCapacity(this->State.Capacity, this->State.FrameLimitCount),
        this->FrameCount);
    }
  }
  this->ShowingSinglePass = false;
  this->State.Schedule.ContinueAt(this->SampleAndBlend(tf, mode, seconds));
  if (pass.NextTile < this->State.Schedule.PassSize())
  {
    return false;
  }
  this->State.Schedule.ContinueAt(0);
  const std::vector<std::size_t>* tiles = this->State.Schedule.PassTiles();
  if (!pass.Resume)
  {
    const int frames = pass.Frames + 1;
    this->State.ForEachTile(
      [frames](Tile& tile, ThreadBuffers&) { tile.Frames = frames; }, 0, 0.0, tiles);
    this->FrameCount = std::max(this->FrameCount, frames);
  }
  this->UpdateErrorEstimate(tf, mode, tiles, false);
  this->State.Schedule.ChoosePass(this->State.FrameLimitCount);
  if (this->Complete())
  {
    // No frame reads them again.
    for (Tile& tile : this->State.Tiles)
    {
      tile.Paths.Release();
    }
  }
  return true;
}

double FrameLoop::FrameProgress() const
{
  return this->State.Schedule.Progress();
}

std::size_t FrameLoop::SampleAndBlend(
  const TransferFunctionTable& tf, BlendMode mode, double seconds)
{
  // A resuming pass blends the frames its tiles have; any other samples the next.
  const FramePass& pass = this->State.Schedule.Pass();
  const int frames = pass.Resume ? pass.Frames : pass.Frames + 1;
  const TileWork work = pass.Resume ? TileWork::Resume : TileWork::Sample;
  const std::vector<std::size_t>* tiles = this->State.Schedule.PassTiles();
  if (this->State.Encoder.Bytes == 1)
  {
    return this->TilePasses<std::uint8_t>(
      tf, mode, work, frames, this->State.Pixels.data(), pass.NextTile, seconds, tiles);
  }
  return this->TilePasses<std::uint16_t>(
    tf, mode, work, frames, this->State.Pixels.data(), pass.NextTile, seconds, tiles);
}

void FrameLoop::BlendStored(const TransferFunctionTable& tf, BlendMode mode, int frames,
  float* target, const std::vector<std::size_t>* tiles)
{
  if (this->State.Encoder.Bytes == 1)
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
  this->State.Schedule.ContinueAt(0);
  if (this->FrameCount == 0 || this->State.Tiles.empty())
  {
    return;
  }
  if (mode == BlendMode::Slice)
  {
    this->Single.RenderSlice(tf);
    this->ShownBlendValid = false;
    this->ShowingSinglePass = false;
    return;
  }
  if (this->State.FrameLimitCount == 0)
  {
    // Nothing is stored: the plain pass is the image.
    this->RenderSinglePass(tf, mode, this->State.Settings.SampleDistance, 0.0);
    this->ShowingSinglePass = false;
    return;
  }
  this->BlendOwnFrames(tf, mode, this->State.Pixels.data());
  this->ShownBlend = this->BlendKey(tf, mode);
  this->ShownBlendValid = true;
  this->ShowingSinglePass = false;
  this->UpdateErrorEstimate(tf, mode, nullptr, true);
  this->State.Schedule.ChoosePass(this->State.FrameLimitCount);
}

void FrameLoop::BlendOwnFrames(const TransferFunctionTable& tf, BlendMode mode, float* target)
{
  for (const TileSchedule::TileGroup& group :
    this->State.Schedule.Groups([](const Tile& tile) { return tile.Frames; }))
  {
    this->BlendStored(
      tf, mode, group.first, target, group.second.empty() ? nullptr : &group.second);
  }
}

void FrameLoop::UpdateErrorEstimate(const TransferFunctionTable& tf, BlendMode mode,
  const std::vector<std::size_t>* tiles, bool reblended)
{
  const BlendIdentity blend{ tf.Generation(), mode, this->State.Inputs.Generation() };
  this->Errors.Update(this->State.Pixels, this->State.CurrentViewData.Width,
    this->State.CoveredPixels, blend, tiles, reblended,
    [&](int frames, float* target, const std::vector<std::size_t>& stale)
    { this->BlendStored(tf, mode, frames, target, &stale); });
}

template <typename Code>
std::size_t FrameLoop::TilePasses(const TransferFunctionTable& tf, BlendMode mode, TileWork work,
  int frames, float* target, std::size_t first, double seconds,
  const std::vector<std::size_t>* tiles)
{
  this->Blending.Prepare(tf, frames);
  const StoredAttributes attributes = this->State.CurrentAttributes();
  // Samples are encoded eight at a time where the CPU can (the same codes as Encode).
  const bool vectorEncode = this->State.Settings.Vectorize && detail::HaveAVX2();
  std::vector<const double*> sortedTables;
  const bool plain = this->Blending.PlainIntervalTables(tf, mode, frames, attributes, sortedTables);
  // Codes below `transparent` are (codes past the table's are not looked at).
  std::uint32_t transparent = 0;
  while (plain && this->State.Settings.PassOverTransparentRows && transparent < tf.Size() &&
         tf.Extinction(transparent) == 0.0)
  {
    ++transparent;
  }
  const detail::RowScan<Code> scan(transparent, this->State.Capacity, frames,
    this->State.Settings.Vectorize && detail::HaveAVX2());
  const bool allTabled =
    std::find(sortedTables.begin(), sortedTables.end(), nullptr) == sortedTables.end();
  const TileBlend<Code> blend{ tf, mode, frames, attributes, this->State.Source->HasSecondCode(),
    sortedTables, plain, plain && allTabled && vectorEncode && !attributes.Shading, scan, target };
  // Paths hold values only.
  const bool alongPaths = work != TileWork::Blend && !attributes.Any() && !blend.HasSecondCodes;
  const bool horizonsApply = this->Sampling.HorizonsApply(tf, mode, attributes);
  // The first frame sets each ray's front where this transfer function makes every block before
  // it transparent; later passes sample the rays whole where that no longer holds.
  std::vector<std::uint8_t> transparentBlocks;
  SkipMask frontMask;
  frontMask.Skip = &transparentBlocks;
  bool setFronts = false;
  if (work == TileWork::Sample && frames == 1)
  {
    std::uint32_t nanCode = 0;
    setFronts = this->Sampling.FrontsApply(tf, mode, attributes) &&
                this->State.TransparentBlocks(tf, transparentBlocks, nanCode);
    this->Sampling.SetFronts(setFronts ? transparentBlocks : std::vector<std::uint8_t>(), tf, mode);
  }
  const bool frontsHold = this->Sampling.FrontsHold(tf, mode, attributes);
  // Each tile: the new frame's samples of its rays first (the sampling pass), then every stored
  // frame of its rays blended (the blending pass), while the tile's rows are still in cache;
  // rays that the blend did not make opaque at their horizon are sampled whole and the tile
  // blended again (a blend alone marks the tile for that).
  std::atomic<std::uint64_t> sampled{ 0 };
  const std::size_t next = this->State.ForEachTile(
    [&](Tile& tile, ThreadBuffers& buffers)
    {
      buffers.Sampled = 0;
      if (work == TileWork::Sample)
      {
        this->Sampling.SampleTile<Code>(tile, buffers, attributes, vectorEncode, alongPaths,
          horizonsApply ? &tf : nullptr, setFronts ? &frontMask : nullptr);
      }
      this->Blending.BlendTile(tile, buffers, blend);
      const bool sample = work != TileWork::Blend;
      const int taken = std::max(work == TileWork::Sample ? frames : 0, tile.Frames);
      if (this->Sampling.ResumeRays<Code>(tile, buffers, attributes, vectorEncode, alongPaths,
            taken, target, horizonsApply, frontsHold, sample))
      {
        if (sample)
        {
          this->Blending.BlendTile(tile, buffers, blend);
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
  this->State.Taken += sampled;
  return next;
}

void FrameLoop::RenderSinglePass(const TransferFunctionTable& tf, BlendMode mode, double step,
  double offset, const PassOptions& options)
{
  if (this->State.Tiles.empty() || !(step > 0.0))
  {
    return;
  }
  // The pass replaces the image: a frame under way starts over (with the same samples).
  this->State.Schedule.ContinueAt(0);
  this->ShownBlendValid = false;
  if (mode == BlendMode::Slice)
  {
    this->Single.RenderSlice(tf);
    this->ShowingSinglePass = true;
    return;
  }
  this->ShowingSinglePass = true;
  this->Single.Render(tf, mode, step, offset, options);
}

void FrameLoop::PreviewRemainingTiles(const TransferFunctionTable& tf, BlendMode mode, int stride)
{
  const FramePass& pass = this->State.Schedule.Pass();
  // Only the first frame: later ones would cover the images their tiles have already.
  if (this->FrameCount > 0 || pass.Resume || pass.NextTile == 0 ||
      pass.NextTile >= this->State.Schedule.PassSize() || mode == BlendMode::Slice)
  {
    return;
  }
  this->Single.Render(tf, mode, this->State.Settings.SampleDistance, 0.0, PassOptions::Fast(stride),
    pass.NextTile, this->State.Schedule.PassTiles());
}

bool FrameLoop::CanBlendDepthWindows(BlendMode mode) const
{
  return WindowedBlend(mode) && !this->ShowingSinglePass && this->State.FrameLimitCount > 0 &&
         this->FrameCount > 0 && !this->State.Tiles.empty();
}

void FrameLoop::BlendDepthWindows(
  const TransferFunctionTable& tf, BlendMode mode, const DepthWindow* windows, int count)
{
  if (!this->CanBlendDepthWindows(mode) || count <= 0)
  {
    return;
  }
  // Each tile's own frames, the frames its pixels hold.
  for (const TileSchedule::TileGroup& group :
    this->State.Schedule.Groups([](const Tile& tile) { return tile.Frames; }))
  {
    const std::vector<std::size_t>* tiles = group.second.empty() ? nullptr : &group.second;
    if (this->State.Encoder.Bytes == 1)
    {
      this->Blending.BlendWindows<std::uint8_t>(tf, mode, windows, count, group.first, tiles);
    }
    else
    {
      this->Blending.BlendWindows<std::uint16_t>(tf, mode, windows, count, group.first, tiles);
    }
  }
}

} // namespace savr

// A view's state: its rays, the step its frames sample at, and how the memory budget divides
// between the view's buffers and the stored samples; and what the passes ask of it.

#include "frame/FrameState.h"

#include "frame/PassScratch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <thread>
#include <vector>

namespace savr
{

FrameState::FrameState()
  : Scratch(new ThreadScratch)
{
}

FrameState::~FrameState() = default;

void FrameState::Reset(
  const View& view, std::shared_ptr<const Sampler> sampler, const FrameSettings& settings)
{
  // The old view's samples go first: the new view's buffers must not add to them.
  for (Tile& tile : this->Tiles)
  {
    tile.Stores.Free();
    tile.Paths.Release();
  }
  this->CurrentViewData = view;
  this->CurrentViewData.Prepare();
  this->Source = std::move(sampler);
  this->Settings = settings;
  this->Settings.TileSize = std::max(1, settings.TileSize);
  this->Schedule.SetThreads(this->Settings.Threads);
  // Second codes take the attributes' upper half, where magnitudes would go.
  const bool secondCodes = this->Source && this->Source->HasSecondCode();
  if (secondCodes)
  {
    this->Settings.GradientMagnitudes = false;
  }
  this->Schedule.ResetPass();
  this->Capacity = 0;
  this->TotalSamplesPerFrame = 0;
  this->CoveredPixels = 0;
  this->FrameLimitCount = 0;
  this->Fixed = 0;
  // Buffers only grow: sized afresh for each view, they stay within what is counted for it.
  this->Scratch->Local.clear();
  std::fill(this->Rectangle, this->Rectangle + 4, 0);
  if (!this->Source || view.Width <= 0 || view.Height <= 0 || !(settings.SampleDistance > 0.0))
  {
    this->Pixels.assign(
      static_cast<std::size_t>(std::max(view.Width, 0)) * std::max(view.Height, 0) * 4, 0.0f);
    this->Tiles.clear();
    return;
  }
  this->Encoder = SampleEncoding::ForSampler(
    *this->Source, this->Settings.FineCodes, this->Settings.CodedWindow);
  int pixels[4] = { 0, 0, view.Width, view.Height };
  this->CurrentViewData.HullPixels(*this->Source, pixels);
  std::copy(pixels, pixels + 4, this->Rectangle);

  // What the view needs whatever the samples, checked before any of it is allocated. Kept
  // per-voxel gradients that do not fit give way to gradients computed where asked for.
  this->Fixed = this->ViewBytes();
  if (this->OverBudget() && this->NeedsGradients() && this->Source->ComputeGradientsOnDemand())
  {
    this->Fixed = this->ViewBytes();
  }
  if (this->OverBudget())
  {
    this->Release();
    return;
  }
  // A smaller view than the last frees the rest: what is counted is what is held.
  const std::size_t floats = static_cast<std::size_t>(view.Width) * view.Height * 4;
  if (this->Pixels.capacity() > floats)
  {
    std::vector<float>().swap(this->Pixels);
  }
  this->Pixels.assign(floats, 0.0f);
  this->FindRays();
  this->LimitSamplesPerFrame();
  this->LimitFrames(static_cast<std::size_t>(this->LayOutRays()));
}

void FrameState::LimitFrames(std::size_t longestRay)
{
  // Per thread: a ray's values, codes and gradients, and four rays' offsets and tables.
  const bool gradients = this->NeedsGradients();
  const bool secondCodes = this->Source->HasSecondCode();
  const std::size_t perSample =
    sizeof(float) + sizeof(std::uint32_t) +
    (gradients ? 3 * sizeof(float) + sizeof(std::uint16_t) : 0) +
    (this->Settings.ComponentMagnitudes || this->Settings.ComponentNormals ? 12 * sizeof(float)
                                                                           : 0) +
    (secondCodes ? sizeof(std::uint16_t) : 0);
  const std::size_t perFrame = 4 * (sizeof(double) + sizeof(int) + sizeof(const double*));
  const int threads =
    this->Settings.Threads > 0 ? this->Settings.Threads : tbb::this_task_arena::max_concurrency();
  // Each stored sample's bytes; a thread lays out one tile's first frame at a time, in whole
  // rows of one slot.
  const std::size_t storedBytes = this->CurrentStoreLayout().BytesPerSample();
  std::size_t tileRows = 0;
  for (const Tile& tile : this->Tiles)
  {
    tileRows = std::max(tileRows, tile.Stores.RowCount());
  }
  const std::size_t scratch =
    static_cast<std::size_t>(threads) *
    (((longestRay + 3) & ~std::size_t(3)) * perSample + tileRows * storedBytes +
      static_cast<std::size_t>(std::max(this->Settings.MaximumFrames, 1)) * perFrame);
  this->Fixed += scratch;
  if (this->OverBudget() && this->NeedsGradients() && this->Source->ComputeGradientsOnDemand())
  {
    this->Fixed = this->ViewBytes() + scratch;
  }
  if (this->OverBudget())
  {
    this->Release();
    return;
  }

  // The stored samples have what remains: the most frames whose growth fits.
  const std::size_t bytesPerFrame = this->TotalSamplesPerFrame * storedBytes;
  const int wanted = std::max(this->Settings.MaximumFrames, 1);
  if (bytesPerFrame == 0)
  {
    this->FrameLimitCount = wanted;
    return;
  }
  const std::size_t slots = (this->Settings.MemoryBudget - this->Fixed) / bytesPerFrame;
  int low = 0;
  int high = wanted;
  while (low < high)
  {
    const int middle = low + (high - low + 1) / 2;
    if (RayStores::PeakSlots(middle) <= slots)
    {
      low = middle;
    }
    else
    {
      high = middle - 1;
    }
  }
  this->FrameLimitCount = low;
  this->SharePathBudget(RayStores::PeakSlots(low) * bytesPerFrame);
}

void FrameState::SharePathBudget(std::size_t storedBytes)
{
  if (this->FrameLimitCount < 2 || !this->Settings.TracePaths || !this->Source->TracesPaths() ||
      this->NeedsGradients() || this->Source->HasSecondCode() || this->TotalSamplesPerFrame == 0)
  {
    return;
  }
  // Counted as if every thread of the machine had its scratch, so that which rays keep paths
  // (and so the image) does not depend on the thread count: each ray's path is at most
  // TilePaths::kMaxPieces pieces.
  const int threads = std::max<int>(
    { 1, this->Settings.Threads, static_cast<int>(std::thread::hardware_concurrency()) });
  const std::size_t scratch =
    static_cast<std::size_t>(threads) * TilePaths::kMaxPieces * sizeof(PathPiece);
  const std::size_t used = this->Fixed + storedBytes + scratch;
  if (used >= this->Settings.MemoryBudget)
  {
    return;
  }
  const double left = static_cast<double>(this->Settings.MemoryBudget - used);
  for (Tile& tile : this->Tiles)
  {
    std::size_t samples = 0;
    for (const RayInfo& ray : tile.Rays)
    {
      samples += ray.SamplesPerFrame;
    }
    tile.Paths.Reset(tile.Rays.size(),
      static_cast<std::size_t>(left * samples / static_cast<double>(this->TotalSamplesPerFrame)));
  }
}

std::size_t FrameState::ViewBytes() const
{
  const View& view = this->CurrentViewData;
  const std::size_t viewPixels = static_cast<std::size_t>(view.Width) * view.Height;
  const int* r = this->Rectangle;
  const std::size_t shown =
    static_cast<std::size_t>(std::max(r[2] - r[0], 0)) * std::max(r[3] - r[1], 0);
  // Ray tables are kept by the tiles that meet the rectangle, room for a whole tile each.
  const int ts = this->Settings.TileSize;
  std::size_t tiled = 0;
  if (shown > 0)
  {
    const std::size_t x0 = r[0] / ts * ts;
    const std::size_t y0 = r[1] / ts * ts;
    const std::size_t x1 = std::min<std::size_t>((r[2] + ts - 1) / ts * ts, view.Width);
    const std::size_t y1 = std::min<std::size_t>((r[3] + ts - 1) / ts * ts, view.Height);
    tiled = (x1 - x0) * (y1 - y0);
  }
  const std::size_t tiles =
    static_cast<std::size_t>((view.Width + ts - 1) / ts) * ((view.Height + ts - 1) / ts);
  // The image and the error estimate's earlier image: 4 floats per pixel each.
  return 2 * 4 * sizeof(float) * viewPixels + view.Depth.size() * sizeof(float) +
         tiles * sizeof(Tile) + tiled * sizeof(RayInfo) + this->Settings.ReservedBytes +
         this->Settings.ReservedBytesPerShownPixel * shown +
         (this->NeedsGradients() ? this->Source->GradientBytes() : 0);
}

void FrameState::Release()
{
  std::vector<float>().swap(this->Pixels);
  std::vector<Tile>().swap(this->Tiles);
  std::vector<float>().swap(this->CurrentViewData.Depth);
  std::fill(this->Rectangle, this->Rectangle + 4, 0);
}

void FrameState::FindRays()
{
  const View& view = this->CurrentViewData;
  const int ts = this->Settings.TileSize;
  const std::size_t tilesX = (view.Width + ts - 1) / ts;
  const std::size_t tilesY = (view.Height + ts - 1) / ts;
  this->Tiles.resize(tilesX * tilesY);
  this->Schedule.ResetCosts(tilesX);
  const int* r = this->Rectangle;
  for (std::size_t t = 0; t < this->Tiles.size(); ++t)
  {
    Tile& tile = this->Tiles[t];
    tile.X0 = static_cast<int>(t % tilesX) * ts;
    tile.Y0 = static_cast<int>(t / tilesX) * ts;
    tile.X1 = std::min(tile.X0 + ts, view.Width);
    tile.Y1 = std::min(tile.Y0 + ts, view.Height);
    tile.Rays.clear();
    tile.Frames = 0;
    tile.SnapshotFrames = 0;
    tile.ErrorSum = 0.0;
    tile.Resume = false;
    // Tiles keep their ray tables across resets (while the camera moves, every frame is one),
    // with room for the whole tile where the rectangle meets it and none elsewhere.
    if (tile.X1 <= r[0] || tile.X0 >= r[2] || tile.Y1 <= r[1] || tile.Y0 >= r[3])
    {
      std::vector<RayInfo>().swap(tile.Rays);
    }
    else
    {
      tile.Rays.reserve(static_cast<std::size_t>(tile.X1 - tile.X0) * (tile.Y1 - tile.Y0));
    }
  }
  const Sampler& source = *this->Source;
  // The step before LimitSamplesPerFrame: a step it coarsens takes the kept samples at another
  // phase (a lattice of whole fine steps from the segment's start).
  const double dt = this->Settings.SampleDistance;
  this->ForEachTile(
    [&](Tile& tile, ThreadBuffers&)
    {
      for (int y = std::max(tile.Y0, r[1]); y < std::min(tile.Y1, r[3]); ++y)
      {
        for (int x = std::max(tile.X0, r[0]); x < std::min(tile.X1, r[2]); ++x)
        {
          Ray ray;
          double tEnter = 0.0;
          double tExit = 0.0;
          if (!view.Segment(source, x, y, ray, tEnter, tExit))
          {
            continue;
          }
          // Where the sampler can give no sample (outside a cropping box), whole steps are
          // dropped: the lattice stays where the segment put it, and one step is kept on either
          // side so that the first and last samples inside have the intervals they have on the
          // whole segment.
          double t0 = tEnter;
          double t1 = tExit;
          if (!source.Restrict(ray, t0, t1))
          {
            continue;
          }
          const double before = std::floor((t0 - tEnter) / dt) - 1.0;
          if (before > 0.0)
          {
            tEnter += before * dt;
          }
          if (t1 < tExit)
          {
            tExit = std::min(tExit, tEnter + (std::ceil((t1 - tEnter) / dt) + 1.0) * dt);
          }
          tile.Rays.push_back({ y * view.Width + x, 0, tEnter, tExit - tEnter, 0, 0, 0, 0.0, 0 });
        }
      }
    });
}

void FrameState::LimitSamplesPerFrame()
{
  const std::size_t limit = this->Settings.MaximumSamplesPerFrame;
  if (limit == 0)
  {
    return;
  }
  // In tile order: the same step whatever the thread count.
  double length = 0.0;
  for (const Tile& tile : this->Tiles)
  {
    for (const RayInfo& ray : tile.Rays)
    {
      length += ray.Length;
    }
  }
  double& dt = this->Settings.SampleDistance;
  int& frames = this->Settings.MaximumFrames;
  while (length / dt > static_cast<double>(limit))
  {
    dt *= 2.0;
    frames = std::min(2 * std::max(frames, 1), kMaximumFrames);
  }
}

int FrameState::LayOutRays()
{
  const double dt = this->Settings.SampleDistance;
  const int width = this->CurrentViewData.Width;
  const StoreLayout layout = this->CurrentStoreLayout();
  this->ForEachTile(
    [&](Tile& tile, ThreadBuffers&)
    {
      std::size_t rows = 0;
      for (RayInfo& ray : tile.Rays)
      {
        ray.Length = std::min(ray.Length, kMaxSamplesPerRay * dt);
        ray.SamplesPerFrame = static_cast<int>(std::ceil(ray.Length / dt));
        ray.Horizon = ray.SamplesPerFrame;
        ray.Front = 0;
        ray.Back = ray.SamplesPerFrame;
        ray.Rotation = this->RotationOf(ray.Pixel % width, ray.Pixel / width, dt);
        ray.FirstRow = rows;
        rows += ray.SamplesPerFrame;
      }
      tile.Stores.Lay(layout, rows, 0);
    });
  int longest = 0;
  for (const Tile& tile : this->Tiles)
  {
    this->CoveredPixels += tile.Rays.size();
    for (const RayInfo& ray : tile.Rays)
    {
      this->TotalSamplesPerFrame += ray.SamplesPerFrame;
      longest = std::max(longest, ray.SamplesPerFrame);
    }
  }
  return longest;
}

StoredAttributes FrameState::CurrentAttributes() const
{
  StoredAttributes a;
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

StoreLayout FrameState::CurrentStoreLayout() const
{
  StoreLayout layout;
  layout.CodeBytes = this->Encoder.Bytes;
  layout.Normals = this->Settings.Shade && !this->Settings.ComponentNormals;
  layout.ComponentNormals = this->Settings.Shade && this->Settings.ComponentNormals;
  layout.Magnitudes = this->Settings.GradientMagnitudes;
  layout.ComponentMagnitudes = this->Settings.ComponentMagnitudes;
  layout.SecondCodes = this->Source && this->Source->HasSecondCode();
  return layout;
}

double FrameState::RotationOf(int x, int y, double step) const
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

void FrameState::PrepareGradients()
{
  if (this->NeedsGradients())
  {
    this->InArena([this]() { this->Source->PrepareGradients(); });
  }
}

std::size_t FrameState::MemoryInUse() const
{
  std::size_t bytes = 0;
  for (const Tile& tile : this->Tiles)
  {
    bytes += tile.Stores.MemoryInUse() + tile.Paths.Bytes();
  }
  return bytes;
}

std::uint64_t FrameState::StoredSamples() const
{
  std::uint64_t samples = 0;
  for (const Tile& tile : this->Tiles)
  {
    samples += static_cast<std::uint64_t>(tile.Stores.RowCount()) * tile.Frames;
  }
  return samples;
}

void FrameState::Grow(int capacity, int frames)
{
  this->Capacity = capacity;
  if (frames == 0)
  {
    return; // each tile's first frame allocates its stores
  }
  this->ForEachTile([&](Tile& tile, ThreadBuffers&) { tile.Stores.Grow(capacity, frames); });
}

bool FrameState::TransparentBlocks(
  const TransferFunctionTable& tf, std::vector<std::uint8_t>& skip, std::uint32_t& nanCode) const
{
  const std::vector<float>& ranges = this->Source->BlockRanges();
  const std::uint32_t levels = this->Encoder.Levels;
  // nextVisible[c]: the first code at or after c that is not transparent.
  std::vector<std::uint32_t> nextVisible(levels + 1, levels);
  for (std::uint32_t c = levels; c-- > 0;)
  {
    nextVisible[c] = tf.Extinction(c) > 0.0 ? c : nextVisible[c + 1];
  }
  std::uint32_t transparent = 0;
  while (transparent < levels && tf.Extinction(transparent) > 0.0)
  {
    ++transparent;
  }
  if (ranges.empty() || transparent == levels)
  {
    return false; // no blocks, or nothing is transparent
  }
  if (!this->Encoder.HasNaNCode)
  {
    nanCode = transparent; // skipped samples need a transparent code of their own
  }
  const std::size_t blocks = ranges.size() / 2;
  skip.assign(blocks, 0);
  for (std::size_t b = 0; b < blocks; ++b)
  {
    const float lo = ranges[2 * b];
    const float hi = ranges[2 * b + 1];
    skip[b] = !(lo <= hi) || nextVisible[this->Encoder.Encode(lo)] > this->Encoder.Encode(hi);
  }
  this->Source->SkipDistances(skip);
  return true;
}

} // namespace savr

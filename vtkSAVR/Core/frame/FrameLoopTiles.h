#pragma once
// What the files that implement FrameLoop share: its tiles, the per-thread buffers, how work
// runs over the tiles, and what a tile's blending pass is given.

#include "blend/StoredAVX2.h"
#include "frame/FrameLoop.h"
#include "frame/TilePaths.h"

#include <algorithm>
#include <atomic>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace savr
{

// What a ray keeps between frames; its direction is recomputed from the pixel (cheaply, and
// identically) so that large images do not pay for it in memory.
struct FrameLoop::RayInfo
{
  int Pixel;
  int SamplesPerFrame;
  double TEnter;
  double Length;
  std::size_t FirstRow;
  // Rows every frame has sampled: SamplesPerFrame, or fewer once the first frame found the
  // ray opaque there (its opacity horizon); frames after the first sample these rows only.
  int Horizon;
  // Rows before it are not sampled: the first frame's transfer function makes every block they
  // pass through transparent (its front; FrameLoop::FrontsHold). Frames sample rows
  // [Front, Horizon).
  int Front;
  // FrameLoop::RotationOf its pixel at the loop's step: its frames' offsets are rotated by it.
  double Rotation;
  // Rows from it on are not sampled either: past the last block the ray meets that the first
  // frame's function does not make transparent (its back; SamplesPerFrame when none). The
  // horizon lies at the back or before it.
  int Back;

  // Whether the ray keeps no rows: the first frame's function makes every block it meets
  // transparent, and its composite is empty.
  bool KeepsNoRows() const { return this->Horizon <= this->Front; }
};

struct FrameLoop::Tile
{
  int X0 = 0, Y0 = 0, X1 = 0, Y1 = 0;
  std::vector<RayInfo> Rays;
  SampleStore Store;
  SampleStore Normals;             // used only when shading
  SampleStore Magnitudes;          // used only with gradient opacity
  SampleStore ComponentNormals;    // used only when shading independent components
  SampleStore ComponentMagnitudes; // used only with independent components' gradient opacity
  SampleStore SecondCodes;         // used only when the sampler has second codes
  TilePaths Paths;                 // while accumulating, for samplers that trace paths
  int Frames = 0;                  // frames its rays have taken (see SetTileTolerance)
  int SnapshotFrames = 0;          // frames of its pixels in the snapshot (0: none valid)
  double ErrorSum = 0.0;           // its share of the error estimate's sum of squares
  bool Resume = false;             // a ray's blend is not opaque at its horizon: sample it whole

  // Calls f(store, its counterpart in `other`) for each store.
  template <typename F>
  void EachStore(Tile& other, F&& f)
  {
    f(this->Store, other.Store);
    f(this->Normals, other.Normals);
    f(this->Magnitudes, other.Magnitudes);
    f(this->ComponentNormals, other.ComponentNormals);
    f(this->ComponentMagnitudes, other.ComponentMagnitudes);
    f(this->SecondCodes, other.SecondCodes);
  }
};

struct FrameLoop::Buffers
{
  std::vector<float> Values;
  std::vector<float> Gradients;
  std::vector<std::uint16_t> SecondCodes;
  std::vector<std::uint16_t> Normals;
  std::vector<double> U;
  std::vector<int> Order;
  std::vector<const double*> Tables;
  std::vector<std::uint32_t> Codes;
  std::vector<float> ComponentGradients;    // each component's, with their gradient opacity
  std::vector<SampleAttributes> Attributes; // a single pass's chunk: normal and magnitude codes
  std::vector<PathPiece> Path;              // a ray's path as it is traced
  std::size_t Sampled = 0;                  // samples the tile at hand took
  // A tile's stores while its rays' rows are laid out anew: its first frame, sampled here
  // with whole rows of one slot, and the stores a resumption lays out (FrameLoop::SampleTile,
  // FrameLoop::ResumeRays).
  Tile Relaid;
  std::vector<char> Flags; // per ray of the tile at hand
};

struct FrameLoop::Scratch
{
  tbb::enumerable_thread_specific<Buffers> Local;
};

template <typename Code>
struct FrameLoop::StoredRows
{
  Code* Codes = nullptr;
  std::uint16_t* Normals = nullptr;             // when shading
  std::uint8_t* Magnitudes = nullptr;           // with gradient opacity
  std::uint64_t* ComponentNormals = nullptr;    // when shading independent components
  std::uint32_t* ComponentMagnitudes = nullptr; // with independent components' gradient opacity
  std::uint16_t* SecondCodes = nullptr;         // when the sampler has second codes
  int Capacity = 1;                             // slots per row

  static StoredRows Of(
    Tile& tile, std::size_t firstRow, const Attributes& attributes, bool secondCodes)
  {
    StoredRows rows;
    rows.Codes = tile.Store.template Row<Code>(firstRow);
    rows.Capacity = tile.Store.SlotCapacity();
    rows.Normals =
      attributes.Normals ? tile.Normals.template Row<std::uint16_t>(firstRow) : nullptr;
    rows.Magnitudes =
      attributes.Magnitudes ? tile.Magnitudes.template Row<std::uint8_t>(firstRow) : nullptr;
    rows.ComponentNormals = attributes.ComponentNormals
                              ? tile.ComponentNormals.template Row<std::uint64_t>(firstRow)
                              : nullptr;
    rows.ComponentMagnitudes = attributes.ComponentMagnitudes
                                 ? tile.ComponentMagnitudes.template Row<std::uint32_t>(firstRow)
                                 : nullptr;
    rows.SecondCodes =
      secondCodes ? tile.SecondCodes.template Row<std::uint16_t>(firstRow) : nullptr;
    return rows;
  }

  /// Rows `first` on: the same rows, shifted.
  StoredRows From(int first) const
  {
    const std::size_t k = static_cast<std::size_t>(first) * this->Capacity;
    StoredRows rows = *this;
    rows.Codes += k;
    rows.Normals = rows.Normals ? rows.Normals + k : nullptr;
    rows.Magnitudes = rows.Magnitudes ? rows.Magnitudes + k : nullptr;
    rows.ComponentNormals = rows.ComponentNormals ? rows.ComponentNormals + k : nullptr;
    rows.ComponentMagnitudes = rows.ComponentMagnitudes ? rows.ComponentMagnitudes + k : nullptr;
    rows.SecondCodes = rows.SecondCodes ? rows.SecondCodes + k : nullptr;
    return rows;
  }

  /// The first `frames` frames of `ray` in these rows, the slots' offsets `u` in `order`: up
  /// to its horizon, where the ray ends for the blends.
  RayLayout<Code> Layout(
    const RayInfo& ray, int frames, const double* u, const int* order, double dt) const
  {
    RayLayout<Code> layout;
    layout.Codes = this->Codes;
    layout.Normals = this->Normals;
    layout.Magnitudes = this->Magnitudes;
    layout.ComponentNormals = this->ComponentNormals;
    layout.ComponentMagnitudes = this->ComponentMagnitudes;
    layout.SecondCodes = this->SecondCodes;
    layout.SamplesPerFrame = ray.Horizon;
    layout.FirstRow = ray.Front;
    layout.Capacity = this->Capacity;
    layout.Frames = frames;
    layout.U = u;
    layout.Order = order;
    layout.Dt = dt;
    layout.Length =
      ray.Horizon < ray.SamplesPerFrame ? std::min(ray.Length, ray.Horizon * dt) : ray.Length;
    return layout;
  }
};

template <typename Work>
void FrameLoop::InArena(Work&& work)
{
  if (this->Settings.Threads > 0)
  {
    tbb::task_arena arena(this->Settings.Threads);
    arena.execute(work);
  }
  else
  {
    work();
  }
}

template <typename Body>
std::size_t FrameLoop::ForEachTile(
  Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles)
{
  const std::size_t count = tiles ? tiles->size() : this->Tiles.size();
  if (seconds > 0.0)
  {
    return this->ForEachTileWithin(body, first, seconds, tiles);
  }
  this->InArena(
    [&]()
    {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(std::min(first, count), count, 1),
        [&](const tbb::blocked_range<std::size_t>& range)
        {
          Buffers& buffers = this->ThreadScratch->Local.local();
          for (std::size_t t = range.begin(); t != range.end(); ++t)
          {
            body(this->Tiles[tiles ? (*tiles)[t] : t], buffers);
          }
        });
    });
  return count;
}

template <typename Body>
std::size_t FrameLoop::ForEachTileWithin(
  Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles)
{
  const std::size_t count = tiles ? tiles->size() : this->Tiles.size();
  const auto tileAt = [&](std::size_t t) -> Tile& { return this->Tiles[tiles ? (*tiles)[t] : t]; };
  // A tile's work: its rays and their samples per frame (an empty tile costs next to nothing,
  // one the data fills the most).
  const auto work = [&](std::size_t t)
  {
    const Tile& tile = tileAt(t);
    double samples = 1.0 + double(tile.Rays.size());
    for (const RayInfo& ray : tile.Rays)
    {
      samples += ray.SamplesPerFrame;
    }
    return samples;
  };
  // Tiles in order, each thread taking the next one while the bound is not passed, so that the
  // tiles done are the ones before the returned index whatever the timing, and the bound is
  // passed by one tile per thread at most. No tile but a call's first starts that is estimated
  // to pass the bound by more than a quarter of it: its work at the highest cost per unit of
  // work of its own last run and of the tile above it in this frame, or, with neither
  // measured, at the highest of this frame (kept over the calls that continue it). The cost of
  // a unit of work varies from tile to tile (particles: with the density of the cloud the rays
  // cross, 50 times over a few tiles) and changes little from one tile to the next below it.
  const std::size_t threads = static_cast<std::size_t>(
    this->Settings.Threads > 0 ? this->Settings.Threads : tbb::this_task_arena::max_concurrency());
  const int ts = this->Settings.TileSize;
  const std::size_t tilesX = static_cast<std::size_t>((this->CurrentViewData.Width + ts - 1) / ts);
  if (first == 0)
  {
    ++this->TimedFrame;
    this->HighestTileRate = 0.0;
  }
  const std::uint64_t frame = this->TimedFrame;
  std::atomic<double> highest{ this->HighestTileRate };
  // A tile's cost as TileCosts holds it (the frame's low 32 bits over the rate's float bits).
  const std::uint64_t stamp = (frame & 0xffffffffu) << 32;
  const auto pack = [stamp](double rate)
  {
    const float narrow = static_cast<float>(rate);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &narrow, sizeof bits);
    return stamp | bits;
  };
  const auto rateOf = [](std::uint64_t packed)
  {
    const std::uint32_t bits = static_cast<std::uint32_t>(packed);
    float rate = 0.0f;
    std::memcpy(&rate, &bits, sizeof rate);
    return static_cast<double>(rate);
  };
  // A tile's estimated time, 0 when nothing is known yet.
  const auto estimate = [&](std::size_t t)
  {
    const std::size_t index = tiles ? (*tiles)[t] : t;
    double rate = rateOf(this->TileCosts[index].load(std::memory_order_relaxed));
    if (index >= tilesX && !this->Tiles[index - tilesX].Rays.empty())
    {
      const std::uint64_t above = this->TileCosts[index - tilesX].load(std::memory_order_relaxed);
      if ((above & ~std::uint64_t(0xffffffffu)) == stamp)
      {
        rate = std::max(rate, rateOf(above));
      }
    }
    return (rate > 0.0 ? rate : highest.load()) * work(t);
  };
  const std::size_t begin = std::min(first, count);
  std::atomic<std::size_t> cursor{ begin };
  const double start = this->Now();
  this->InArena(
    [&]()
    {
      tbb::parallel_for(std::size_t(0), std::max<std::size_t>(threads, 1),
        [&](std::size_t)
        {
          Buffers& buffers = this->ThreadScratch->Local.local();
          std::size_t t = cursor.load();
          while (t < count)
          {
            if (t != begin)
            {
              const double elapsed = this->Now() - start;
              if (elapsed >= seconds || elapsed + estimate(t) > 1.25 * seconds)
              {
                return;
              }
            }
            if (!cursor.compare_exchange_weak(t, t + 1))
            {
              continue; // another thread took it: t is the cursor now
            }
            Tile& tile = tileAt(t);
            const double started = this->Now();
            body(tile, buffers);
            const double rate = (this->Now() - started) / work(t);
            this->TileCosts[tiles ? (*tiles)[t] : t].store(pack(rate), std::memory_order_relaxed);
            // Empty tiles' few microseconds are mostly the clock's.
            double seen = highest.load();
            while (!tile.Rays.empty() && rate > seen && !highest.compare_exchange_weak(seen, rate))
            {
            }
            t = cursor.load();
          }
        });
    });
  this->HighestTileRate = highest.load();
  const std::size_t next = std::min(cursor.load(), count);
  return next;
}

// What the blending pass of every tile of a frame shares (FrameLoop::TilePasses, BlendTile).
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

} // namespace savr

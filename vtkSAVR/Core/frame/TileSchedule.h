#pragma once
// The frame loop's tile schedule: which tiles the next frame's pass takes (tiles to resume
// first, then those with the fewest frames, settled tiles none), how a frame under way is split
// over calls, and how a pass runs over its tiles on TBB, in a fixed order and, when given one,
// within a time bound. It decides which tiles are worked on, never what a tile's pixels are, so
// images do not depend on it, the thread count or the timing.

#include "frame/Tile.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace savr
{

/// The next frame's pass (TileSchedule::ChoosePass) and how far a frame under way has come.
struct FramePass
{
  std::vector<std::size_t> Tiles;  // the pass's tiles, when not all
  bool All = true;                 // every tile takes the frame
  bool Resume = false;             // the pass resumes rays of its tiles (Tile::Resume)
  int Frames = 0;                  // frames the pass's tiles have taken: the slot they fill
  std::size_t NextTile = 0;        // the next tile of the frame under way, 0 when none is
  std::uint64_t NextTileBlend = 0; // the tables and mode the frame under way blends with
};

class TileSchedule
{
public:
  /// Seconds since some fixed point, as a time bound reads them. Called from several threads at
  /// once.
  using Clock = std::function<double()>;
  /// A frame count and the tiles that have it (empty: every tile).
  using TileGroup = std::pair<int, std::vector<std::size_t>>;

  /// Schedules `tiles`, which the caller owns and lays out (see Reset).
  explicit TileSchedule(std::vector<Tile>& tiles);

  /// The clock that time bounds read; by default std::chrono::steady_clock. (Null restores the
  /// default.)
  void SetClock(Clock clock);
  double Now() const { return this->Time(); }

  /// Passes run in an arena of this many threads; 0 (the default): TBB's.
  void SetThreads(int threads) { this->Threads = std::max(threads, 0); }
  /// Runs `work` in that arena.
  template <typename Work>
  void InArena(Work&& work) const;

  /// Forgets the pass under way and chooses none: every tile, none of its frames taken.
  void ResetPass();
  /// After the tiles were laid out anew, `tilesPerRow` to a row of the image: forgets their costs.
  void ResetCosts(std::size_t tilesPerRow);

  /// With a tolerance > 0, a tile whose share of the error estimate (Tile::ErrorSum, as a root
  /// mean square over its pixels' four channels) is below it is settled: it takes no more
  /// frames. 0 (the default): none is.
  void SetTolerance(double tolerance) { this->Tolerance = std::max(tolerance, 0.0); }
  bool Settled(const Tile& tile) const;
  /// Tiles with rays that are settled below `frameLimit` frames.
  std::size_t SettledTiles(int frameLimit) const;
  /// The tiles whose `frames` (a frame count of a tile) is positive, grouped by it, ascending;
  /// a group of every tile has no list.
  std::vector<TileGroup> Groups(int (*frames)(const Tile&)) const;

  /// The next frame's pass: the tiles marked for resuming with the fewest frames, else the tiles
  /// that are not settled and have taken the fewest frames, or none, Frames at `frameLimit` (at
  /// least 1), when every tile is settled or done.
  void ChoosePass(int frameLimit);
  const FramePass& Pass() const { return this->Current; }
  /// The pass's tiles; null when it takes every tile.
  const std::vector<std::size_t>* PassTiles() const
  {
    return this->Current.All ? nullptr : &this->Current.Tiles;
  }
  std::size_t PassSize() const
  {
    return this->Current.All ? this->Tiles.size() : this->Current.Tiles.size();
  }
  /// The fraction of the pass's tiles that a frame under way has done.
  double Progress() const
  {
    const std::size_t size = this->PassSize();
    return size == 0 ? 0.0 : double(this->Current.NextTile) / double(size);
  }
  /// The frame under way goes on at the pass's tile `next` (0: none is under way).
  void ContinueAt(std::size_t next) { this->Current.NextTile = next; }
  /// The tables and mode (a key) the frame under way blends with.
  void BlendWith(std::uint64_t key) { this->Current.NextTileBlend = key; }
  /// Every tile has taken `frames` frames that stored nothing: the pass takes none.
  void Conclude(int frames) { this->Current.Frames = frames; }

  /// Runs `body(tile)` on every tile (of `tiles`, indices, when given) from `first` on, in
  /// parallel, one thread at a time on a tile. With `seconds` > 0, in order, each thread taking
  /// the next tile until the bound is passed or the tile is estimated to pass it by more than a
  /// quarter of it (a call's first tile is always done), timing each tile. Returns the next tile.
  template <typename Body>
  std::size_t ForEach(Body&& body, std::size_t first = 0, double seconds = 0.0,
    const std::vector<std::size_t>* tiles = nullptr);

private:
  template <typename Body>
  std::size_t ForEachWithin(
    Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles);

  std::vector<Tile>& Tiles;
  FramePass Current;
  Clock Time;
  int Threads = 0;
  double Tolerance = 0.0;
  std::size_t TilesPerRow = 1;
  // Counts the frames ForEachWithin has run, and the highest cost per unit of work of a tile
  // with rays in the last one.
  std::uint64_t TimedFrame = 0;
  double HighestTileRate = 0.0;
  // Each tile's cost the last time a bounded call ran it: the low 32 bits of that call's frame
  // (TimedFrame) over the float bits of its seconds per unit of work; 0 when not measured since
  // the tiles were laid out. Atomic: a thread estimating its next tile reads the tile above,
  // which another thread may be writing.
  std::unique_ptr<std::atomic<std::uint64_t>[]> Costs;
  std::size_t CostCount = 0;
};

template <typename Work>
void TileSchedule::InArena(Work&& work) const
{
  if (this->Threads > 0)
  {
    tbb::task_arena arena(this->Threads);
    arena.execute(work);
  }
  else
  {
    work();
  }
}

template <typename Body>
std::size_t TileSchedule::ForEach(
  Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles)
{
  const std::size_t count = tiles ? tiles->size() : this->Tiles.size();
  if (seconds > 0.0)
  {
    return this->ForEachWithin(body, first, seconds, tiles);
  }
  this->InArena(
    [&]()
    {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(std::min(first, count), count, 1),
        [&](const tbb::blocked_range<std::size_t>& range)
        {
          for (std::size_t t = range.begin(); t != range.end(); ++t)
          {
            body(this->Tiles[tiles ? (*tiles)[t] : t]);
          }
        });
    });
  return count;
}

template <typename Body>
std::size_t TileSchedule::ForEachWithin(
  Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles)
{
  const std::size_t count = tiles ? tiles->size() : this->Tiles.size();
  const auto indexOf = [&](std::size_t t) { return tiles ? (*tiles)[t] : t; };
  // Tiles in order, each thread taking the next one while the bound is not passed, so that the
  // tiles done are the ones before the returned index whatever the timing, and the bound is
  // passed by one tile per thread at most. No tile but a call's first starts that is estimated
  // to pass the bound by more than a quarter of it: its work at the highest cost per unit of
  // work of its own last run and of the tile above it in this frame, or, with neither
  // measured, at the highest of this frame (kept over the calls that continue it). The cost of
  // a unit of work varies from tile to tile (particles: with the density of the cloud the rays
  // cross, 50 times over a few tiles) and changes little from one tile to the next below it.
  const std::size_t threads = static_cast<std::size_t>(
    this->Threads > 0 ? this->Threads : tbb::this_task_arena::max_concurrency());
  const std::size_t tilesX = this->TilesPerRow;
  if (first == 0)
  {
    ++this->TimedFrame;
    this->HighestTileRate = 0.0;
  }
  const std::uint64_t frame = this->TimedFrame;
  std::atomic<double> highest{ this->HighestTileRate };
  // A tile's cost as Costs holds it (the frame's low 32 bits over the rate's float bits).
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
    const std::size_t index = indexOf(t);
    double rate = rateOf(this->Costs[index].load(std::memory_order_relaxed));
    if (index >= tilesX && !this->Tiles[index - tilesX].Rays.empty())
    {
      const std::uint64_t above = this->Costs[index - tilesX].load(std::memory_order_relaxed);
      if ((above & ~std::uint64_t(0xffffffffu)) == stamp)
      {
        rate = std::max(rate, rateOf(above));
      }
    }
    return (rate > 0.0 ? rate : highest.load()) * this->Tiles[index].Work();
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
            Tile& tile = this->Tiles[indexOf(t)];
            const double started = this->Now();
            body(tile);
            const double rate = (this->Now() - started) / tile.Work();
            this->Costs[indexOf(t)].store(pack(rate), std::memory_order_relaxed);
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
  return std::min(cursor.load(), count);
}

} // namespace savr

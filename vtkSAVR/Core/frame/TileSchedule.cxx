// Which tiles a frame's pass takes: each tile has taken its own number of frames; tiles whose
// rays wait to be resumed go first, then those behind, and a tile tolerance settles the tiles
// whose error estimate has fallen below it.

#include "frame/TileSchedule.h"

#include <chrono>
#include <limits>
#include <map>

namespace savr
{

TileSchedule::TileSchedule(std::vector<Tile>& tiles)
  : Tiles(tiles)
{
  this->SetClock(nullptr);
}

void TileSchedule::SetClock(Clock clock)
{
  if (!clock)
  {
    clock = []()
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
    };
  }
  this->Time = std::move(clock);
}

void TileSchedule::ResetPass()
{
  this->Current = FramePass();
}

void TileSchedule::ResetCosts(std::size_t tilesPerRow)
{
  this->TilesPerRow = std::max<std::size_t>(tilesPerRow, 1);
  if (this->CostCount != this->Tiles.size() || !this->Costs)
  {
    this->Costs.reset(new std::atomic<std::uint64_t>[this->Tiles.size()]);
    this->CostCount = this->Tiles.size();
  }
  for (std::size_t t = 0; t < this->CostCount; ++t)
  {
    this->Costs[t].store(0, std::memory_order_relaxed);
  }
}

bool TileSchedule::Settled(const Tile& tile) const
{
  if (!(this->Tolerance > 0.0) || tile.Frames < 2)
  {
    return false;
  }
  // Below the tolerance as a root mean square over the tile's covered pixels' four channels.
  const double squares =
    this->Tolerance * this->Tolerance * 4.0 * static_cast<double>(tile.Rays.size());
  return tile.Rays.empty() || tile.ErrorSum < squares;
}

std::size_t TileSchedule::SettledTiles(int frameLimit) const
{
  std::size_t settled = 0;
  for (const Tile& tile : this->Tiles)
  {
    settled += !tile.Rays.empty() && tile.Frames < frameLimit && this->Settled(tile);
  }
  return settled;
}

std::vector<TileSchedule::TileGroup> TileSchedule::Groups(int (*frames)(const Tile&)) const
{
  std::map<int, std::vector<std::size_t>> groups;
  for (std::size_t t = 0; t < this->Tiles.size(); ++t)
  {
    const int f = frames(this->Tiles[t]);
    if (f > 0)
    {
      groups[f].push_back(t);
    }
  }
  std::vector<TileGroup> ordered(groups.begin(), groups.end());
  if (ordered.size() == 1 && ordered[0].second.size() == this->Tiles.size())
  {
    ordered[0].second.clear(); // every tile
  }
  return ordered;
}

void TileSchedule::ChoosePass(int frameLimit)
{
  FramePass& pass = this->Current;
  const int limit = std::max(frameLimit, 1);
  // Tiles to resume come first, whatever their frames or tolerance.
  int fewest = std::numeric_limits<int>::max();
  for (const Tile& tile : this->Tiles)
  {
    if (tile.Resume)
    {
      fewest = std::min(fewest, tile.Frames);
    }
  }
  pass.Resume = fewest != std::numeric_limits<int>::max();
  const auto inPass = [&](const Tile& tile)
  { return pass.Resume ? tile.Resume : !this->Settled(tile); };
  if (!pass.Resume)
  {
    fewest = limit;
    for (const Tile& tile : this->Tiles)
    {
      if (tile.Frames < fewest && inPass(tile))
      {
        fewest = tile.Frames;
      }
    }
  }
  pass.Frames = fewest;
  pass.Tiles.clear();
  if (!pass.Resume && fewest >= limit)
  {
    pass.All = false;
    return;
  }
  for (std::size_t t = 0; t < this->Tiles.size(); ++t)
  {
    const Tile& tile = this->Tiles[t];
    if (tile.Frames == fewest && inPass(tile))
    {
      pass.Tiles.push_back(t);
    }
  }
  pass.All = pass.Tiles.size() == this->Tiles.size();
  if (pass.All)
  {
    pass.Tiles.clear();
  }
}

} // namespace savr

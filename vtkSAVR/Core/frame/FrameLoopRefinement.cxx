// Which tiles a frame refines, and the error estimate they answer to: each tile has taken its
// own number of frames, compares its image with its own at the power of two of frames below,
// and with a tile tolerance stops once that change is below it.

#include "frame/FrameLoop.h"

#include "frame/FrameLoopTiles.h"

#include <cmath>
#include <limits>
#include <map>

namespace savr
{
namespace
{
// The largest power of two below `frames` (at least 2 frames).
int EarlierFrames(int frames)
{
  int earlier = 1;
  while (2 * earlier < frames)
  {
    earlier *= 2;
  }
  return earlier;
}
} // namespace

bool FrameLoop::Settled(const Tile& tile) const
{
  if (!(this->TileTolerance > 0.0) || tile.Frames < 2)
  {
    return false;
  }
  // Below the tolerance as a root mean square over the tile's covered pixels' four channels.
  const double squares =
    this->TileTolerance * this->TileTolerance * 4.0 * static_cast<double>(tile.Rays.size());
  return tile.Rays.empty() || tile.ErrorSum < squares;
}

std::size_t FrameLoop::SettledTiles() const
{
  std::size_t settled = 0;
  for (const Tile& tile : this->Tiles)
  {
    settled += !tile.Rays.empty() && tile.Frames < this->FrameLimitCount && this->Settled(tile);
  }
  return settled;
}

std::vector<FrameLoop::TileGroup> FrameLoop::TileGroups(int (*frames)(const Tile&)) const
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

void FrameLoop::ChoosePass()
{
  const int limit = std::max(this->FrameLimitCount, 1);
  // Tiles to resume come first, whatever their frames or tolerance.
  int fewest = std::numeric_limits<int>::max();
  for (const Tile& tile : this->Tiles)
  {
    if (tile.Resume)
    {
      fewest = std::min(fewest, tile.Frames);
    }
  }
  this->Pass.Resume = fewest != std::numeric_limits<int>::max();
  const auto inPass = [&](const Tile& tile)
  { return this->Pass.Resume ? tile.Resume : !this->Settled(tile); };
  if (!this->Pass.Resume)
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
  this->Pass.Frames = fewest;
  this->Pass.Tiles.clear();
  if (!this->Pass.Resume && fewest >= limit)
  {
    this->Pass.All = false;
    return;
  }
  for (std::size_t t = 0; t < this->Tiles.size(); ++t)
  {
    const Tile& tile = this->Tiles[t];
    if (tile.Frames == fewest && inPass(tile))
    {
      this->Pass.Tiles.push_back(t);
    }
  }
  this->Pass.All = this->Pass.Tiles.size() == this->Tiles.size();
  if (this->Pass.All)
  {
    this->Pass.Tiles.clear();
  }
}

void FrameLoop::BlendOwnFrames(const TransferFunctionTable& tf, BlendMode mode, float* target)
{
  for (const TileGroup& group : this->TileGroups([](const Tile& tile) { return tile.Frames; }))
  {
    this->BlendStored(
      tf, mode, group.first, target, group.second.empty() ? nullptr : &group.second);
  }
}

void FrameLoop::UpdateErrorEstimate(const TransferFunctionTable& tf, BlendMode mode,
  const std::vector<std::size_t>* tiles, bool reblended)
{
  // Snapshots blended with other tables or another mode no longer hold.
  const std::uint64_t shading = this->Inputs.Generation();
  if (this->Errors.Generation != tf.Generation() || this->Errors.Mode != mode ||
      this->Errors.Shading != shading)
  {
    for (Tile& tile : this->Tiles)
    {
      tile.SnapshotFrames = 0;
    }
    this->Errors.Generation = tf.Generation();
    this->Errors.Mode = mode;
    this->Errors.Shading = shading;
  }
  if (this->Errors.Image.size() != this->Pixels.size())
  {
    this->Errors.Image.assign(this->Pixels.size(), 0.0f);
  }
  std::vector<std::size_t> all;
  if (!tiles)
  {
    all.resize(this->Tiles.size());
    for (std::size_t t = 0; t < all.size(); ++t)
    {
      all[t] = t;
    }
    tiles = &all;
  }
  // Tiles whose comparison image is not the snapshot's: blended again, by frames.
  std::map<int, std::vector<std::size_t>> stale;
  for (const std::size_t t : *tiles)
  {
    const Tile& tile = this->Tiles[t];
    if (tile.Frames >= 2 && tile.SnapshotFrames != EarlierFrames(tile.Frames))
    {
      stale[EarlierFrames(tile.Frames)].push_back(t);
    }
  }
  for (const auto& group : stale)
  {
    this->BlendStored(tf, mode, group.first, this->Errors.Image.data(), &group.second);
    for (const std::size_t t : group.second)
    {
      this->Tiles[t].SnapshotFrames = group.first;
    }
  }
  // Each tile's sum of squared changes over its covered pixels (zero outside them in both).
  const std::size_t width = static_cast<std::size_t>(this->CurrentViewData.Width);
  const float* now = this->Pixels.data();
  float* then = this->Errors.Image.data();
  this->ForEachTile(
    [&](Tile& tile, Buffers&)
    {
      double sum = 0.0;
      for (const RayInfo& ray : tile.Rays)
      {
        const std::size_t i = 4 * static_cast<std::size_t>(ray.Pixel);
        for (std::size_t c = i; c < i + 4; ++c)
        {
          const double d = static_cast<double>(now[c]) - then[c];
          sum += d * d;
        }
      }
      tile.ErrorSum = tile.Frames >= 2 ? sum : 0.0;
      // The next frames of a tile at a power of two compare with its image now.
      if (!reblended && tile.Frames >= 1 && (tile.Frames & (tile.Frames - 1)) == 0)
      {
        for (int y = tile.Y0; y < tile.Y1; ++y)
        {
          const std::size_t row = 4 * (static_cast<std::size_t>(y) * width);
          std::copy(now + row + 4 * tile.X0, now + row + 4 * tile.X1, then + row + 4 * tile.X0);
        }
        tile.SnapshotFrames = tile.Frames;
      }
    },
    0, 0.0, tiles);
  // The whole estimate once every tile with rays has two frames and none waits to resume rays,
  // over the covered pixels, the tiles' sums added in order: the same bits whatever the thread
  // count.
  double sum = 0.0;
  for (const Tile& tile : this->Tiles)
  {
    if ((!tile.Rays.empty() && tile.Frames < 2) || tile.Resume)
    {
      this->Errors.Estimate = -1.0; // not yet
      return;
    }
    sum += tile.ErrorSum;
  }
  this->Errors.Estimate = std::sqrt(sum / std::max<std::size_t>(4 * this->CoveredPixels, 1));
}

} // namespace savr

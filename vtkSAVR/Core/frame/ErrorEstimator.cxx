// The error estimate: snapshots at powers of two of each tile's frames, and the change since.

#include "frame/ErrorEstimator.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace savr
{

ErrorEstimator::ErrorEstimator(std::vector<Tile>& tiles, TileSchedule& schedule)
  : Tiles(tiles)
  , Schedule(schedule)
{
}

int ErrorEstimator::EarlierFrames(int frames)
{
  int earlier = 1;
  while (2 * earlier < frames)
  {
    earlier *= 2;
  }
  return earlier;
}

void ErrorEstimator::Reset()
{
  this->Image.clear();
  this->Blended.TransferFunction = 0;
  this->Estimate = -1.0;
}

void ErrorEstimator::Release()
{
  std::vector<float>().swap(this->Image);
}

void ErrorEstimator::Update(const std::vector<float>& image, int width, std::size_t covered,
  const BlendIdentity& blend, const std::vector<std::size_t>* tiles, bool reblended,
  const BlendFrames& blendEarlier)
{
  // Snapshots blended with other tables or another mode no longer hold.
  if (this->Blended != blend)
  {
    for (Tile& tile : this->Tiles)
    {
      tile.SnapshotFrames = 0;
    }
    this->Blended = blend;
  }
  if (this->Image.size() != image.size())
  {
    this->Image.assign(image.size(), 0.0f);
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
    blendEarlier(group.first, this->Image.data(), group.second);
    for (const std::size_t t : group.second)
    {
      this->Tiles[t].SnapshotFrames = group.first;
    }
  }
  // Each tile's sum of squared changes over its covered pixels (zero outside them in both).
  const std::size_t rowPixels = static_cast<std::size_t>(width);
  const float* now = image.data();
  float* then = this->Image.data();
  this->Schedule.ForEach(
    [&](Tile& tile)
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
          const std::size_t row = 4 * (static_cast<std::size_t>(y) * rowPixels);
          std::copy(now + row + 4 * tile.X0, now + row + 4 * tile.X1, then + row + 4 * tile.X0);
        }
        tile.SnapshotFrames = tile.Frames;
      }
    },
    0, 0.0, tiles);
  double sum = 0.0;
  for (const Tile& tile : this->Tiles)
  {
    if ((!tile.Rays.empty() && tile.Frames < 2) || tile.Resume)
    {
      this->Estimate = -1.0; // not yet
      return;
    }
    sum += tile.ErrorSum;
  }
  this->Estimate = std::sqrt(sum / std::max<std::size_t>(4 * covered, 1));
}

} // namespace savr

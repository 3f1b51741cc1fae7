// The tile schedule alone: which tiles a pass takes, and how a pass runs over them in order
// within a time bound, on a clock that the tiles' work advances.

#include "frame/TileSchedule.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <vector>

namespace
{
// Tiles in one row, each with one ray of `work` - 2 samples per frame: Tile::Work() is `work`.
std::vector<savr::Tile> TilesOfWork(const std::vector<int>& work)
{
  std::vector<savr::Tile> tiles(work.size());
  for (std::size_t t = 0; t < tiles.size(); ++t)
  {
    savr::RayInfo ray{};
    ray.SamplesPerFrame = work[t] - 2;
    tiles[t].Rays.push_back(ray);
  }
  return tiles;
}

// A clock in microseconds of work, advanced by the tiles the schedule runs.
struct WorkClock
{
  std::atomic<std::int64_t> Micro{ 0 };
  double Seconds() const { return 1e-6 * static_cast<double>(this->Micro.load()); }
};
} // namespace

TEST(TileSchedule, APassTakesTheTilesWithTheFewestFrames)
{
  std::vector<savr::Tile> tiles = TilesOfWork({ 10, 10, 10, 10 });
  savr::TileSchedule schedule(tiles);
  const int frames[] = { 2, 1, 1, 3 };
  for (std::size_t t = 0; t < tiles.size(); ++t)
  {
    tiles[t].Frames = frames[t];
  }
  schedule.ChoosePass(8);
  EXPECT_FALSE(schedule.Pass().Resume);
  EXPECT_EQ(schedule.Pass().Frames, 1);
  ASSERT_NE(schedule.PassTiles(), nullptr);
  EXPECT_EQ(*schedule.PassTiles(), (std::vector<std::size_t>{ 1, 2 }));
  EXPECT_EQ(schedule.PassSize(), 2u);

  // Tiles whose rays wait to be resumed go first, whatever their frames.
  tiles[3].Resume = true;
  schedule.ChoosePass(8);
  EXPECT_TRUE(schedule.Pass().Resume);
  EXPECT_EQ(schedule.Pass().Frames, 3);
  EXPECT_EQ(*schedule.PassTiles(), (std::vector<std::size_t>{ 3 }));

  // Every tile at the same count: every tile, no list.
  tiles[3].Resume = false;
  for (savr::Tile& tile : tiles)
  {
    tile.Frames = 4;
  }
  schedule.ChoosePass(8);
  EXPECT_TRUE(schedule.Pass().All);
  EXPECT_EQ(schedule.PassTiles(), nullptr);
  EXPECT_EQ(schedule.PassSize(), tiles.size());

  // At the limit: no tile, and the pass's frames are the limit's.
  schedule.ChoosePass(4);
  EXPECT_FALSE(schedule.Pass().All);
  EXPECT_EQ(schedule.PassSize(), 0u);
  EXPECT_EQ(schedule.Pass().Frames, 4);
}

TEST(TileSchedule, SettledTilesTakeNoFrames)
{
  std::vector<savr::Tile> tiles = TilesOfWork({ 10, 10, 10 });
  savr::TileSchedule schedule(tiles);
  for (savr::Tile& tile : tiles)
  {
    tile.Frames = 2;
    tile.ErrorSum = 1.0;
  }
  // A root mean square over one pixel's four channels: sqrt(ErrorSum / 4).
  tiles[1].ErrorSum = 4.0 * 0.01 * 0.01 * 0.5;
  EXPECT_FALSE(schedule.Settled(tiles[1])); // no tolerance: none settles
  schedule.SetTolerance(0.01);
  EXPECT_TRUE(schedule.Settled(tiles[1]));
  EXPECT_FALSE(schedule.Settled(tiles[0]));
  EXPECT_EQ(schedule.SettledTiles(16), 1u);
  EXPECT_EQ(schedule.SettledTiles(2), 0u); // at the limit, done rather than settled
  schedule.ChoosePass(16);
  EXPECT_EQ(*schedule.PassTiles(), (std::vector<std::size_t>{ 0, 2 }));
  // One frame says nothing of the error yet.
  tiles[1].Frames = 1;
  EXPECT_FALSE(schedule.Settled(tiles[1]));
}

TEST(TileSchedule, GroupsByFramesAscending)
{
  std::vector<savr::Tile> tiles = TilesOfWork({ 10, 10, 10, 10 });
  savr::TileSchedule schedule(tiles);
  const int frames[] = { 4, 0, 2, 4 };
  for (std::size_t t = 0; t < tiles.size(); ++t)
  {
    tiles[t].Frames = frames[t];
  }
  const auto groups = schedule.Groups([](const savr::Tile& tile) { return tile.Frames; });
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].first, 2);
  EXPECT_EQ(groups[0].second, (std::vector<std::size_t>{ 2 }));
  EXPECT_EQ(groups[1].first, 4);
  EXPECT_EQ(groups[1].second, (std::vector<std::size_t>{ 0, 3 }));
  for (savr::Tile& tile : tiles)
  {
    tile.Frames = 3;
  }
  const auto all = schedule.Groups([](const savr::Tile& tile) { return tile.Frames; });
  ASSERT_EQ(all.size(), 1u);
  EXPECT_TRUE(all[0].second.empty());
}

TEST(TileSchedule, AnUnboundedPassRunsEachTileOnce)
{
  std::vector<savr::Tile> tiles = TilesOfWork(std::vector<int>(37, 5));
  savr::TileSchedule schedule(tiles);
  schedule.SetThreads(2);
  std::vector<std::atomic<int>> runs(tiles.size());
  const std::vector<std::size_t> some = { 3, 5, 30 };
  EXPECT_EQ(
    schedule.ForEach([&](savr::Tile& tile) { ++runs[&tile - tiles.data()]; }), tiles.size());
  EXPECT_EQ(
    schedule.ForEach([&](savr::Tile& tile) { ++runs[&tile - tiles.data()]; }, 1, 0.0, &some),
    some.size());
  for (std::size_t t = 0; t < tiles.size(); ++t)
  {
    EXPECT_EQ(runs[t].load(), t == 5 || t == 30 ? 2 : 1) << t;
  }
}

// One thread, a clock that only the tiles' work moves: a call stops at the bound, or before a
// tile estimated to pass it by more than a quarter, and the next call goes on where it stopped.
TEST(TileSchedule, ABoundedPassStopsInOrderAndGoesOn)
{
  const std::vector<int> work = { 10, 10, 10, 1000, 10, 10, 10, 10 };
  std::vector<savr::Tile> tiles = TilesOfWork(work);
  savr::TileSchedule schedule(tiles);
  schedule.SetThreads(1);
  schedule.ResetCosts(tiles.size());
  WorkClock clock;
  schedule.SetClock([&clock]() { return clock.Seconds(); });
  std::vector<std::size_t> order;
  const auto body = [&](savr::Tile& tile)
  {
    order.push_back(static_cast<std::size_t>(&tile - tiles.data()));
    clock.Micro += static_cast<std::int64_t>(tile.Work()); // a microsecond per unit of work
  };
  const double bound = 100e-6;
  // Three tiles (30 us); the fourth (1000 us) would pass the bound by far.
  EXPECT_EQ(schedule.ForEach(body, 0, bound), 3u);
  // A call's first tile is always done, however long: then the bound is passed.
  EXPECT_EQ(schedule.ForEach(body, 3, bound), 4u);
  // The rest fits.
  EXPECT_EQ(schedule.ForEach(body, 4, bound), tiles.size());
  EXPECT_EQ(order, (std::vector<std::size_t>{ 0, 1, 2, 3, 4, 5, 6, 7 }));

  // The next frame knows the big tile's cost from its last run: the call before it stops there.
  order.clear();
  EXPECT_EQ(schedule.ForEach(body, 0, 50e-6), 3u);
  // A bound of 25 us takes tiles until it is reached: 10, 20, then 30 >= 25.
  EXPECT_EQ(schedule.ForEach(body, 4, 25e-6), 7u);
  EXPECT_EQ(order, (std::vector<std::size_t>{ 0, 1, 2, 4, 5, 6 }));
}

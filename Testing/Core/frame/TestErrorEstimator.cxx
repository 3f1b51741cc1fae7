// The error estimate alone: tiles of known pixels, images set by hand, and the snapshots it
// keeps and asks to be blended anew.

#include "frame/ErrorEstimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace
{
// A view of 4 x 1 pixels in two tiles of 2 x 1, every pixel covered.
struct TwoTiles
{
  std::vector<savr::Tile> Tiles = std::vector<savr::Tile>(2);
  savr::TileSchedule Schedule{ this->Tiles };
  savr::ErrorEstimator Estimator{ this->Tiles, this->Schedule };
  std::vector<float> Image = std::vector<float>(16, 0.0f);
  // The frames blendEarlier was asked for, per tile (0: not asked).
  std::vector<int> Asked = std::vector<int>(2, 0);
  float Earlier = 0.0f; // what blendEarlier writes into every channel of the tiles it blends

  TwoTiles()
  {
    for (int t = 0; t < 2; ++t)
    {
      savr::Tile& tile = this->Tiles[t];
      tile.X0 = 2 * t;
      tile.X1 = 2 * t + 2;
      tile.Y0 = 0;
      tile.Y1 = 1;
      for (int x = tile.X0; x < tile.X1; ++x)
      {
        savr::RayInfo ray{};
        ray.Pixel = x;
        tile.Rays.push_back(ray);
      }
    }
  }

  void SetFrames(int frames)
  {
    for (savr::Tile& tile : this->Tiles)
    {
      tile.Frames = frames;
    }
  }

  void Update(const savr::BlendIdentity& blend, bool reblended = false)
  {
    this->Estimator.Update(this->Image, 4, 4, blend, nullptr, reblended,
      [&](int frames, float* target, const std::vector<std::size_t>& tiles)
      {
        for (const std::size_t t : tiles)
        {
          this->Asked[t] = frames;
          for (int x = this->Tiles[t].X0; x < this->Tiles[t].X1; ++x)
          {
            std::fill(target + 4 * x, target + 4 * x + 4, this->Earlier);
          }
        }
      });
  }
};
} // namespace

TEST(ErrorEstimator, ComparesEachTileWithItsImageAtAnEarlierPowerOfTwo)
{
  EXPECT_EQ(savr::ErrorEstimator::EarlierFrames(2), 1);
  EXPECT_EQ(savr::ErrorEstimator::EarlierFrames(3), 2);
  EXPECT_EQ(savr::ErrorEstimator::EarlierFrames(4), 2);
  EXPECT_EQ(savr::ErrorEstimator::EarlierFrames(5), 4);

  TwoTiles view;
  const savr::BlendIdentity blend{ 7, savr::BlendMode::Composite, 0 };
  // One frame: no estimate yet, and the image is the snapshot of frame 1.
  view.SetFrames(1);
  std::fill(view.Image.begin(), view.Image.end(), 0.25f);
  view.Update(blend);
  EXPECT_LT(view.Estimator.Value(), 0.0);
  EXPECT_EQ(view.Tiles[0].SnapshotFrames, 1);

  // Two frames: the change from frame 1, as a root mean square over the covered pixels.
  view.SetFrames(2);
  std::fill(view.Image.begin(), view.Image.end(), 0.5f);
  view.Image[0] = 1.25f; // one channel changed by 1, the other 15 by 0.25
  view.Update(blend);
  EXPECT_NEAR(view.Estimator.Value(), std::sqrt((1.0 + 15 * 0.0625) / 16.0), 1e-12);
  EXPECT_EQ(view.Asked, (std::vector<int>{ 0, 0 })); // the snapshot held
  EXPECT_EQ(view.Tiles[1].SnapshotFrames, 2);

  // Three frames compare with frame 2's image, kept as the snapshot.
  view.SetFrames(3);
  std::fill(view.Image.begin(), view.Image.end(), 0.5f);
  view.Update(blend);
  EXPECT_NEAR(view.Estimator.Value(), std::sqrt(0.5625 / 16.0), 1e-12);
  EXPECT_NEAR(view.Tiles[1].ErrorSum, 0.0, 0.0);
}

TEST(ErrorEstimator, AnotherBlendMakesTheSnapshotsStale)
{
  TwoTiles view;
  view.SetFrames(1);
  view.Update({ 1, savr::BlendMode::Composite, 0 });
  view.SetFrames(3);
  std::fill(view.Image.begin(), view.Image.end(), 0.5f);
  view.Earlier = 0.5f;
  // The transfer function changed: both tiles' images at 2 frames are blended anew, with it.
  view.Update({ 2, savr::BlendMode::Composite, 0 }, true);
  EXPECT_EQ(view.Asked, (std::vector<int>{ 2, 2 }));
  EXPECT_EQ(view.Estimator.Value(), 0.0);
  // Another mode, and other tables, too.
  view.Asked = { 0, 0 };
  view.Update({ 2, savr::BlendMode::Maximum, 0 }, true);
  EXPECT_EQ(view.Asked, (std::vector<int>{ 2, 2 }));
  view.Asked = { 0, 0 };
  view.Update({ 2, savr::BlendMode::Maximum, 5 }, true);
  EXPECT_EQ(view.Asked, (std::vector<int>{ 2, 2 }));
  // The same blend again: the snapshots hold.
  view.Asked = { 0, 0 };
  view.Update({ 2, savr::BlendMode::Maximum, 5 }, true);
  EXPECT_EQ(view.Asked, (std::vector<int>{ 0, 0 }));
}

TEST(ErrorEstimator, NoEstimateWhileATileWaitsOrLags)
{
  TwoTiles view;
  const savr::BlendIdentity blend{ 1, savr::BlendMode::Composite, 0 };
  view.SetFrames(2);
  view.Update(blend);
  EXPECT_GE(view.Estimator.Value(), 0.0);
  view.Tiles[1].Resume = true;
  view.Update(blend);
  EXPECT_LT(view.Estimator.Value(), 0.0);
  view.Tiles[1].Resume = false;
  view.Tiles[1].Frames = 1;
  view.Update(blend);
  EXPECT_LT(view.Estimator.Value(), 0.0);
  // A tile without rays does not hold it back.
  view.Tiles[1].Rays.clear();
  view.Update(blend);
  EXPECT_GE(view.Estimator.Value(), 0.0);
  view.Estimator.Reset();
  EXPECT_LT(view.Estimator.Value(), 0.0);
}

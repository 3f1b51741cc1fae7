// A view's state alone: the rays Reset lays out, the step it keeps to, and a budget the view's
// own buffers exceed.

#include "FrameLoopScenes.h"
#include "frame/FrameState.h"

#include <gtest/gtest.h>

#include <cmath>

TEST(FrameState, LaysOutTheRaysThatMeetTheData)
{
  savr_test::WaveGrid wave(16);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 8;
  savr::FrameState state;
  state.Reset(savr_test::HeadOnView(48), wave.Sampler(), settings);
  ASSERT_FALSE(state.OverBudget());
  EXPECT_EQ(state.Tiles.size(), 9u); // 48 / 16 squared
  EXPECT_EQ(state.FrameLimitCount, 8);
  std::size_t rays = 0;
  std::size_t samples = 0;
  for (const savr::Tile& tile : state.Tiles)
  {
    for (const savr::RayInfo& ray : tile.Rays)
    {
      const int x = ray.Pixel % 48;
      const int y = ray.Pixel / 48;
      EXPECT_TRUE(x >= tile.X0 && x < tile.X1 && y >= tile.Y0 && y < tile.Y1);
      EXPECT_TRUE(x >= state.Rectangle[0] && x < state.Rectangle[2] && y >= state.Rectangle[1] &&
                  y < state.Rectangle[3]);
      EXPECT_EQ(ray.SamplesPerFrame, static_cast<int>(std::ceil(ray.Length / 0.1)));
      EXPECT_EQ(ray.Horizon, ray.SamplesPerFrame);
      const double rotation = state.RotationOf(x, y, 0.1);
      EXPECT_TRUE(rotation >= 0.0 && rotation < 1.0);
      EXPECT_EQ(ray.Rotation, rotation);
      samples += ray.SamplesPerFrame;
    }
    rays += tile.Rays.size();
    EXPECT_EQ(tile.Stores.MemoryInUse(), 0u); // nothing allocated before a frame
  }
  EXPECT_GT(rays, 48u * 48u / 4u);
  EXPECT_LT(rays, 48u * 48u);
  EXPECT_EQ(state.CoveredPixels, rays);
  EXPECT_EQ(state.TotalSamplesPerFrame, samples);
  EXPECT_EQ(state.Pixels.size(), 48u * 48u * 4u);
}

TEST(FrameState, KeepsWithinTheSamplesPerFrame)
{
  savr_test::WaveGrid wave(16);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.01;
  settings.MaximumFrames = 2;
  savr::FrameState whole;
  whole.Reset(savr_test::HeadOnView(32), wave.Sampler(), settings);
  // A fifth of that: the step doubles three times (8 > 5), the frames with it.
  settings.MaximumSamplesPerFrame = whole.TotalSamplesPerFrame / 5;
  savr::FrameState limited;
  limited.Reset(savr_test::HeadOnView(32), wave.Sampler(), settings);
  EXPECT_EQ(limited.Settings.SampleDistance, 0.08);
  EXPECT_EQ(limited.Settings.MaximumFrames, 16);
  EXPECT_LE(limited.TotalSamplesPerFrame, settings.MaximumSamplesPerFrame);
}

TEST(FrameState, AllocatesNothingOverBudget)
{
  savr_test::WaveGrid wave(16);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MemoryBudget = 1000; // less than the image
  savr::FrameState state;
  state.Reset(savr_test::HeadOnView(32), wave.Sampler(), settings);
  EXPECT_TRUE(state.OverBudget());
  EXPECT_TRUE(state.Tiles.empty());
  EXPECT_EQ(state.Pixels.capacity(), 0u);
  EXPECT_EQ(state.MemoryInUse(), 0u);
  // Without offsets rotated, every pixel's rotation is 0.
  settings.MemoryBudget = std::size_t(1) << 30;
  settings.RotateOffsets = false;
  state.Reset(savr_test::HeadOnView(32), wave.Sampler(), settings);
  EXPECT_EQ(state.RotationOf(5, 7, 0.1), 0.0);
}

// The single pass alone: the slab's closed-form composite, one ray per block of pixels, and a
// pass over some tiles only.

#include "FrameLoopScenes.h"
#include "PassScenes.h"
#include "frame/SinglePass.h"

#include <gtest/gtest.h>

#include <algorithm>

TEST(SinglePass, GivesTheSlabsBeerLambertComposite)
{
  for (const bool fast : { true, false })
  {
    savr_test::SlabScene scene(0.1);
    scene.State.Settings.FastPaths = fast; // the lean loop, and the general blend
    savr::SinglePass pass(scene.State);
    pass.Render(scene.TF, savr::BlendMode::Composite, 0.1, 0.25, savr::PassOptions());
    int pixels = 0;
    for (std::size_t p = 0; p < scene.State.Pixels.size(); p += 4)
    {
      EXPECT_NEAR(scene.State.Pixels[p + 3], scene.ExpectedAlpha(), 2e-6) << p / 4;
      EXPECT_NEAR(scene.State.Pixels[p + 2], 0.9 * scene.ExpectedAlpha(), 2e-6);
      ++pixels;
    }
    EXPECT_EQ(pixels, 32 * 32);
    EXPECT_GT(scene.State.Taken, 0u);
  }
}

TEST(SinglePass, OneRayPerBlockOfPixels)
{
  savr_test::WaveGrid wave(16);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.05;
  savr::FrameState state;
  state.Reset(savr_test::HeadOnView(32), wave.Sampler(), settings);
  const auto tf = savr_test::WaveTable(state.Encoder);
  savr::SinglePass pass(state);
  savr::PassOptions options;
  options.PixelStride = 2;
  pass.Render(tf, savr::BlendMode::Composite, 0.05, 0.0, options);
  // Each pixel with a ray shows its block's ray, the block's middle pixel (kept in its tile).
  int shown = 0;
  for (const savr::Tile& tile : state.Tiles)
  {
    for (const savr::RayInfo& ray : tile.Rays)
    {
      const int x = ray.Pixel % 32;
      const int y = ray.Pixel / 32;
      const int bx = std::min(x - x % 2 + 1, tile.X1 - 1);
      const int by = std::min(y - y % 2 + 1, tile.Y1 - 1);
      const float* p = &state.Pixels[4 * ray.Pixel];
      const float* q = &state.Pixels[4 * (bx + 32 * by)];
      EXPECT_TRUE(std::equal(p, p + 4, q)) << x << " " << y;
      shown += p[3] > 0.0f;
    }
  }
  EXPECT_GT(shown, 100);
}

TEST(SinglePass, APassOverSomeTilesLeavesTheOthers)
{
  savr_test::SlabScene scene(0.1);
  std::fill(scene.State.Pixels.begin(), scene.State.Pixels.end(), -1.0f);
  savr::SinglePass pass(scene.State);
  const std::vector<std::size_t> tiles = { 0, 2, 3 };
  // From the list's second tile on: tiles 2 and 3.
  pass.Render(scene.TF, savr::BlendMode::Composite, 0.1, 0.0, savr::PassOptions(), 1, &tiles);
  for (std::size_t t = 0; t < scene.State.Tiles.size(); ++t)
  {
    const savr::Tile& tile = scene.State.Tiles[t];
    const float alpha = scene.State.Pixels[4 * (tile.X0 + 32 * tile.Y0) + 3];
    if (t == 2 || t == 3)
    {
      EXPECT_NEAR(alpha, scene.ExpectedAlpha(), 2e-6) << t;
    }
    else
    {
      EXPECT_EQ(alpha, -1.0f) << t;
    }
  }
}

// Fewer rays: a single pass with one ray per block of pixels (PassOptions::PixelStride), and the
// preview it gives the tiles a first frame split by a time bound has not reached yet.

#include "frame/FrameLoopScenes.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace savr_test;

namespace
{
// Pixel (x, y)'s RGBA in a loop's image of width `width`.
const float* At(const std::vector<float>& image, int width, int x, int y)
{
  return image.data() + 4 * (static_cast<std::size_t>(y) * width + x);
}

bool Same(const float* a, const float* b)
{
  return std::memcmp(a, b, 4 * sizeof(float)) == 0;
}

savr::PassOptions Strided(int stride)
{
  savr::PassOptions options;
  options.PixelStride = stride;
  return options;
}
} // namespace

// Each pixel of a strided pass has the colour the full pass gives its block's middle pixel, where
// that pixel has a ray (tiles start at multiples of the stride, so blocks stay in their tile);
// a sixteenth of the rays take about a sixteenth of the samples; the image does not depend on
// the thread count; a stride that does not divide the tile size reads as 1.
TEST(PixelStride, EachBlockShowsItsMiddleRay)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const int size = 70; // not a multiple of 16: the last tiles' blocks are cut short
  const savr::View view = HeadOnView(size);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  savr::FrameLoop full;
  full.Reset(view, sampler, settings);
  const auto table = WaveTable(full.Encoding(), 1.0);
  full.RenderSinglePass(table, savr::BlendMode::Composite, 0.1, 0.0);
  const std::uint64_t fullSamples = full.SamplesTaken();

  savr::FrameLoop strided;
  strided.Reset(view, sampler, settings);
  strided.RenderSinglePass(table, savr::BlendMode::Composite, 0.1, 0.0, Strided(4));
  const std::vector<float>& coarse = strided.Image();
  const std::vector<float>& fine = full.Image();
  int lit = 0;
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const int mx = std::min(x - x % 4 + 2, std::min(x - x % 16 + 16, size) - 1);
      const int my = std::min(y - y % 4 + 2, std::min(y - y % 16 + 16, size) - 1);
      const float* pixel = At(coarse, size, x, y);
      const float* middle = At(fine, size, mx, my);
      const bool hasRay = At(fine, size, x, y)[3] > 0.0f;
      if (hasRay)
      {
        ASSERT_TRUE(Same(pixel, middle)) << x << ", " << y;
        lit += pixel[3] > 0.0f;
      }
    }
  }
  EXPECT_GT(lit, size * size / 4);
  const double ratio = double(strided.SamplesTaken()) / double(fullSamples);
  EXPECT_GT(ratio, 0.03);
  EXPECT_LT(ratio, 0.1) << "one ray in 16";

  settings.Threads = 1;
  savr::FrameLoop one;
  one.Reset(view, sampler, settings);
  one.RenderSinglePass(table, savr::BlendMode::Composite, 0.1, 0.0, Strided(4));
  EXPECT_EQ(0, std::memcmp(one.Image().data(), coarse.data(), coarse.size() * sizeof(float)));

  savr::FrameLoop odd;
  odd.Reset(view, sampler, settings);
  odd.RenderSinglePass(table, savr::BlendMode::Composite, 0.1, 0.0, Strided(3));
  EXPECT_EQ(0, std::memcmp(odd.Image().data(), fine.data(), fine.size() * sizeof(float)));
}

// A first frame split by a time bound: the tiles it has not reached show the strided preview
// (the tiles it has are untouched), and once the frame ends the image has the same bits as a
// frame never split nor previewed. A later frame is not previewed.
TEST(PixelStride, APreviewFillsTheTilesTheFirstFrameHasNotReached)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const int size = 96;
  const savr::View view = HeadOnView(size);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 4;
  settings.Threads = 2;
  savr::FrameLoop whole;
  whole.Reset(view, sampler, settings);
  const auto table = WaveTable(whole.Encoding(), 1.0);
  whole.AccumulateFrame(table, savr::BlendMode::Composite);
  savr::FrameLoop preview;
  preview.Reset(view, sampler, settings);
  // What PreviewRemainingTiles asks of the pass.
  preview.RenderSinglePass(table, savr::BlendMode::Composite, 0.1, 0.0, savr::PassOptions::Fast(2));
  const std::vector<float> previewImage = preview.Image();

  savr::FrameLoop split;
  split.Reset(view, sampler, settings);
  ASSERT_FALSE(split.AccumulateFrame(table, savr::BlendMode::Composite, 1e-9));
  const std::vector<float> before = split.Image();
  split.PreviewRemainingTiles(table, savr::BlendMode::Composite, 2);
  const std::vector<float>& shown = split.Image();
  // Tiles run in rows from the bottom: the rows of the tiles done keep their pixels; those of
  // the tiles not reached are the preview's.
  int changed = 0;
  int previewed = 0;
  for (std::size_t p = 0; p < shown.size() / 4; ++p)
  {
    const bool kept = Same(&shown[4 * p], &before[4 * p]);
    const bool fromPreview = Same(&shown[4 * p], &previewImage[4 * p]);
    ASSERT_TRUE(kept || fromPreview) << "pixel " << p;
    changed += !kept;
    previewed += fromPreview && previewImage[4 * p + 3] > 0.0f;
  }
  EXPECT_GT(changed, size * size / 3) << "most of the image is shown before its frame";
  EXPECT_GT(previewed, size * size / 3);

  AccumulateAll(split, table, 1e-9); // the first frame, then the rest, each split
  savr::FrameLoop whole4;
  whole4.Reset(view, sampler, settings);
  AccumulateAll(whole4, table, 0.0);
  EXPECT_EQ(0, std::memcmp(split.Image().data(), whole4.Image().data(),
                 whole4.Image().size() * sizeof(float)));

  // After the first frame, a preview changes nothing.
  savr::FrameLoop later;
  later.Reset(view, sampler, settings);
  later.AccumulateFrame(table, savr::BlendMode::Composite);
  ASSERT_FALSE(later.AccumulateFrame(table, savr::BlendMode::Composite, 1e-9));
  const std::vector<float> partial = later.Image();
  later.PreviewRemainingTiles(table, savr::BlendMode::Composite, 2);
  EXPECT_EQ(0, std::memcmp(partial.data(), later.Image().data(), partial.size() * sizeof(float)));
}

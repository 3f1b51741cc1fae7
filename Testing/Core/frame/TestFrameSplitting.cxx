// A frame split over several calls by a time bound (FrameLoop::AccumulateFrame's `seconds`):
// the same bits as whole frames.

#include "frame/FrameLoopScenes.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace savr_test;

// A frame split over calls by a time bound (here so small that each call does one group of
// tiles) ends with the same bits as whole frames, for several blend modes and with a transfer
// function edited between frames; a call that did not finish its frame counts no frame and
// reports the part done.
TEST(FrameLoop, FramesSplitOverCallsGiveTheSameBits)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(70);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.15;
  settings.MaximumFrames = 4;
  settings.Threads = 2;
  for (savr::BlendMode mode : { savr::BlendMode::Composite, savr::BlendMode::Maximum,
         savr::BlendMode::Average, savr::BlendMode::PreIntegrated })
  {
    savr::FrameLoop whole;
    whole.Reset(view, sampler, settings);
    const auto table = WaveTable(whole.Encoding(), 1.0);
    const auto edited = WaveTable(whole.Encoding(), 0.4);
    for (int k = 0; k < 4; ++k)
    {
      whole.AccumulateFrame(k < 2 ? table : edited, mode);
    }

    savr::FrameLoop split;
    split.Reset(view, sampler, settings);
    int calls = 0;
    int partial = 0;
    bool sawProgress = false;
    while (!split.Complete() && calls < 10000)
    {
      const int before = split.Frames();
      // The edit arrives with the third frame, as in `whole`.
      const bool editNow = split.Frames() >= 2;
      const bool done = split.AccumulateFrame(editNow ? edited : table, mode, 1e-9);
      ++calls;
      if (!done)
      {
        ++partial;
        EXPECT_EQ(split.Frames(), before);
        EXPECT_GT(split.FrameProgress(), 0.0);
        EXPECT_LT(split.FrameProgress(), 1.0);
        sawProgress = true;
      }
      else
      {
        EXPECT_EQ(split.Frames(), before + 1);
        EXPECT_EQ(split.FrameProgress(), 0.0);
      }
    }
    EXPECT_TRUE(sawProgress);
    EXPECT_GT(partial, 4) << "each call did one group of tiles";
    ASSERT_EQ(split.Image().size(), whole.Image().size());
    EXPECT_EQ(0,
      std::memcmp(split.Image().data(), whole.Image().data(), whole.Image().size() * sizeof(float)))
      << "mode " << static_cast<int>(mode);
    EXPECT_EQ(split.ErrorEstimate(), whole.ErrorEstimate());
  }
}

// The transfer function edited while a frame is under way: the frame starts over with the new
// one, so the image after it is the one of whole frames with the edit before that frame.
TEST(FrameLoop, AnEditWhileAFrameIsUnderWayStartsItOver)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(64);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.15;
  settings.MaximumFrames = 2;
  settings.Threads = 2;
  savr::FrameLoop whole;
  whole.Reset(view, sampler, settings);
  const auto table = WaveTable(whole.Encoding(), 1.0);
  const auto edited = WaveTable(whole.Encoding(), 0.4);
  whole.AccumulateFrame(table, savr::BlendMode::Composite);
  whole.AccumulateFrame(edited, savr::BlendMode::Composite);

  savr::FrameLoop split;
  split.Reset(view, sampler, settings);
  split.AccumulateFrame(table, savr::BlendMode::Composite);
  // Part of the second frame with the first table, then the rest with the edit.
  ASSERT_FALSE(split.AccumulateFrame(table, savr::BlendMode::Composite, 1e-9));
  ASSERT_FALSE(split.AccumulateFrame(table, savr::BlendMode::Composite, 1e-9));
  while (!split.AccumulateFrame(edited, savr::BlendMode::Composite, 1e-9))
  {
  }
  EXPECT_EQ(split.Frames(), 2);
  EXPECT_EQ(0,
    std::memcmp(split.Image().data(), whole.Image().data(), whole.Image().size() * sizeof(float)));
}

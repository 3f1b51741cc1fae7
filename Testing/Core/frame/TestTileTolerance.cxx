// Refinement where the image still changes (FrameLoop::SetTileTolerance): tiles whose own error
// estimate is below the tolerance take no more frames, the others go on to the frame limit,
// and a re-blend that makes a settled tile change again resumes it until it catches up.

#include "frame/FrameLoop.h"
#include "frame/FrameLoopScenes.h"

#include <gtest/gtest.h>

using namespace savr_test;

namespace
{
// The wave, moved out of the transfer function's reach (below -0.5, transparent under
// WaveTable) where x > -0.3: the right of the view is empty until the function changes.
struct HalfHiddenWave
{
  HalfHiddenWave()
    : Wave(24)
  {
    const int n = 24;
    for (int i = 0; i < n; ++i)
    {
      if (-1.0 + 2.0 * i / (n - 1) <= -0.3)
      {
        continue;
      }
      for (int k = 0; k < n * n; ++k)
      {
        this->Wave.Values[i + n * k] -= 3.0f;
      }
    }
  }
  WaveGrid Wave;
};

// Shows values down to -4 as well (the hidden half).
savr::TransferFunctionTable ShowAll(const savr::SampleEncoding& e)
{
  return MakeTable(
    e, [](double v) { return Eigen::Vector3d(0.5 + 0.1 * v, 0.4, 0.6 - 0.1 * v); },
    [](double v) { return std::min(1.0, std::max(0.0, 0.15 * (v + 4.5))); }, 0.5);
}
} // namespace

TEST(TileTolerance, SettledTilesStopAndResumeWhenTheImageChangesThere)
{
  HalfHiddenWave scene;
  auto sampler = scene.Wave.Sampler();
  const savr::View view = HeadOnView(64);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 8;
  // Whole rays (no fronts or horizons): the empty right costs samples until its tiles settle.
  settings.OpacityHorizons = false;

  savr::FrameLoop every;
  every.Reset(view, sampler, settings);
  const auto tf = WaveTable(every.Encoding());
  AccumulateAll(every, tf, 0.0);
  ASSERT_EQ(every.Frames(), 8);

  savr::FrameLoop adaptive;
  adaptive.SetTileTolerance(1e-6);
  adaptive.Reset(view, sampler, settings);
  AccumulateAll(adaptive, tf, 0.0);
  EXPECT_EQ(adaptive.Frames(), 8);
  EXPECT_GT(adaptive.SettledTiles(), 0u) << "the empty right stops early";
  EXPECT_LT(adaptive.SamplesTaken(), every.SamplesTaken() * 0.7);
  // Settled tiles are empty at any frame count; the others took every frame: the same image
  // and the same estimate.
  EXPECT_GT(MaxValue(every.Image()), 0.2) << "the scene must not be blank";
  EXPECT_TRUE(SameBits(adaptive.Image(), every.Image()));
  EXPECT_NEAR(adaptive.ErrorEstimate(), every.ErrorEstimate(), 1e-12);

  // Split over calls by a time bound, on one thread: the same bits.
  savr::FrameSettings oneThread = settings;
  oneThread.Threads = 1;
  savr::FrameLoop bounded;
  bounded.SetTileTolerance(1e-6);
  bounded.Reset(view, sampler, oneThread);
  EXPECT_GT(AccumulateAll(bounded, tf, 1e-9), 8);
  EXPECT_TRUE(SameBits(bounded.Image(), every.Image()));
  EXPECT_EQ(bounded.SamplesTaken(), adaptive.SamplesTaken());

  // A function that shows the hidden half: its tiles change between frames again, resume, and
  // catch up with the others.
  const auto shown = ShowAll(every.Encoding());
  every.Reblend(shown, savr::BlendMode::Composite);
  adaptive.Reblend(shown, savr::BlendMode::Composite);
  EXPECT_FALSE(adaptive.Complete());
  EXPECT_GT(adaptive.ErrorEstimate(), every.ErrorEstimate()) << "honest: the right is behind";
  const std::uint64_t before = adaptive.SamplesTaken();
  AccumulateAll(adaptive, shown, 0.0);
  EXPECT_GT(adaptive.SamplesTaken(), before);
  EXPECT_EQ(adaptive.SettledTiles(), 0u);
  EXPECT_TRUE(SameBits(adaptive.Image(), every.Image()));
  EXPECT_NEAR(adaptive.ErrorEstimate(), every.ErrorEstimate(), 1e-12);

  // A tolerance no tile meets changes nothing: every tile takes every frame.
  savr::FrameLoop strict;
  strict.SetTileTolerance(1e-30);
  strict.Reset(view, sampler, settings);
  AccumulateAll(strict, shown, 0.0);
  const std::uint64_t earlier = every.SamplesTaken();
  every.Reset(view, sampler, settings);
  AccumulateAll(every, shown, 0.0);
  EXPECT_EQ(strict.SamplesTaken(), every.SamplesTaken() - earlier);
  EXPECT_TRUE(SameBits(strict.Image(), every.Image()));
}

// A pass blends only its own tiles. When the function changes before refinement completes and
// the next frames go to a few tiles (here the ones a re-blend made change again), every other
// tile shows the new function too: the image is that of a loop refined with it throughout.
TEST(TileTolerance, AnEditBeforeCompletionShowsInEveryTile)
{
  HalfHiddenWave scene;
  auto sampler = scene.Wave.Sampler();
  const savr::View view = HeadOnView(64);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 8;
  settings.OpacityHorizons = false;

  savr::FrameLoop adaptive;
  adaptive.SetTileTolerance(1e-6);
  adaptive.Reset(view, sampler, settings);
  const auto tf = WaveTable(adaptive.Encoding());
  AccumulateAll(adaptive, tf, 0.0);
  savr::FrameLoop reference;
  reference.SetTileTolerance(1e-6);
  reference.Reset(view, sampler, settings);
  AccumulateAll(reference, tf, 0.0);
  ASSERT_GT(MaxValue(reference.Image()), 0.2) << "the scene must not be blank";

  // Shown, then taken back before the settled tiles caught up: the frames that follow go to
  // those tiles alone, with the first function.
  const auto shown = ShowAll(adaptive.Encoding());
  adaptive.Reblend(shown, savr::BlendMode::Composite);
  ASSERT_FALSE(adaptive.Complete());
  ASSERT_TRUE(adaptive.AccumulateFrame(tf, savr::BlendMode::Composite));
  EXPECT_LT(MaxAbsDifference(adaptive.Image(), reference.Image()), 1e-6)
    << "a tile the frame did not reach still shows the other function";
  AccumulateAll(adaptive, tf, 0.0);
  EXPECT_TRUE(SameBits(adaptive.Image(), reference.Image()));

  // The same after a single pass (a moment of interaction that did not move the camera).
  adaptive.Reblend(shown, savr::BlendMode::Composite);
  adaptive.RenderSinglePass(tf, savr::BlendMode::Composite, 0.3, 0.0);
  AccumulateAll(adaptive, tf, 0.0);
  EXPECT_TRUE(SameBits(adaptive.Image(), reference.Image()));
}

// Opacity horizons (FrameSettings::OpacityHorizons): composite frames after a ray's first sample
// it only up to where the first frame made it opaque; a re-blend with a function that no longer
// does shows at once and the next frames sample those rays whole.

#include "frame/FrameLoop.h"
#include "frame/FrameLoopScenes.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace savr_test;

TEST(OpacityHorizons, RaysEndWhereTheyAreOpaqueAndResumeWhenTheyNoLongerAre)
{
  WaveGrid wave(24);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(48);
  const CutAndWhole configs;
  const savr::FrameSettings& settings = configs.Cut;
  const savr::FrameSettings& whole = configs.Whole;

  // Dense: most rays are opaque a short way in.
  savr::FrameLoop cut;
  cut.Reset(view, sampler, settings);
  const auto dense = WaveTable(cut.Encoding(), 40.0);
  AccumulateAll(cut, dense, 0.0);
  savr::FrameLoop full;
  full.Reset(view, sampler, whole);
  AccumulateAll(full, dense, 0.0);
  EXPECT_GT(MaxValue(full.Image()), 0.2) << "the scene must not be blank";
  EXPECT_LT(MaxAbsDifference(cut.Image(), full.Image()), 1e-6);
  EXPECT_LT(static_cast<double>(cut.SamplesTaken()), 0.6 * full.SamplesTaken());
  // Memory follows: rays store the rows they sampled.
  EXPECT_LT(static_cast<double>(cut.MemoryInUse()), 0.6 * full.MemoryInUse());
  EXPECT_LT(static_cast<double>(cut.StoredSamples()), 0.6 * full.StoredSamples());

  // Lighter: rays are no longer opaque at their horizons. The re-blend samples nothing and shows
  // at once; the next frames sample the cut rays whole, and the image is a whole-ray image.
  const auto light = WaveTable(cut.Encoding(), 0.3);
  const std::uint64_t before = cut.SamplesTaken();
  cut.Reblend(light, savr::BlendMode::Composite);
  EXPECT_EQ(cut.SamplesTaken(), before);
  EXPECT_FALSE(cut.Complete());
  EXPECT_LT(cut.ErrorEstimate(), 0.0) << "unknown until the cut rays are whole";
  full.Reblend(light, savr::BlendMode::Composite);
  EXPECT_TRUE(full.Complete());
  EXPECT_GT(MaxAbsDifference(cut.Image(), full.Image()), 1e-2) << "what lay behind is missing";
  AccumulateAll(cut, light, 1e-9);
  EXPECT_GT(cut.SamplesTaken(), before);
  EXPECT_LT(MaxAbsDifference(cut.Image(), full.Image()), 1e-6);
  EXPECT_NEAR(cut.ErrorEstimate(), full.ErrorEstimate(), 1e-7);
  EXPECT_GT(cut.MemoryInUse(), full.MemoryInUse() / 2) << "the resumed rays store whole rows";

  // The same with the new function from the start: it cuts no ray it does not make opaque.
  savr::FrameLoop fresh;
  fresh.Reset(view, sampler, settings);
  AccumulateAll(fresh, light, 0.0);
  EXPECT_LT(MaxAbsDifference(fresh.Image(), full.Image()), 1e-6);

  // Other blend modes see whole rays.
  savr::FrameLoop maximum;
  maximum.Reset(view, sampler, settings);
  savr::FrameLoop maximumWhole;
  maximumWhole.Reset(view, sampler, whole);
  for (int k = 0; k < 8; ++k)
  {
    maximum.AccumulateFrame(dense, savr::BlendMode::Maximum);
    maximumWhole.AccumulateFrame(dense, savr::BlendMode::Maximum);
  }
  EXPECT_EQ(maximum.SamplesTaken(), maximumWhole.SamplesTaken());
  EXPECT_EQ(0, std::memcmp(maximum.Image().data(), maximumWhole.Image().data(),
                 maximum.Image().size() * sizeof(float)));
}

// Rays stop where what lies behind could change a channel by less than half an 8-bit level
// (FrameSettings::Termination), as the interacting pass stops them: on a function that makes
// rays opaque gradually, frames sample and keep less than rays blended to 1e-6 of the light, and
// the image differs from theirs by less than the light left.
TEST(OpacityHorizons, RaysStopWhereWhatLiesBehindCannotShow)
{
  WaveGrid wave(24);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(48);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.05;
  settings.MaximumFrames = 4;
  savr::FrameSettings deep = settings;
  deep.Termination = 1e-6;

  savr::FrameLoop stopped;
  stopped.Reset(view, sampler, settings);
  // Optical depth 12 per unit everywhere: 24 across the data, where rays stop at 6.2.
  const auto gradual = MakeTable(
    stopped.Encoding(),
    [](double v) { return Eigen::Vector3d(0.5 + 0.4 * std::tanh(v), 0.3, 0.6); },
    [](double) { return 1.0 - std::exp(-6.0); }, 0.5);
  AccumulateAll(stopped, gradual, 0.0);
  savr::FrameLoop further;
  further.Reset(view, sampler, deep);
  AccumulateAll(further, gradual, 0.0);
  EXPECT_GT(MaxValue(further.Image()), 0.2) << "the scene must not be blank";
  const double difference = MaxAbsDifference(stopped.Image(), further.Image());
  std::cout << "samples " << stopped.SamplesTaken() << " against " << further.SamplesTaken()
            << ", stored " << stopped.StoredSamples() << " against " << further.StoredSamples()
            << "; images differ by " << difference << "\n";
  EXPECT_LT(difference, settings.Termination);
  EXPECT_LT(static_cast<double>(stopped.SamplesTaken()), 0.8 * further.SamplesTaken());
  EXPECT_LT(static_cast<double>(stopped.StoredSamples()), 0.8 * further.StoredSamples());

  // A single pass stops its rays at the same light: four frames equal the pass at a quarter step.
  savr::FrameLoop pass;
  pass.Reset(view, sampler, settings);
  pass.RenderSinglePass(gradual, savr::BlendMode::Composite, 0.25 * settings.SampleDistance, 0.0);
  EXPECT_LT(MaxAbsDifference(pass.Image(), stopped.Image()), 1e-6);
}

// A re-blend that makes the rays of some tiles transparent at their horizon marks those tiles;
// when the function is taken back before they were sampled whole, the frames that resume them
// blend those tiles alone, and every other tile shows the function taken back too.
TEST(OpacityHorizons, AnEditTakenBackShowsInEveryTile)
{
  // The wave's right half moved below -1, where both functions give it a faint colour of its
  // own: its rays are never cut.
  WaveGrid wave(24);
  for (std::size_t p = 0; p < wave.Values.size(); ++p)
  {
    const int i = static_cast<int>(p % 24);
    wave.Values[p] -= -1.0 + 2.0 * i / 23.0 > 0.2 ? 3.0f : 0.0f;
  }
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(48);
  savr::FrameLoop loop;
  loop.Reset(view, sampler, CutAndWhole().Cut);
  const auto table = [&](double left, double red)
  {
    return MakeTable(
      loop.Encoding(),
      [red](double v)
      {
        return v < -1.0 ? Eigen::Vector3d(red, 0.2, 1.0 - red)
                        : Eigen::Vector3d(0.5 + 0.4 * std::tanh(v), 0.3, 0.6);
      },
      [left](double v)
      { return v < -1.0 ? 0.05 : left * std::min(1.0, std::max(0.0, 0.6 * (v + 0.5))); },
      0.5);
  };
  const auto dense = table(40.0, 1.0);
  const auto light = table(0.3, 0.0);
  AccumulateAll(loop, dense, 0.0);
  const std::vector<float> denseImage = loop.Image();
  ASSERT_GT(MaxValue(denseImage), 0.2) << "the scene must not be blank";
  loop.Reblend(light, savr::BlendMode::Composite);
  ASSERT_FALSE(loop.Complete()) << "the left's rays wait to be sampled whole";
  ASSERT_GT(MaxAbsDifference(loop.Image(), denseImage), 0.1) << "the right changed colour";
  AccumulateAll(loop, dense, 0.0);
  EXPECT_LT(MaxAbsDifference(loop.Image(), denseImage), 1e-6);
}

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
  savr::FrameSettings settings;
  settings.SampleDistance = 0.05;
  settings.MaximumFrames = 8;
  savr::FrameSettings whole = settings;
  whole.OpacityHorizons = false;

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

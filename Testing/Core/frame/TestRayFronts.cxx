// Ray fronts (with FrameSettings::OpacityHorizons): a composite frame's rays start a row before
// the first sample whose block the first frame's transfer function does not make transparent;
// an edit that keeps those blocks transparent re-blends as before, and one that shows them
// re-blends at once and the next frames sample the rays whole.

#include "frame/FrameLoop.h"
#include "frame/FrameLoopScenes.h"

#include <gtest/gtest.h>

using namespace savr_test;

namespace
{
// The wave with the slices nearest the camera (z from 0.3 on) moved out of WaveTable's reach
// (below -0.5, transparent): every ray first crosses a layer of blocks it makes transparent.
// With `far`, the slices farthest from it (z up to -0.3) instead: every ray ends in such a layer.
struct FrontHiddenWave
{
  explicit FrontHiddenWave(bool far = false)
    : Wave(24)
  {
    const int n = 24;
    for (int k = 0; k < n; ++k)
    {
      const double z = -1.0 + 2.0 * k / (n - 1);
      if (far ? z > -0.3 : z < 0.3)
      {
        continue;
      }
      for (int i = 0; i < n * n; ++i)
      {
        this->Wave.Values[i + n * n * k] -= 4.0f;
      }
    }
  }
  WaveGrid Wave;
};

// Shows values down to -5 as well (the hidden layer).
savr::TransferFunctionTable ShowAll(const savr::SampleEncoding& e)
{
  return MakeTable(
    e, [](double v) { return Eigen::Vector3d(0.5 + 0.1 * v, 0.4, 0.6 - 0.1 * v); },
    [](double v) { return std::min(1.0, std::max(0.0, 0.05 * (v + 5.5))); }, 0.5);
}
} // namespace

TEST(RayFronts, RaysStartWhereTheFunctionCanSeeAndResumeWhenItShowsMore)
{
  FrontHiddenWave scene;
  auto sampler = scene.Wave.Sampler();
  const savr::View view = HeadOnView(48);
  const CutAndWhole configs;
  const savr::FrameSettings& settings = configs.Cut;
  const savr::FrameSettings& whole = configs.Whole;

  // Light enough that no ray is cut at a horizon: fronts alone, and the same bits as whole rays.
  savr::FrameLoop fronted;
  fronted.Reset(view, sampler, settings);
  const auto light = WaveTable(fronted.Encoding(), 0.3);
  AccumulateAll(fronted, light, 0.0);
  savr::FrameLoop full;
  full.Reset(view, sampler, whole);
  AccumulateAll(full, light, 0.0);
  EXPECT_GT(MaxValue(full.Image()), 0.1) << "the scene must not be blank";
  EXPECT_TRUE(SameBits(fronted.Image(), full.Image()));
  EXPECT_LT(static_cast<double>(fronted.SamplesTaken()), 0.85 * full.SamplesTaken())
    << "the hidden layer is not sampled";
  EXPECT_LT(static_cast<double>(fronted.MemoryInUse()), 0.85 * full.MemoryInUse()) << "nor stored";
  EXPECT_NEAR(fronted.ErrorEstimate(), full.ErrorEstimate(), 1e-12);

  // An edit that leaves the layer transparent re-blends as before: nothing to sample.
  const auto lighter = WaveTable(fronted.Encoding(), 0.2);
  const std::uint64_t before = fronted.SamplesTaken();
  fronted.Reblend(lighter, savr::BlendMode::Composite);
  full.Reblend(lighter, savr::BlendMode::Composite);
  EXPECT_TRUE(fronted.Complete());
  EXPECT_EQ(fronted.SamplesTaken(), before);
  EXPECT_TRUE(SameBits(fronted.Image(), full.Image()));

  // One that shows the layer: the re-blend samples nothing and shows at once without it; the
  // next frames sample the rays whole, and the image is the whole-ray image.
  const auto shown = ShowAll(fronted.Encoding());
  fronted.Reblend(shown, savr::BlendMode::Composite);
  full.Reblend(shown, savr::BlendMode::Composite);
  EXPECT_EQ(fronted.SamplesTaken(), before);
  EXPECT_FALSE(fronted.Complete());
  EXPECT_LT(fronted.ErrorEstimate(), 0.0) << "unknown until the rays are whole";
  EXPECT_GT(MaxAbsDifference(fronted.Image(), full.Image()), 1e-2) << "the layer is missing";
  AccumulateAll(fronted, shown, 1e-9);
  EXPECT_GT(fronted.SamplesTaken(), before);
  EXPECT_TRUE(SameBits(fronted.Image(), full.Image()));
  EXPECT_NEAR(fronted.ErrorEstimate(), full.ErrorEstimate(), 1e-12);

  // Other blend modes start rays at the entry.
  savr::FrameLoop maximum;
  maximum.Reset(view, sampler, settings);
  savr::FrameLoop maximumWhole;
  maximumWhole.Reset(view, sampler, whole);
  for (int k = 0; k < 8; ++k)
  {
    maximum.AccumulateFrame(light, savr::BlendMode::Maximum);
    maximumWhole.AccumulateFrame(light, savr::BlendMode::Maximum);
  }
  EXPECT_EQ(maximum.SamplesTaken(), maximumWhole.SamplesTaken());
  EXPECT_TRUE(SameBits(maximum.Image(), maximumWhole.Image()));
}

// Ray backs: the rows past the last block the first frame's function does not make transparent
// are not sampled either; an edit that shows those blocks samples the rays whole.
TEST(RayFronts, RaysEndPastTheLastBlockTheFunctionCanSee)
{
  FrontHiddenWave scene(true);
  auto sampler = scene.Wave.Sampler();
  const savr::View view = HeadOnView(48);
  const CutAndWhole configs;
  const savr::FrameSettings& settings = configs.Cut;
  const savr::FrameSettings& whole = configs.Whole;

  savr::FrameLoop backed;
  backed.Reset(view, sampler, settings);
  const auto light = WaveTable(backed.Encoding(), 0.3);
  AccumulateAll(backed, light, 0.0);
  savr::FrameLoop full;
  full.Reset(view, sampler, whole);
  AccumulateAll(full, light, 0.0);
  EXPECT_GT(MaxValue(full.Image()), 0.1) << "the scene must not be blank";
  EXPECT_TRUE(SameBits(backed.Image(), full.Image()));
  EXPECT_LT(static_cast<double>(backed.SamplesTaken()), 0.85 * full.SamplesTaken())
    << "the hidden layer is not sampled";
  EXPECT_LT(static_cast<double>(backed.MemoryInUse()), 0.85 * full.MemoryInUse()) << "nor stored";
  EXPECT_NEAR(backed.ErrorEstimate(), full.ErrorEstimate(), 1e-12);

  // Showing the layer: the re-blend shows at once without it, the next frames sample the rays
  // whole, and the image is the whole-ray image.
  const std::uint64_t before = backed.SamplesTaken();
  const auto shown = ShowAll(backed.Encoding());
  backed.Reblend(shown, savr::BlendMode::Composite);
  full.Reblend(shown, savr::BlendMode::Composite);
  EXPECT_FALSE(backed.Complete());
  EXPECT_GT(MaxAbsDifference(backed.Image(), full.Image()), 1e-2) << "the layer is missing";
  AccumulateAll(backed, shown, 0.0);
  EXPECT_GT(backed.SamplesTaken(), before);
  EXPECT_TRUE(SameBits(backed.Image(), full.Image()));

  // A single pass at the step the frames refine to gives the image.
  savr::FrameLoop pass;
  pass.Reset(view, sampler, settings);
  pass.RenderSinglePass(light, savr::BlendMode::Composite, settings.SampleDistance / 8, 0.0);
  savr::FrameLoop again;
  again.Reset(view, sampler, settings);
  AccumulateAll(again, light, 0.0);
  EXPECT_LT(MaxAbsDifference(again.Image(), pass.Image()), 1e-6);
}

// A ray its first piece of samples makes opaque is cut at its horizon without a walk to its
// back. An edit that leaves such rays clear must sample them on: to their back where the far
// layer stays hidden, whole where it shows.
TEST(RayFronts, RaysOpaqueBeforeTheirBackResumeWhenTheyAreClear)
{
  FrontHiddenWave scene(true);
  auto sampler = scene.Wave.Sampler();
  const savr::View view = HeadOnView(48);
  const CutAndWhole configs;
  const savr::FrameSettings& settings = configs.Cut;
  const savr::FrameSettings& whole = configs.Whole;

  for (const bool showFar : { false, true })
  {
    savr::FrameLoop cut;
    cut.Reset(view, sampler, settings);
    const auto dense = WaveTable(cut.Encoding(), 40.0);
    AccumulateAll(cut, dense, 0.0);
    savr::FrameLoop full;
    full.Reset(view, sampler, whole);
    AccumulateAll(full, dense, 0.0);
    EXPECT_GT(MaxValue(full.Image()), 0.2) << "the scene must not be blank";
    EXPECT_LT(MaxAbsDifference(cut.Image(), full.Image()), 1e-6);
    EXPECT_LT(static_cast<double>(cut.SamplesTaken()), 0.6 * full.SamplesTaken())
      << "the rays end at their horizons";

    const std::uint64_t before = cut.SamplesTaken();
    const auto edit = showFar ? ShowAll(cut.Encoding()) : WaveTable(cut.Encoding(), 0.3);
    cut.Reblend(edit, savr::BlendMode::Composite);
    full.Reblend(edit, savr::BlendMode::Composite);
    EXPECT_FALSE(cut.Complete()) << "far layer shown: " << showFar;
    EXPECT_GT(MaxAbsDifference(cut.Image(), full.Image()), 1e-2)
      << "what lay behind is missing (far layer shown: " << showFar << ")";
    AccumulateAll(cut, edit, 1e-9);
    EXPECT_GT(cut.SamplesTaken(), before);
    EXPECT_LT(MaxAbsDifference(cut.Image(), full.Image()), 1e-6) << "far layer shown: " << showFar;
  }
}

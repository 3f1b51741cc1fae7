// Numerics of DESIGN §2 checked against closed forms.
#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace savr_test;

TEST(Numerics, IntervalOpacityKeepsSmallAlphasAccurate)
{
  // alpha = 1e-5 per unit distance, interval 1/256 of it: the naive float formula loses half
  // the digits here; the extinction form must not.
  savr::SampleEncoding e;
  e.Bytes = 1;
  e.Levels = 1;
  e.Scale = 1.0;
  const double rgb[3] = { 1, 1, 1 };
  for (double alpha : { 1e-5, 1e-3, 0.5, 0.999 })
  {
    savr::TransferFunctionTable table;
    table.Build(e, rgb, &alpha, 1.0);
    const double h = 1.0 / 256.0;
    const long double exact =
      1.0L - std::pow(1.0L - static_cast<long double>(alpha), static_cast<long double>(h));
    EXPECT_NEAR(table.IntervalAlpha(0, h) / static_cast<double>(exact), 1.0, 1e-12) << alpha;
  }
}

TEST(Numerics, OpacityOneStaysFinite)
{
  savr::SampleEncoding e;
  e.Bytes = 1;
  e.Levels = 1;
  const double rgb[3] = { 1, 1, 1 };
  const double one = 1.0;
  savr::TransferFunctionTable table;
  table.Build(e, rgb, &one, 1.0);
  EXPECT_TRUE(std::isfinite(table.Extinction(0)));
  EXPECT_GT(table.IntervalAlpha(0, 0.1), 0.9999);
}

// A homogeneous slab seen along its thickness: the pixel's opacity must be 1 - exp(-sigma L)
// and its colour c (1 - exp(-sigma L)), whatever the number of samples.
TEST(Numerics, HomogeneousSlabMatchesBeerLambert)
{
  const double length = 2.0;
  const double opacity = 0.3; // per unit distance
  const double unit = 0.7;
  const double sigma = -std::log1p(-opacity) / unit;
  const Eigen::Vector3d color(0.9, 0.5, 0.2);
  auto sampler = std::make_shared<ConstantSlab>(length, 0.5f);
  const auto encoding = savr::SampleEncoding::ForSampler(*sampler);
  const auto table = MakeTable(
    encoding, [&](double) { return color; }, [&](double) { return opacity; }, unit);
  const double expectedAlpha = -std::expm1(-sigma * length);

  for (double samples : { 1.0, 3.0, 10.0, 1000.0, 1e5 / 4 })
  {
    for (int frames : { 1, 3, 4 }) // up to 1e5 samples per ray in all
    {
      savr::FrameLoop loop;
      savr::FrameSettings settings;
      settings.SampleDistance = length / samples; // samples per frame along the slab
      settings.MaximumFrames = frames;
      loop.Reset(ParallelViewAlongX(2, 0.5, -1.0, length + 1.0), sampler, settings);
      for (int k = 0; k < frames; ++k)
      {
        loop.AccumulateFrame(table, savr::BlendMode::Composite);
      }
      ASSERT_TRUE(loop.Complete());
      const std::vector<float>& image = loop.Image();
      for (int p = 0; p < 4; ++p)
      {
        EXPECT_NEAR(image[4 * p + 3] / expectedAlpha, 1.0, 1e-6)
          << samples << " samples, " << frames << " frames";
        for (int c = 0; c < 3; ++c)
        {
          EXPECT_NEAR(image[4 * p + c] / (color[c] * expectedAlpha), 1.0, 1e-6);
        }
      }
    }
  }
}

TEST(Numerics, LongRaysDoNotDrift)
{
  // 1e6 samples of a nearly transparent medium: float accumulation would drift by ~6e-4.
  const double length = 1.0;
  const double opacity = 1e-6;
  auto sampler = std::make_shared<ConstantSlab>(length, 0.5f);
  const auto encoding = savr::SampleEncoding::ForSampler(*sampler);
  const auto table = MakeTable(
    encoding, [](double) { return Eigen::Vector3d(1, 1, 1); }, [&](double) { return opacity; },
    1e-4);
  savr::FrameLoop loop;
  savr::FrameSettings settings;
  settings.SampleDistance = length / 1e6;
  settings.MaximumFrames = 1;
  loop.Reset(ParallelViewAlongX(1, 0.5, -1.0, 2.0), sampler, settings);
  loop.AccumulateFrame(table, savr::BlendMode::Composite);
  const double expected = -std::expm1(std::log1p(-opacity) / 1e-4 * length);
  EXPECT_NEAR(loop.Image()[3] / expected, 1.0, 1e-6);
}

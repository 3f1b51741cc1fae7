#include "TestHelpers.h"
#include "blend/ShadingTable.h"
#include "encoding/EncodeAVX2.h"
#include "frame/FrameLoopScenes.h" // the scenes shared with TestFrameSplitting.cxx
#include "sampler/CroppingSampler.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace savr_test;

// DESIGN §2: after 2^m frames, SAVR equals one pass at dt / 2^m (float round-off aside).
// Also for 8-bit data, whose one-byte codes are filed into their slots their own way.
TEST(FrameLoop, PowerOfTwoFramesEqualOneFinePass)
{
  WaveGrid wave(24);
  std::vector<std::uint8_t> bytes;
  const std::shared_ptr<const savr::Sampler> samplers[2] = { wave.Sampler(),
    ByteWave(wave, bytes) };
  ASSERT_TRUE(samplers[1]);
  const savr::View view = HeadOnView(48);
  const double dt = 0.2;
  for (const double phaseLength : { 0.0, 0.7 * dt, 2.5 * dt })
    for (int m = 0; m <= 5; ++m)
      for (const auto& sampler : samplers)
      {
        const int frames = 1 << m;
        savr::FrameSettings settings;
        settings.SampleDistance = dt;
        settings.MaximumFrames = frames;
        settings.PhaseLength = phaseLength;
        savr::FrameLoop accumulated;
        accumulated.Reset(view, sampler, settings);
        // The same functions of the wave's value for both.
        const auto table = WaveTable(accumulated.Encoding(), 1.0, sampler == samplers[1]);
        for (int k = 0; k < frames; ++k)
        {
          accumulated.AccumulateFrame(table, savr::BlendMode::Composite);
        }
        ASSERT_TRUE(accumulated.Complete());

        savr::FrameLoop single;
        single.Reset(view, sampler, settings);
        single.RenderSinglePass(table, savr::BlendMode::Composite, dt / frames, 0.0);

        EXPECT_GT(MaxValue(single.Image()), 0.2) << "the scene must not be blank";
        // Round-off in sample positions, plus early ray termination at 1e-6 transmittance.
        EXPECT_LT(MaxAbsDifference(accumulated.Image(), single.Image()), 1e-5)
          << "m=" << m << " phase length " << phaseLength;
        if (phaseLength > 0.0)
        {
          // With a phase length of its own, one frame of a loop whose base step is dt / frames
          // takes the same samples too (what the mapper does for SetSampleDistance(dt / frames)).
          savr::FrameSettings fine = settings;
          fine.SampleDistance = dt / frames;
          fine.MaximumFrames = 1;
          savr::FrameLoop oneFrame;
          oneFrame.Reset(view, sampler, fine);
          oneFrame.AccumulateFrame(table, savr::BlendMode::Composite);
          EXPECT_LT(MaxAbsDifference(accumulated.Image(), oneFrame.Image()), 1e-5)
            << "m=" << m << " phase length " << phaseLength;
        }
        if (m > 0)
        {
          // and the refined image differs from one coarse pass, or the test would prove nothing
          savr::FrameLoop coarse;
          coarse.Reset(view, sampler, settings);
          coarse.RenderSinglePass(table, savr::BlendMode::Composite, dt, 0.0);
          EXPECT_GT(MaxAbsDifference(accumulated.Image(), coarse.Image()), 1e-3);
        }
      }
}

TEST(FrameLoop, ReblendWithANewTransferFunctionEqualsAFreshRender)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(40);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.15;
  settings.MaximumFrames = 6;
  for (savr::BlendMode mode :
    { savr::BlendMode::Composite, savr::BlendMode::Maximum, savr::BlendMode::Minimum,
      savr::BlendMode::Average, savr::BlendMode::Additive, savr::BlendMode::PreIntegrated })
  {
    savr::FrameLoop edited;
    edited.Reset(view, sampler, settings);
    const auto before = WaveTable(edited.Encoding(), 1.0);
    const auto after = WaveTable(edited.Encoding(), 0.35);
    for (int k = 0; k < 6; ++k)
    {
      edited.AccumulateFrame(before, mode);
    }
    const std::vector<float> beforeImage = edited.Image();
    edited.Reblend(after, mode);
    // Rays the lighter function no longer makes opaque at their horizon are sampled whole by
    // the next frames (nothing new is sampled otherwise).
    for (int k = 0; k < 6 && !edited.Complete(); ++k)
    {
      edited.AccumulateFrame(after, mode);
    }
    EXPECT_TRUE(edited.Complete());

    savr::FrameLoop fresh;
    fresh.Reset(view, sampler, settings);
    for (int k = 0; k < 6; ++k)
    {
      fresh.AccumulateFrame(after, mode);
    }
    EXPECT_EQ(edited.Image(), fresh.Image()) << "mode " << static_cast<int>(mode);
    EXPECT_GT(MaxAbsDifference(beforeImage, fresh.Image()), 1e-3)
      << "mode " << static_cast<int>(mode);
  }
}

TEST(FrameLoop, ImagesDoNotDependOnTheThreadCount)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(70); // tiles do not divide the image evenly
  std::vector<std::vector<float>> images;
  for (int threads : { 1, 2, 8 })
  {
    savr::FrameSettings settings;
    settings.SampleDistance = 0.1;
    settings.MaximumFrames = 5;
    settings.Threads = threads;
    savr::FrameLoop loop;
    loop.Reset(view, sampler, settings);
    const auto table = WaveTable(loop.Encoding());
    for (int k = 0; k < 5; ++k)
    {
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
    }
    images.push_back(loop.Image());
  }
  EXPECT_GT(MaxValue(images[0]), 0.2);
  for (std::size_t i = 1; i < images.size(); ++i)
  {
    ASSERT_EQ(images[i].size(), images[0].size());
    EXPECT_EQ(0, std::memcmp(images[i].data(), images[0].data(), images[0].size() * sizeof(float)));
  }
}

TEST(FrameLoop, MemoryBudgetCapsFramesAndEightBitDataTakesOneBytePerSample)
{
  std::vector<std::uint8_t> bytes(16 * 16 * 16);
  for (std::size_t i = 0; i < bytes.size(); ++i)
  {
    bytes[i] = static_cast<std::uint8_t>((i * 37) % 251);
  }
  savr::GridDescription grid;
  grid.Data = bytes.data();
  grid.Type = savr::ScalarType::UInt8;
  grid.Dims = { 16, 16, 16 };
  grid.WorldToIndex = Eigen::Affine3d::Identity();
  grid.WorldToIndex.scale(7.5);
  grid.WorldToIndex.translate(Eigen::Vector3d(1, 1, 1));
  std::string error;
  auto sampler = savr::MakeGridSampler(grid, error);
  ASSERT_TRUE(sampler) << error;

  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 64;
  savr::FrameLoop probe;
  probe.Reset(HeadOnView(32), sampler, settings);
  ASSERT_EQ(probe.Encoding().Bytes, 1);
  const std::size_t perFrame = probe.SamplesPerFrame();
  ASSERT_GT(perFrame, 0u);

  // The images, ray tables and scratch come first; the samples have the rest.
  const std::size_t fixed = probe.FixedBytes();
  ASSERT_GT(fixed, 0u);
  settings.MemoryBudget = fixed + perFrame * 3 + perFrame / 2; // room for 3 frames, not 4
  savr::FrameLoop loop;
  loop.Reset(HeadOnView(32), sampler, settings);
  EXPECT_EQ(loop.FrameLimit(), 3);
  const auto table = MakeTable(
    loop.Encoding(), [](double) { return Eigen::Vector3d(1, 1, 1); },
    [](double v) { return v / 255; });
  int frames = 0;
  while (!loop.Complete() && frames < 100)
  {
    loop.AccumulateFrame(table, savr::BlendMode::Composite);
    ++frames;
    EXPECT_LE(loop.FixedBytes() + loop.MemoryInUse(), settings.MemoryBudget);
    // One byte per stored sample, for every slot allocated.
    EXPECT_LE(loop.MemoryInUse(), perFrame * 4);
  }
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(loop.MemoryInUse(), perFrame * 3);

  // Not even one frame: plain ray casting, never a failure.
  settings.MemoryBudget = fixed + perFrame / 2;
  savr::FrameLoop tiny;
  tiny.Reset(HeadOnView(32), sampler, settings);
  EXPECT_EQ(tiny.FrameLimit(), 0);
  tiny.AccumulateFrame(table, savr::BlendMode::Composite);
  EXPECT_TRUE(tiny.Complete());
  EXPECT_EQ(tiny.MemoryInUse(), 0u);
  EXPECT_GT(MaxValue(tiny.Image()), 0.05);

  // Growing copies the store (4, then 16 slots: 20 side by side), so room for 20 frames gives
  // 16, not 17 (16 + 17 would be side by side).
  settings.MemoryBudget = fixed + perFrame * 20;
  savr::FrameLoop growing;
  growing.Reset(HeadOnView(32), sampler, settings);
  EXPECT_EQ(growing.FrameLimit(), 16);

  // The images alone over the budget: nothing is allocated for the view.
  settings.MemoryBudget = fixed - 1;
  savr::FrameLoop over;
  over.Reset(HeadOnView(32), sampler, settings);
  EXPECT_TRUE(over.OverBudget());
  EXPECT_GE(over.FixedBytes(), 32u * 32u * 32u) << "two float RGBA images at least";
  EXPECT_TRUE(over.Image().empty());
  EXPECT_EQ(over.FrameLimit(), 0);
  over.AccumulateFrame(table, savr::BlendMode::Composite);
  EXPECT_EQ(over.MemoryInUse(), 0u);
  EXPECT_EQ(over.Frames(), 0);
}

// A step that would take more samples per frame than allowed is coarsened by a power of two and
// the frames multiplied by it: the frames still refine to one pass at the step asked.
TEST(FrameLoop, ASampleBoundCoarsensFramesThatStillRefineToTheStepAsked)
{
  WaveGrid wave(24);
  const auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(48);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.05;
  settings.MaximumFrames = 1;
  savr::FrameLoop probe;
  probe.Reset(view, sampler, settings);
  const std::size_t unbounded = probe.SamplesPerFrame();
  ASSERT_GT(unbounded, 1000u);

  settings.MaximumSamplesPerFrame = unbounded / 3; // half the samples are too many, a quarter not
  savr::FrameLoop bounded;
  bounded.Reset(view, sampler, settings);
  EXPECT_EQ(bounded.SampleDistance(), 4 * settings.SampleDistance);
  EXPECT_EQ(bounded.FrameLimit(), 4);
  EXPECT_LE(bounded.SamplesPerFrame(), settings.MaximumSamplesPerFrame + bounded.PixelsCovered());
  const auto table = WaveTable(bounded.Encoding());
  for (int k = 0; k < 4; ++k)
  {
    const std::uint64_t before = bounded.SamplesTaken();
    bounded.AccumulateFrame(table, savr::BlendMode::Composite);
    EXPECT_LE(
      bounded.SamplesTaken() - before, settings.MaximumSamplesPerFrame + bounded.PixelsCovered());
  }
  ASSERT_TRUE(bounded.Complete());

  // One pass at the step asked, its pixels' offsets rotated as the bounded frames' are.
  savr::FrameLoop fine;
  fine.Reset(view, sampler, settings);
  fine.RenderSinglePass(table, savr::BlendMode::Composite, settings.SampleDistance, 0.0);
  EXPECT_GT(MaxValue(fine.Image()), 0.2) << "the scene must not be blank";
  EXPECT_LT(MaxAbsDifference(bounded.Image(), fine.Image()), 1e-5);
}

TEST(FrameLoop, MaximumIntensityFindsTheBrightestVoxel)
{
  // One bright voxel in a dark grid, nearest interpolation: every ray through it must show the
  // transfer function of the maximum, and rays that miss it show the background value's.
  const int n = 9;
  std::vector<float> values(n * n * n, 0.1f);
  values[4 + n * (4 + n * 4)] = 0.9f;
  savr::GridDescription grid;
  grid.Data = values.data();
  grid.Dims = { n, n, n };
  grid.Interpolation = savr::Interpolation::Nearest;
  grid.WorldToIndex = Eigen::Affine3d::Identity();
  grid.WorldToIndex.scale(0.5 * (n - 1));
  grid.WorldToIndex.translate(Eigen::Vector3d(1, 1, 1));
  std::string error;
  auto sampler = savr::MakeGridSampler(grid, error);
  ASSERT_TRUE(sampler);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.05;
  settings.MaximumFrames = 2;
  savr::FrameLoop loop;
  loop.Reset(ParallelViewAlongX(9, 1.0, -2.0, 2.0), sampler, settings);
  const auto table = MakeTable(
    loop.Encoding(), [](double v) { return Eigen::Vector3d(v, v, v); }, [](double v) { return v; });
  loop.AccumulateFrame(table, savr::BlendMode::Maximum);
  loop.AccumulateFrame(table, savr::BlendMode::Maximum);
  const std::vector<float>& image = loop.Image();
  const float centre = image[4 * (4 + 9 * 4) + 3];
  const float corner = image[3];
  EXPECT_NEAR(centre, 0.9f, 1e-4);
  EXPECT_NEAR(corner, 0.1f, 1e-4);
}

TEST(FrameLoop, SkippingTransparentBlocksChangesNothing)
{
  WaveGrid wave(40);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(48);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.03;
  savr::FrameLoop loop;
  loop.Reset(view, sampler, settings);
  // Opaque only above 0.6: most blocks of the field are transparent.
  const auto table = MakeTable(
    loop.Encoding(), [](double v) { return Eigen::Vector3d(v, 0.5, 1 - v); },
    [](double v) { return v > 0.6 ? 0.8 * (v - 0.6) : 0.0; }, 0.2);
  loop.RenderSinglePass(table, savr::BlendMode::Composite, settings.SampleDistance, 0.0);
  const std::vector<float> plain = loop.Image();
  savr::PassOptions skipping;
  skipping.SkipTransparent = true;
  loop.RenderSinglePass(table, savr::BlendMode::Composite, settings.SampleDistance, 0.0, skipping);
  EXPECT_GT(MaxValue(plain), 0.2);
  // Transparent samples add exactly nothing: passing over them (and starting each ray at its
  // first sample outside a skipped block) changes no bit.
  EXPECT_EQ(MaxAbsDifference(plain, loop.Image()), 0.0);
}

TEST(FrameLoop, PhasesFollowTheFramesTaken)
{
  WaveGrid wave(16);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.2;
  settings.MaximumFrames = 2;
  savr::FrameLoop loop;
  loop.Reset(HeadOnView(16), wave.Sampler(), settings);
  const auto table = WaveTable(loop.Encoding());
  EXPECT_EQ(loop.CurrentPhase(), savr::Phase::Accumulating);
  loop.RenderSinglePass(table, savr::BlendMode::Composite, 0.2, 0.0);
  EXPECT_EQ(loop.CurrentPhase(), savr::Phase::Interacting);
  EXPECT_EQ(loop.Frames(), 0);
  loop.AccumulateFrame(table, savr::BlendMode::Composite);
  EXPECT_EQ(loop.CurrentPhase(), savr::Phase::Accumulating);
  loop.AccumulateFrame(table, savr::BlendMode::Composite);
  EXPECT_EQ(loop.CurrentPhase(), savr::Phase::Complete);
  loop.AccumulateFrame(table, savr::BlendMode::Composite); // no effect once complete
  EXPECT_EQ(loop.Frames(), 2);
}

// The runtime estimate must track the true error: against an image refined 64 times finer, it
// stays within a small factor of the truth and falls as frames accumulate.
TEST(FrameLoop, ErrorEstimateTracksTheTrueError)
{
  WaveGrid wave(24);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(40);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.4;
  settings.MaximumFrames = 16;
  savr::FrameLoop loop;
  loop.Reset(view, sampler, settings);
  const auto table = WaveTable(loop.Encoding());
  savr::FrameLoop reference;
  reference.Reset(view, sampler, settings);
  reference.RenderSinglePass(
    table, savr::BlendMode::Composite, settings.SampleDistance / 1024, 0.0);
  auto rmse = [&](const std::vector<float>& a)
  {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      sum += (a[i] - reference.Image()[i]) * (a[i] - reference.Image()[i]);
    }
    return std::sqrt(sum / a.size());
  };
  double previous = 1e9;
  for (int k = 1; k <= 16; ++k)
  {
    loop.AccumulateFrame(table, savr::BlendMode::Composite);
    const double estimate = loop.ErrorEstimate();
    const double truth = rmse(loop.Image());
    if (k == 1)
    {
      EXPECT_LT(estimate, 0.0) << "no estimate from one frame";
      continue;
    }
    if ((k & (k - 1)) == 0)
    {
      std::cout << k << " frames: estimate " << estimate << ", true RMSE " << truth << "\n";
      EXPECT_GT(estimate, truth / 2) << k << " frames";
      EXPECT_LT(estimate, truth * 4) << k << " frames";
      EXPECT_LT(estimate, previous) << k << " frames";
      previous = estimate;
    }
  }
  // A transfer function changed during accumulation: the estimate compares images seen through
  // the new one.
  {
    savr::FrameLoop edited;
    edited.Reset(view, sampler, settings);
    const auto lighter = WaveTable(edited.Encoding(), 0.3);
    for (int k = 0; k < 3; ++k)
    {
      edited.AccumulateFrame(table, savr::BlendMode::Composite);
    }
    edited.AccumulateFrame(lighter, savr::BlendMode::Composite); // frame 4, new function
    savr::FrameLoop two;
    two.Reset(view, sampler, settings);
    two.AccumulateFrame(lighter, savr::BlendMode::Composite);
    two.AccumulateFrame(lighter, savr::BlendMode::Composite);
    double sum = 0.0;
    for (std::size_t i = 0; i < two.Image().size(); ++i)
    {
      const double d = edited.Image()[i] - two.Image()[i];
      sum += d * d;
    }
    EXPECT_NEAR(edited.ErrorEstimate(), std::sqrt(sum / (4 * edited.PixelsCovered())), 1e-7);
  }

  // A new transfer function re-estimates from the stored samples.
  const auto lighter = WaveTable(loop.Encoding(), 0.3);
  loop.Reblend(lighter, savr::BlendMode::Composite);
  // Unknown while rays cut at horizons the lighter function no longer makes opaque wait to be
  // sampled whole, as the next frame does.
  while (!loop.Complete())
  {
    loop.AccumulateFrame(lighter, savr::BlendMode::Composite);
  }
  EXPECT_GT(loop.ErrorEstimate(), 0.0);
  EXPECT_LT(loop.ErrorEstimate(), previous);
}

namespace
{
// The same data without HullCorners: every pixel's ray is clipped.
class WithoutHull final : public ForwardingSampler
{
public:
  using ForwardingSampler::ForwardingSampler;
  bool HullCorners(std::array<Eigen::Vector3d, 8>&) const override { return false; }
};
} // namespace

// Pixels outside the image of the data's hull are passed over without clipping their rays:
// the same rays, samples and images as clipping every pixel's, from outside the data, from
// inside it (where no pixel can be passed over) and along parallel rays, for a rotated grid.
TEST(FrameLoop, PassingOverPixelsOutsideTheHullChangesNothing)
{
  WaveGrid wave(20);
  wave.Grid.WorldToIndex.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  const auto sampler = wave.Sampler();
  std::array<Eigen::Vector3d, 8> corners;
  ASSERT_TRUE(sampler->HullCorners(corners));
  const auto plain = std::make_shared<WithoutHull>(sampler);
  const savr::View views[3] = { HeadOnView(70),
    PerspectiveView(Eigen::Vector3d(0.2, 0.1, 0.3), Eigen::Vector3d(1, 1, 1),
      Eigen::Vector3d(0, 1, 0), 60.0, 50, 40, 0.05, 10.0),
    ParallelViewAlongX(48, 2.5, -4.0, 4.0) };
  for (int v = 0; v < 3; ++v)
  {
    std::vector<float> images[2];
    std::uint64_t samples[2] = { 0, 0 };
    for (int k = 0; k < 2; ++k)
    {
      savr::FrameSettings settings;
      settings.SampleDistance = 0.1;
      settings.MaximumFrames = 2;
      savr::FrameLoop loop;
      loop.Reset(views[v], k == 0 ? sampler : plain, settings);
      const auto table = WaveTable(loop.Encoding());
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
      images[k] = loop.Image();
      samples[k] = loop.SamplesPerFrame();
    }
    EXPECT_GT(MaxValue(images[0]), 0.2) << "view " << v;
    EXPECT_EQ(samples[0], samples[1]) << "view " << v;
    ASSERT_EQ(images[0].size(), images[1].size());
    EXPECT_EQ(0, std::memcmp(images[0].data(), images[1].data(), images[0].size() * sizeof(float)))
      << "view " << v;
  }
}

// Stored frames encode, file and blend with AVX2 (four rays at a time) where the CPU has it:
// the same bits as the scalar paths, frame by frame and after a re-blend, for 16-bit and 8-bit
// codes, lit and unlit, with rays that the blend stops early.
TEST(FrameLoop, VectorAndScalarStoredPathsGiveTheSameBits)
{
  if (!savr::detail::HaveAVX2())
  {
    GTEST_SKIP() << "this CPU has no AVX2: only the scalar paths run";
  }
  WaveGrid wave(22);
  std::vector<std::uint8_t> bytes;
  const std::shared_ptr<const savr::Sampler> samplers[2] = { wave.Sampler(),
    ByteWave(wave, bytes) };
  ASSERT_TRUE(samplers[1]);
  const savr::View view = HeadOnView(37); // rays do not fill groups of four evenly
  // A coloured light, so that each channel's factors differ.
  savr::Light light;
  light.Direction = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  light.Ambient = Eigen::Vector3d(0.2, 0.1, 0.3);
  light.Diffuse = Eigen::Vector3d(1.0, 0.7, 0.4);
  light.Specular = Eigen::Vector3d(0.5, 0.9, 0.3);
  savr::ShadingTable shading;
  shading.Build({ light }, Eigen::Vector3d::UnitZ(), 0.3, 0.6, 0.4, 12.0);
  for (const bool shade : { false, true })
    for (const auto& sampler : samplers)
    {
      savr::FrameLoop loops[2];
      for (int k = 0; k < 2; ++k)
      {
        savr::FrameSettings settings;
        settings.SampleDistance = 0.15;
        settings.MaximumFrames = 6;
        settings.Vectorize = k == 0;
        settings.Shade = shade;
        loops[k].Reset(view, sampler, settings);
        if (shade)
        {
          loops[k].SetShading(&shading);
        }
      }
      // Opaque enough that many rays stop early, a few samples after the transmittance starts
      // to fall (so that compositing past the stop would show), then thinner.
      const bool byteData = sampler == samplers[1];
      const auto opaque = MakeTable(
        loops[0].Encoding(), [](double v) { return Eigen::Vector3d(0.2 + 0.001 * v, 0.5, 0.7); },
        [byteData](double v) { return (byteData ? v / 80.0 - 1.5 : v) > -0.5 ? 0.99 : 0.0; }, 0.5);
      const auto thin = WaveTable(loops[0].Encoding(), 0.3);
      double stopped = 0.0;
      for (int frame = 1; frame <= 6; ++frame)
      {
        for (savr::FrameLoop& loop : loops)
        {
          loop.AccumulateFrame(opaque, savr::BlendMode::Composite);
        }
        ASSERT_EQ(0, std::memcmp(loops[0].Image().data(), loops[1].Image().data(),
                       loops[0].Image().size() * sizeof(float)))
          << "frame " << frame << (shade ? ", lit" : "");
        const std::vector<float>& image = loops[0].Image();
        for (std::size_t i = 3; i < image.size(); i += 4)
        {
          stopped = std::max(stopped, static_cast<double>(image[i]));
        }
      }
      // Solid from the first sample on where the wave is high: rays done in their first row next
      // to rays that go on.
      const auto solid = MakeTable(
        loops[0].Encoding(), [](double v) { return Eigen::Vector3d(0.9, 0.2 + 0.001 * v, 0.4); },
        [byteData](double v) { return (byteData ? v / 80.0 - 1.5 : v) > 0.3 ? 1.0 : 0.0; }, 0.5);
      for (savr::FrameLoop& loop : loops)
      {
        loop.Reblend(solid, savr::BlendMode::Composite);
      }
      EXPECT_EQ(0, std::memcmp(loops[0].Image().data(), loops[1].Image().data(),
                     loops[0].Image().size() * sizeof(float)));
      for (savr::FrameLoop& loop : loops)
      {
        loop.Reblend(thin, savr::BlendMode::Composite);
      }
      EXPECT_GE(stopped, 1.0 - savr::FrameSettings().Termination)
        << "no ray reached the termination transmittance";
      EXPECT_GT(MaxValue(loops[0].Image()), 0.1);
      EXPECT_EQ(0, std::memcmp(loops[0].Image().data(), loops[1].Image().data(),
                     loops[0].Image().size() * sizeof(float)));
    }
}

// Stored blends pass over the rows at a ray's ends that hold only transparent codes: with 8-
// and 16-bit codes, rows of 1, 2 and 4 slots (scanned 32 bytes at a time) and of 6 (scanned
// row by row), the vector and the scalar walks, and re-blends with tables that make more or
// less of the data transparent, the images keep every bit.
TEST(FrameLoop, PassingOverTransparentRowsChangesNothing)
{
  WaveGrid wave(22);
  std::vector<std::uint8_t> bytes;
  const std::shared_ptr<const savr::Sampler> samplers[2] = { wave.Sampler(),
    ByteWave(wave, bytes) };
  ASSERT_TRUE(samplers[1]);
  const savr::View view = HeadOnView(37);
  // Up to 1, 2 and 6 frames: room for 1, 2, and then 4 and 6 frames.
  for (const int maximumFrames : { 1, 2, 6 })
    for (const auto& sampler : samplers)
      for (const bool vectorize : { true, false })
      {
        savr::FrameLoop loops[2];
        for (int k = 0; k < 2; ++k)
        {
          savr::FrameSettings settings;
          settings.SampleDistance = 0.15;
          settings.MaximumFrames = maximumFrames;
          settings.Vectorize = vectorize;
          settings.PassOverTransparentRows = k == 0;
          loops[k].Reset(view, sampler, settings);
        }
        const bool byteData = sampler == samplers[1];
        const auto value = [byteData](double v) { return byteData ? v / 80.0 - 1.5 : v; };
        // Transparent below a value that leaves some rays all transparent, and most with
        // transparent rows at both ends.
        const auto table = [&](double below, double opacity)
        {
          return MakeTable(
            loops[0].Encoding(),
            [](double v) { return Eigen::Vector3d(0.3, 0.6 + 0.001 * v, 0.2); },
            [=](double v) { return value(v) > below ? opacity : 0.0; }, 0.5);
        };
        const auto thin = table(0.2, 0.3);
        for (int frame = 1; frame <= maximumFrames; ++frame)
        {
          for (savr::FrameLoop& loop : loops)
          {
            loop.AccumulateFrame(thin, savr::BlendMode::Composite);
          }
          ASSERT_GT(MaxValue(loops[0].Image()), 0.05) << "frame " << frame;
          ASSERT_EQ(0, std::memcmp(loops[0].Image().data(), loops[1].Image().data(),
                         loops[0].Image().size() * sizeof(float)))
            << "frame " << frame << (vectorize ? ", vector" : ", scalar");
        }
        for (const auto& other :
          { table(-0.8, 0.5), table(0.6, 1.0), WaveTable(loops[0].Encoding()) })
        {
          for (savr::FrameLoop& loop : loops)
          {
            loop.Reblend(other, savr::BlendMode::Composite);
          }
          EXPECT_GT(MaxValue(loops[0].Image()), 0.05);
          EXPECT_EQ(0, std::memcmp(loops[0].Image().data(), loops[1].Image().data(),
                         loops[0].Image().size() * sizeof(float)));
        }
      }
}

// Cropping to a box (the middle region alone shown) drops the steps outside it from each ray
// (Sampler::Restrict), keeping the lattice: the image is the one full rays give with NaN
// outside the box, and far fewer samples are stored. This is how a rank of a parallel run
// samples only its region of an AMR hierarchy.
TEST(FrameLoop, ACroppingBoxStoresOnlyTheStepsInsideIt)
{
  WaveGrid wave(24);
  const double planes[6] = { -0.45, 0.2, -0.8, 0.6, -0.3, 0.35 };
  constexpr std::uint32_t kMiddleOnly = 1u << 13;
  auto cropped = std::make_shared<savr::CroppingSampler>(
    wave.Sampler(), Eigen::Affine3d::Identity(), planes, kMiddleOnly);
  // The same sampler without Restrict: every step of the segment is taken and stored.
  auto fullRays = std::make_shared<ForwardingSampler>(cropped);
  const savr::View view = HeadOnView(48);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.05;
  settings.MaximumFrames = 4;
  savr::FrameLoop narrow;
  savr::FrameLoop full;
  narrow.Reset(view, cropped, settings);
  full.Reset(view, fullRays, settings);
  const auto table = WaveTable(narrow.Encoding());
  for (int k = 0; k < settings.MaximumFrames; ++k)
  {
    narrow.AccumulateFrame(table, savr::BlendMode::Composite);
    full.AccumulateFrame(table, savr::BlendMode::Composite);
  }
  EXPECT_GT(MaxValue(narrow.Image()), 0.1) << "the box must show";
  EXPECT_EQ(MaxAbsDifference(narrow.Image(), full.Image()), 0.0);
  std::printf("stored: %zu bytes in the box's steps, %zu over whole segments\n",
    narrow.MemoryInUse(), full.MemoryInUse());
  EXPECT_LT(narrow.MemoryInUse(), 0.6 * full.MemoryInUse());
}

// Blends over parts of the rays split at window depths composite, front over back, to the image
// (each sample's interval is cut where a part ends), with the frames' uneven gaps of a count that
// is not a power of two, lit and unlit; modes that do not blend intervals are refused.
TEST(FrameLoop, DepthWindowsCompositeToTheImage)
{
  WaveGrid wave(20);
  auto sampler = wave.Sampler();
  const savr::View view = HeadOnView(40);
  // Window depths around the data's centre, a little different from pixel to pixel.
  const Eigen::Vector4d centre = view.NDCToWorld.inverse() * Eigen::Vector4d(0, 0, 0, 1);
  const double middle = 0.5 * (centre[2] / centre[3] + 1.0);
  const std::size_t pixels = static_cast<std::size_t>(view.Width) * view.Height;
  std::vector<float> zero(pixels, 0.0f), one(pixels, 1.0f), near(pixels), far(pixels);
  for (std::size_t i = 0; i < pixels; ++i)
  {
    near[i] = static_cast<float>(middle - 0.002 * (i % 3));
    far[i] = static_cast<float>(middle + 0.003 * (i % 5));
  }
  for (const bool shade : { false, true })
  {
    savr::FrameSettings settings;
    settings.SampleDistance = 0.15;
    settings.MaximumFrames = 5;
    settings.Shade = shade;
    // Each part stops its rays on its own light: they composite to the image up to Termination.
    settings.Termination = 1e-6;
    savr::FrameLoop loop;
    loop.Reset(view, sampler, settings);
    const auto table = WaveTable(loop.Encoding());
    savr::Light light;
    light.Direction = Eigen::Vector3d(0.3, 0.2, 1.0).normalized();
    savr::ShadingTable shading;
    shading.Build({ light }, Eigen::Vector3d(0, 0, 1), 0.2, 0.7, 0.3, 12.0);
    loop.SetShading(shade ? &shading : nullptr);
    EXPECT_FALSE(loop.CanBlendDepthWindows(savr::BlendMode::Composite)) << "nothing stored yet";
    for (int k = 0; k < 5; ++k)
    {
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
    }
    ASSERT_TRUE(loop.CanBlendDepthWindows(savr::BlendMode::Composite));
    EXPECT_FALSE(loop.CanBlendDepthWindows(savr::BlendMode::Isosurface));
    EXPECT_FALSE(loop.CanBlendDepthWindows(savr::BlendMode::PreIntegrated));

    std::vector<float> whole(4 * pixels, 0.0f), front(4 * pixels, 0.0f),
      middlePart(4 * pixels, 0.0f), back(4 * pixels, 0.0f);
    savr::FrameLoop::DepthWindow windows[4];
    windows[0] = { zero.data(), one.data(), whole.data() };
    windows[1] = { zero.data(), near.data(), front.data() };
    windows[2] = { near.data(), far.data(), middlePart.data() };
    windows[3] = { far.data(), one.data(), back.data() };
    loop.BlendDepthWindows(table, savr::BlendMode::Composite, windows, 4);
    EXPECT_LT(MaxAbsDifference(whole, loop.Image()), 1e-5) << "shade " << shade;
    std::vector<float> composited(4 * pixels);
    for (std::size_t i = 0; i < pixels; ++i)
    {
      for (int c = 0; c < 4; ++c)
      {
        const std::size_t k = 4 * i + c;
        const float behind = middlePart[k] + (1.0f - middlePart[4 * i + 3]) * back[k];
        composited[k] = front[k] + (1.0f - front[4 * i + 3]) * behind;
      }
    }
    EXPECT_LT(MaxAbsDifference(composited, loop.Image()), 1e-5) << "shade " << shade;
    EXPECT_GT(MaxValue(front), 0.05) << "the front part is not empty";
    EXPECT_GT(MaxValue(back), 0.05) << "the back part is not empty";
  }
}

// A slice counts every frame at once and stores nothing: a later composite call on the same loop
// has nothing to blend again and leaves the slice as it is.
TEST(FrameLoop, ASliceLeavesNothingToBlendAgain)
{
  WaveGrid wave(16);
  auto sampler = wave.Sampler();
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 4;
  savr::FrameLoop loop;
  loop.Reset(HeadOnView(32), sampler, settings);
  const auto tf = WaveTable(loop.Encoding());
  loop.SetSlicePlane(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(loop.AccumulateFrame(tf, savr::BlendMode::Slice));
  ASSERT_TRUE(loop.Complete());
  const std::vector<float> slice = loop.Image();
  EXPECT_GT(MaxValue(slice), 0.1) << "the slice must not be blank";
  const std::uint64_t taken = loop.SamplesTaken();
  EXPECT_TRUE(loop.AccumulateFrame(tf, savr::BlendMode::Composite));
  EXPECT_EQ(loop.SamplesTaken(), taken);
  EXPECT_TRUE(SameBits(loop.Image(), slice));
}

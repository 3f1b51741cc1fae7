// A frame split over several calls by a time bound (FrameLoop::AccumulateFrame's `seconds`):
// the same bits as whole frames.

#include "frame/FrameLoopScenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <memory>

using namespace savr_test;

// A frame split over calls by a time bound (here so small that each call does one tile) ends
// with the same bits as whole frames, for several blend modes and with a transfer function
// edited between frames; a call that did not finish its frame counts no frame and
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
    EXPECT_GT(partial, 4) << "each call did one tile";
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

namespace
{
// Time as the tests of a bound count it: what the samplers say their work took, summed over the
// threads, whatever the machine's load (FrameLoop::SetClock reads it).
class WorkClock
{
public:
  void Advance(double seconds)
  {
    this->Nanoseconds.fetch_add(static_cast<std::int64_t>(seconds * 1e9));
  }
  double Seconds() const { return 1e-9 * static_cast<double>(this->Nanoseconds.load()); }

private:
  std::atomic<std::int64_t> Nanoseconds{ 0 };
};

// The wave, where each SampleRay call takes `Wait` on the clock for a ray in one half of the view
// (its direction's y above 0 when `Upper`, else below) and a hundredth of that in the other.
class SlowHalf final : public ForwardingSampler
{
public:
  SlowHalf(std::shared_ptr<const savr::Sampler> inner, bool upper, double wait,
    std::shared_ptr<WorkClock> clock)
    : ForwardingSampler(std::move(inner))
    , Upper(upper)
    , Wait(wait)
    , Clock(std::move(clock))
  {
  }
  void SampleRay(const savr::Ray& ray, double t0, double dt, int count, float* out,
    const savr::SkipMask* skip) const override
  {
    this->Clock->Advance((ray.Direction.y() > 0.0) == this->Upper ? this->Wait : 0.01 * this->Wait);
    ForwardingSampler::SampleRay(ray, t0, dt, count, out, skip);
  }

private:
  bool Upper;
  double Wait;
  std::shared_ptr<WorkClock> Clock;
};
} // namespace

// A bound passed by one tile per thread at most, where tiles of the same work cost 100 times
// more in one half of the view than in the other (as a particle cloud's dense middle does):
// estimating the next tiles at the cheap half's cost started tens of slow tiles in one call.
TEST(FrameLoop, ABoundHoldsWhereTilesCostMoreThanTheirWork)
{
  WaveGrid wave(20);
  // Close enough that every ray meets the data: 64 tiles of 16x16 rays.
  const savr::View view = PerspectiveView(Eigen::Vector3d(0.0, 0.0, 2.2), Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(0, 1, 0), 40.0, 128, 128, 0.5, 10.0);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.1;
  settings.MaximumFrames = 2;
  settings.Threads = 2;
  const double wait = 100e-6; // a slow tile: 256 rays, 25.6 ms
  const double tile = 256 * wait;
  const double bound = 0.05;
  for (bool upper : { false, true })
  {
    auto clock = std::make_shared<WorkClock>();
    auto sampler = std::make_shared<SlowHalf>(wave.Sampler(), upper, wait, clock);
    savr::FrameLoop loop;
    loop.SetClock([clock]() { return clock->Seconds(); });
    loop.Reset(view, sampler, settings);
    const auto table = WaveTable(loop.Encoding(), 1.0);
    double longest = 0.0;
    int calls = 0;
    while (!loop.Complete() && calls < 1000)
    {
      const double start = clock->Seconds();
      loop.AccumulateFrame(table, savr::BlendMode::Composite, bound);
      longest = std::max(longest, clock->Seconds() - start);
      ++calls;
    }
    EXPECT_TRUE(loop.Complete());
    // The bound, a slow tile on each thread, and one more.
    EXPECT_LT(longest, bound + 3 * tile)
      << (upper ? "upper" : "lower") << " half slow: " << calls << " calls";
  }
}

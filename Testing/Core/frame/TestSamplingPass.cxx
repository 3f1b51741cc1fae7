// The sampling pass alone: a frame's codes filed where each ray's samples lie, the first
// frame's rows cut at an opacity horizon, and a ray the blend did not make opaque there
// resumed whole.

#include "FrameLoopScenes.h"
#include "encoding/EncodeAVX2.h"
#include "frame/PassScratch.h"
#include "frame/SamplingPass.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace
{
// A view of the wave with its state ready for frame 0: offsets for four frames, stores of four
// slots.
struct WaveFrame
{
  explicit WaveFrame(bool horizons)
  {
    savr::FrameSettings settings;
    settings.SampleDistance = 0.05;
    settings.MaximumFrames = 4;
    settings.OpacityHorizons = horizons;
    this->State.Reset(savr_test::HeadOnView(32), this->Wave.Sampler(), settings);
    this->State.Offsets.Resize(4);
    this->State.Schedule.ChoosePass(this->State.FrameLimitCount);
    this->State.Grow(4, 0);
  }

  // The codes frame `slot` of `ray` should hold in its rows [first, last): the sampler's values
  // at the ray's offset, encoded.
  std::vector<std::uint32_t> Expected(const savr::RayInfo& ray, int slot, int first, int last)
  {
    const double dt = this->State.Settings.SampleDistance;
    const double u = savr::RotatedOffset(this->State.Offsets.Offset(slot), ray.Rotation);
    const savr::Ray r = this->State.CurrentViewData.PixelRay(ray.Pixel % 32, ray.Pixel / 32);
    std::vector<float> values(static_cast<std::size_t>(last - first));
    this->State.Source->SampleRay(
      r, ray.TEnter + (first + u) * dt, dt, last - first, values.data(), nullptr);
    std::vector<std::uint32_t> codes;
    for (float v : values)
    {
      codes.push_back(this->State.Encoder.Encode(v));
    }
    return codes;
  }
  std::vector<std::uint32_t> Stored(
    const savr::Tile& tile, const savr::RayInfo& ray, int slot, int first, int last) const
  {
    std::vector<std::uint32_t> codes;
    for (int j = first; j < last; ++j)
    {
      codes.push_back(
        const_cast<savr::Tile&>(tile).Stores.Codes.Row<std::uint16_t>(ray.FirstRow + j)[slot]);
    }
    return codes;
  }

  savr_test::WaveGrid Wave{ 16 };
  savr::FrameState State;
  savr::ThreadBuffers Buffers;
};
} // namespace

TEST(SamplingPass, FilesEachRaysSamplesInItsSlot)
{
  for (const bool vectorEncode : { false, true })
  {
    if (vectorEncode && !savr::detail::HaveAVX2())
    {
      continue;
    }
    WaveFrame frame(false);
    ASSERT_EQ(frame.State.Encoder.Bytes, 2);
    savr::SamplingPass pass(frame.State);
    const savr::StoredAttributes none;
    std::size_t rays = 0;
    for (savr::Tile& tile : frame.State.Tiles)
    {
      frame.Buffers.Sampled = 0;
      pass.SampleTile<std::uint16_t>(
        tile, frame.Buffers, none, vectorEncode, false, nullptr, nullptr);
      std::size_t samples = 0;
      for (const savr::RayInfo& ray : tile.Rays)
      {
        ASSERT_EQ(frame.Stored(tile, ray, 0, 0, ray.SamplesPerFrame),
          frame.Expected(ray, 0, 0, ray.SamplesPerFrame))
          << ray.Pixel;
        samples += ray.SamplesPerFrame;
        ++rays;
      }
      EXPECT_EQ(frame.Buffers.Sampled, samples);
    }
    EXPECT_GT(rays, 100u);
  }
}

TEST(SamplingPass, CutsAtTheHorizonAndResumesWhole)
{
  WaveFrame frame(true);
  savr::SamplingPass pass(frame.State);
  const savr::StoredAttributes none;
  // Opaque enough that rays through the middle end within a few pieces.
  const auto tf = savr_test::WaveTable(frame.State.Encoder, 40.0);
  ASSERT_TRUE(pass.HorizonsApply(tf, savr::BlendMode::Composite, none));
  EXPECT_FALSE(pass.HorizonsApply(tf, savr::BlendMode::Maximum, none));
  int cut = 0;
  for (savr::Tile& tile : frame.State.Tiles)
  {
    pass.SampleTile<std::uint16_t>(tile, frame.Buffers, none, false, false, &tf, nullptr);
    for (const savr::RayInfo& ray : tile.Rays)
    {
      cut += ray.Horizon < ray.SamplesPerFrame;
      ASSERT_EQ(frame.Stored(tile, ray, 0, 0, ray.Horizon), frame.Expected(ray, 0, 0, ray.Horizon));
    }
  }
  ASSERT_GT(cut, 50);
  // A blend that left every ray clear (alpha 0): rays cut short are sampled whole, and keep the
  // codes they had.
  const std::vector<float> clear(frame.State.Pixels.size(), 0.0f);
  for (savr::Tile& tile : frame.State.Tiles)
  {
    const bool any = std::any_of(tile.Rays.begin(), tile.Rays.end(),
      [](const savr::RayInfo& ray) { return ray.Horizon < ray.SamplesPerFrame; });
    // Asked only whether it would: nothing is sampled.
    EXPECT_EQ(pass.ResumeRays<std::uint16_t>(
                tile, frame.Buffers, none, false, false, 1, clear.data(), true, true, false),
      any);
    EXPECT_EQ(pass.ResumeRays<std::uint16_t>(
                tile, frame.Buffers, none, false, false, 1, clear.data(), true, true, true),
      any);
    for (const savr::RayInfo& ray : tile.Rays)
    {
      EXPECT_EQ(ray.Horizon, ray.SamplesPerFrame);
      ASSERT_EQ(frame.Stored(tile, ray, 0, 0, ray.SamplesPerFrame),
        frame.Expected(ray, 0, 0, ray.SamplesPerFrame));
    }
  }
}

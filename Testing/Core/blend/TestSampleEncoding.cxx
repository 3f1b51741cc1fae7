#include "encoding/SampleEncoding.h"
#include "image/GridSampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace
{
// A sampler over the 2x2x2 grid of `data`.
std::shared_ptr<const savr::Sampler> SamplerOver(const void* data, savr::ScalarType type)
{
  savr::GridDescription grid;
  grid.Data = data;
  grid.Type = type;
  grid.Dims = { 2, 2, 2 };
  std::string error;
  auto sampler = savr::MakeGridSampler(grid, error);
  EXPECT_TRUE(sampler) << error;
  return sampler;
}

savr::SampleEncoding EncodingFor(const void* data, savr::ScalarType type)
{
  return savr::SampleEncoding::ForSampler(*SamplerOver(data, type));
}
} // namespace

TEST(SampleEncoding, StoresAtTheDataPrecision)
{
  const std::uint8_t bytes[8] = { 0, 255, 3, 4, 5, 6, 7, 8 };
  const std::int16_t shorts[8] = { -3000, 3000, 0, 1, 2, 3, 4, 5 };
  const std::int16_t narrowShorts[8] = { -100, 100, 0, 1, 2, 3, 4, 5 };
  const float floats[8] = { -1.f, 2.f, 0.f, 1.f, 0.5f, 0.25f, 0.125f, 1.5f };
  EXPECT_EQ(EncodingFor(bytes, savr::ScalarType::UInt8).Bytes, 1);
  EXPECT_EQ(EncodingFor(shorts, savr::ScalarType::Int16).Bytes, 2);
  EXPECT_EQ(EncodingFor(narrowShorts, savr::ScalarType::Int16).Bytes, 1);
  EXPECT_EQ(EncodingFor(floats, savr::ScalarType::Float32).Bytes, 2);
}

TEST(SampleEncoding, IntegralDataRoundTripsExactly)
{
  const std::uint8_t bytes[8] = { 0, 255, 3, 4, 5, 6, 7, 8 };
  const savr::SampleEncoding e = EncodingFor(bytes, savr::ScalarType::UInt8);
  for (int v = 0; v < 256; ++v)
  {
    EXPECT_EQ(e.Decode(e.Encode(static_cast<float>(v))), v);
  }
}

TEST(SampleEncoding, QuantizationErrorStaysWithinItsBound)
{
  for (double scale : { 1e-30, 1e-3, 1.0, 1e6, 1e30 })
  {
    const float floats[8] = { static_cast<float>(-scale), static_cast<float>(3 * scale), 0, 0, 0, 0,
      0, 0 };
    const savr::SampleEncoding e = EncodingFor(floats, savr::ScalarType::Float32);
    EXPECT_LE(e.MaxError(), 4 * scale / 65534.0 * 0.5 * (1 + 1e-9));
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(-scale, 3 * scale);
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i)
    {
      const float v = static_cast<float>(uniform(random));
      worst = std::max(worst, std::abs(e.Decode(e.Encode(v)) - v));
    }
    // The bound plus the float rounding of the value itself.
    EXPECT_LE(worst, e.MaxError() * (1 + 1e-6) + 4 * scale * 1e-7) << "scale " << scale;
    EXPECT_GT(worst, 0.5 * e.MaxError()) << "the test should exercise the bound";
  }
}

TEST(SampleEncoding, NonFiniteSamplesGetTheirOwnCode)
{
  const float floats[8] = { 0.f, 1.f, std::numeric_limits<float>::quiet_NaN(), 0.5f,
    std::numeric_limits<float>::infinity(), 0.f, 0.f, 0.f };
  const savr::SampleEncoding e = EncodingFor(floats, savr::ScalarType::Float32);
  ASSERT_TRUE(e.HasNaNCode);
  EXPECT_EQ(e.Encode(std::numeric_limits<float>::quiet_NaN()), e.NaNCode);
  EXPECT_EQ(e.Encode(-std::numeric_limits<float>::infinity()), e.NaNCode);
  EXPECT_LT(e.Encode(1.0f), e.NaNCode);
  EXPECT_EQ(e.Decode(e.Encode(1.0f)), 1.0);
}

// An outlier widens the data's range a million times; codes over the transfer functions' window
// keep the precision the window needs, and the outlier takes the window's top code.
TEST(SampleEncoding, AWindowKeepsItsPrecisionBesideAnOutlier)
{
  const float floats[8] = { 0.f, 0.25f, 0.5f, 0.75f, 1.f, 0.125f, 0.375f, 1e6f };
  const auto sampler = SamplerOver(floats, savr::ScalarType::Float32);
  const savr::SampleEncoding whole = savr::SampleEncoding::ForSampler(*sampler);
  const savr::SampleEncoding window = savr::SampleEncoding::ForSampler(*sampler, false, { 0, 1 });
  EXPECT_GT(whole.MaxError(), 5.0);
  EXPECT_LE(window.MaxError(), 0.5 / 65534.0 * (1 + 1e-9));
  EXPECT_EQ(window.CodedRange()[0], 0.0);
  EXPECT_NEAR(window.CodedRange()[1], 1.0, 1e-12);
  EXPECT_EQ(window.Encode(1e6f), window.Levels - 1);
  EXPECT_EQ(window.Encode(-3.f), 0u);
  for (float v : { 0.1f, 0.3337f, 0.9f })
  {
    EXPECT_NEAR(window.Decode(window.Encode(v)), v, window.MaxError() * (1 + 1e-6));
  }
  // Within the data's range only: a window wider than the data is the data's range.
  const savr::SampleEncoding wide = savr::SampleEncoding::ForSampler(*sampler, false, { -5, 2e6 });
  EXPECT_EQ(wide.Offset, whole.Offset);
  EXPECT_EQ(wide.Scale, whole.Scale);
}

TEST(SampleEncoding, IntegralDataKeepsWholeLevelsInAWindow)
{
  const std::uint8_t bytes[8] = { 0, 255, 3, 4, 5, 6, 7, 8 };
  const auto sampler = SamplerOver(bytes, savr::ScalarType::UInt8);
  const savr::SampleEncoding e = savr::SampleEncoding::ForSampler(*sampler, false, { 10.5, 20.2 });
  EXPECT_EQ(e.CodedRange()[0], 10.0);
  EXPECT_GE(e.CodedRange()[1], 21.0);
  for (int v = 10; v <= 21; ++v)
  {
    EXPECT_EQ(e.Decode(e.Encode(static_cast<float>(v))), v);
  }
  // Beyond the window a value is coded at or beyond its end (one byte holds more levels).
  EXPECT_GE(e.Decode(e.Encode(200.f)), 21.0);
  EXPECT_EQ(e.Decode(e.Encode(2.f)), 10.0);
}

// Data wholly outside a window is coded from the window's nearer end outwards: at that end or
// beyond it, where the transfer functions are constant.
TEST(SampleEncoding, DataWhollyOutsideAWindowTakesItsNearerEnd)
{
  const float floats[8] = { 0.f, 1.f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f };
  const auto sampler = SamplerOver(floats, savr::ScalarType::Float32);
  const savr::SampleEncoding above = savr::SampleEncoding::ForSampler(*sampler, false, { 5, 6 });
  EXPECT_EQ(above.CodedRange()[0], 5.0);
  EXPECT_EQ(above.Decode(above.Encode(0.7f)), 5.0);
  const savr::SampleEncoding below = savr::SampleEncoding::ForSampler(*sampler, false, { -6, -5 });
  EXPECT_EQ(below.CodedRange()[0], -5.0);
  EXPECT_GE(below.Decode(below.Encode(0.7f)), -5.0);
}

// Stored codes serve a window they cover about as finely; a wider window, or one narrowed to a
// few of their codes, needs the samples again.
TEST(SampleEncoding, CodesServeTheWindowsTheyResolve)
{
  const float floats[8] = { 0.f, 0.25f, 0.5f, 0.75f, 1.f, 0.125f, 0.375f, 1e6f };
  const auto sampler = SamplerOver(floats, savr::ScalarType::Float32);
  const auto in = [&](double lo, double hi) {
    return savr::SampleEncoding::ForSampler(*sampler, false, { lo, hi });
  };
  const savr::SampleEncoding stored = in(0, 1);
  EXPECT_TRUE(stored.Serves(stored));
  EXPECT_TRUE(stored.Serves(in(0.1, 0.9)));
  EXPECT_FALSE(stored.Serves(in(0, 2)));
  EXPECT_TRUE(stored.Serves(in(-1, 1))) << "below the data there is nothing to cover";
  EXPECT_FALSE(stored.Serves(in(0.4, 0.5)));
  EXPECT_FALSE(savr::SampleEncoding::ForSampler(*sampler).Serves(stored));
}

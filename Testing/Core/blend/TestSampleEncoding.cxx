#include "image/GridSampler.h"
#include "encoding/SampleEncoding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace
{
savr::SampleEncoding EncodingFor(const void* data, savr::ScalarType type)
{
  savr::GridDescription grid;
  grid.Data = data;
  grid.Type = type;
  grid.Dims = { 2, 2, 2 };
  std::string error;
  auto sampler = savr::MakeGridSampler(grid, error);
  EXPECT_TRUE(sampler) << error;
  return savr::SampleEncoding::ForSampler(*sampler);
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

// Accuracy beyond the data's levels: transfer functions with features narrower than one level of
// 8-bit data (fine codes, measured against the reference that does not round), and an error
// estimate that does not depend on how much of the window the data covers.
#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <iostream>

using namespace savr_test;

namespace
{
// An opacity spike a thousandth of the range 0..255 wide, between the levels 100 and 101, over a
// faint background; opacity per 0.02 world units.
constexpr double kSpike = 100.4;
constexpr double kHalfWidth = 0.128;
double SpikeOpacity(double v)
{
  const double d = std::abs(v - kSpike);
  const double background = v > 20.0 ? 0.0005 : 0.0005 * v / 20.0;
  return d < kHalfWidth ? background + (1.0 - background) * (1.0 - d / kHalfWidth) : background;
}
Eigen::Vector3d SpikeColor(double v)
{
  const double w = v / 255.0;
  return Eigen::Vector3d(0.2 + 0.8 * w, 0.3 + 0.5 * w, 0.9 - 0.6 * w);
}
constexpr double kUnit = 0.02;

// The wave of WaveGrid as 8-bit data over 0..250, in `bytes`.
std::shared_ptr<const savr::Sampler> ByteField(
  const WaveGrid& wave, std::vector<std::uint8_t>& bytes)
{
  bytes.resize(wave.Values.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
  {
    bytes[i] = static_cast<std::uint8_t>(
      std::lround(std::min(250.0, std::max(0.0, 70.0 * (wave.Values[i] + 1.6)))));
  }
  savr::GridDescription grid = wave.Grid;
  grid.Data = bytes.data();
  grid.Type = savr::ScalarType::UInt8;
  std::string error;
  return savr::MakeGridSampler(grid, error);
}

double Rmse(const std::vector<float>& a, const std::vector<float>& b)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    sum += (static_cast<double>(a[i]) - b[i]) * (static_cast<double>(a[i]) - b[i]);
  }
  return std::sqrt(sum / std::max<std::size_t>(a.size(), 1));
}
} // namespace

TEST(SubLevelFeatures, FineCodesKeepFractionalBits)
{
  WaveGrid wave(8);
  std::vector<std::uint8_t> bytes;
  const auto sampler = ByteField(wave, bytes);
  const savr::SampleEncoding coarse = savr::SampleEncoding::ForSampler(*sampler);
  const savr::SampleEncoding fine = savr::SampleEncoding::ForSampler(*sampler, true);
  EXPECT_EQ(coarse.Bytes, 1);
  EXPECT_EQ(coarse.FractionBits, 0);
  EXPECT_EQ(fine.Bytes, 2);
  EXPECT_EQ(fine.FractionBits, 8);
  EXPECT_EQ(fine.Scale, 256.0);
  EXPECT_EQ(fine.Encode(100.4f), std::uint32_t(std::lround((100.4 - fine.Offset) * 256)));
  EXPECT_NEAR(fine.Decode(fine.Encode(100.4f)), 100.4, fine.MaxError());
  // 16-bit data: as many fractional bits as fit beside its levels, none over the full range.
  for (const double span : { 1000.0, 65535.0 })
  {
    std::vector<std::uint16_t> shorts(wave.Values.size());
    for (std::size_t i = 0; i < shorts.size(); ++i)
    {
      shorts[i] = static_cast<std::uint16_t>(std::lround(span * (wave.Values[i] + 2.0) / 4.0));
    }
    savr::GridDescription grid = wave.Grid;
    grid.Data = shorts.data();
    grid.Type = savr::ScalarType::UInt16;
    std::string error;
    const auto wide = savr::MakeGridSampler(grid, error);
    ASSERT_TRUE(wide) << error;
    const savr::SampleEncoding e = savr::SampleEncoding::ForSampler(*wide, true);
    EXPECT_EQ(e.Bytes, 2);
    EXPECT_EQ(e.FractionBits, span < 1024.0 ? 6 : 0) << span;
  }
  // Float data has no integer levels to refine.
  const savr::SampleEncoding floats = savr::SampleEncoding::ForSampler(*wave.Sampler(), true);
  EXPECT_EQ(floats.FractionBits, 0);
}

TEST(SubLevelFeatures, FeaturesBetweenLevelsAreFound)
{
  WaveGrid wave(8);
  std::vector<std::uint8_t> bytes;
  const auto sampler = ByteField(wave, bytes);
  const savr::SampleEncoding coarse = savr::SampleEncoding::ForSampler(*sampler);
  const auto color = [](double v, double rgb[3])
  {
    const Eigen::Vector3d c = SpikeColor(v);
    std::copy(c.data(), c.data() + 3, rgb);
  };
  const double spikeNodes[5] = { 0.0, kSpike - kHalfWidth, kSpike, kSpike + kHalfWidth, 255.0 };
  EXPECT_TRUE(coarse.HasFeaturesBetweenCodes(spikeNodes, 5, SpikeOpacity, color));
  // A ramp with nodes between levels: a kink, not a feature.
  const double rampNodes[3] = { 0.0, 60.3, 250.0 };
  const auto ramp = [](double v) { return v < 60.3 ? 0.0 : 0.3 * (v - 60.3) / (250.0 - 60.3); };
  EXPECT_FALSE(coarse.HasFeaturesBetweenCodes(rampNodes, 3, ramp, color));
  // On the fine codes, the spike is many codes wide.
  const savr::SampleEncoding fine = savr::SampleEncoding::ForSampler(*sampler, true);
  EXPECT_FALSE(fine.HasFeaturesBetweenCodes(spikeNodes, 5, SpikeOpacity, color));
}

// A pre-integrated segment between the values 100 and 101 crosses the whole spike: its optical
// depth is the integral of the extinction over the values it spans. Codes at integer levels see
// only the two levels' extinctions; fractional codes tabulate the spike finely enough to hold it.
TEST(SubLevelFeatures, SegmentsAcrossTheSpikeGetItsWholeIntegral)
{
  WaveGrid wave(8);
  std::vector<std::uint8_t> bytes;
  const auto sampler = ByteField(wave, bytes);
  const auto sigma = [](double v) { return -std::log1p(-std::min(SpikeOpacity(v), 1.0 - 1e-12)); };
  // Optical depth over one world unit of a segment whose value runs from 100 to 101.
  double exact = 0.0;
  const int steps = 1 << 20;
  for (int i = 0; i < steps; ++i)
  {
    exact +=
      std::min(sigma(100.0 + (i + 0.5) / steps), savr::TransferFunctionTable::kMaxOpticalDepth);
  }
  exact /= steps * kUnit;
  double depths[2] = { 0.0, 0.0 };
  for (const bool fineCodes : { false, true })
  {
    const savr::SampleEncoding e = savr::SampleEncoding::ForSampler(*sampler, fineCodes);
    const auto table = MakeTable(e, SpikeColor, SpikeOpacity, kUnit);
    double alpha = 0.0;
    Eigen::Array3d color;
    // A short segment, so that its opacity is far from 1 and tells the depth.
    const double length = 1e-4;
    table.Segment(e.Encode(100.0f), e.Encode(101.0f), length, alpha, color);
    depths[fineCodes] = -std::log1p(-alpha) / length;
  }
  std::cout << "optical depth per unit across the spike: exact " << exact << ", integer levels "
            << depths[0] << ", fractional bits " << depths[1] << "\n";
  EXPECT_LT(depths[0], 0.1 * exact);
  EXPECT_NEAR(depths[1], exact, 0.02 * exact);
}

// The spike on 8-bit data against the reference that does not round: with the samples rounded
// to integer levels no sample lands in it and no pre-integrated segment holds it; with
// fractional bits both converge.
TEST(SubLevelFeatures, SpikeBetweenLevelsConverges)
{
  WaveGrid wave(24);
  std::vector<std::uint8_t> bytes;
  const auto sampler = ByteField(wave, bytes);
  const savr::View view = PerspectiveView(Eigen::Vector3d(0.3, -0.4, 4.0), Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(0, 1, 0), 40.0, 48, 48, 1.0, 10.0);
  savr::FrameSettings settings;
  settings.SampleDistance = 2.0 / 23.0; // one voxel
  settings.MaximumFrames = 8;
  savr::ReferenceTransferFunction exact{ SpikeColor, SpikeOpacity, kUnit };
  const std::vector<float> reference =
    savr::ReferenceImage(view, *sampler, exact, settings.SampleDistance / 512.0);
  for (const auto mode : { savr::BlendMode::Composite, savr::BlendMode::PreIntegrated })
  {
    // [fine codes][the table averages the function over each code's interval]
    double errors[2][2] = { { 0.0, 0.0 }, { 0.0, 0.0 } };
    for (const bool fineCodes : { false, true })
      for (const bool averaged : { false, true })
      {
        settings.FineCodes = fineCodes;
        savr::FrameLoop loop;
        loop.Reset(view, sampler, settings);
        const double halfCode = 0.5 / loop.Encoding().Scale;
        // The functions as they are, or averaged over each code's interval.
        const std::function<double(double)> opacity = [halfCode, averaged](double v)
        {
          double sum = 0.0;
          for (int i = 0; averaged && i < 64; ++i)
          {
            sum += SpikeOpacity(v - halfCode + (i + 0.5) * halfCode / 32.0);
          }
          return averaged ? sum / 64.0 : SpikeOpacity(v);
        };
        const std::function<Eigen::Vector3d(double)> color = [halfCode, averaged](double v)
        {
          Eigen::Vector3d sum = Eigen::Vector3d::Zero();
          for (int i = 0; averaged && i < 64; ++i)
          {
            sum += SpikeColor(v - halfCode + (i + 0.5) * halfCode / 32.0);
          }
          return Eigen::Vector3d(averaged ? Eigen::Vector3d(sum / 64.0) : SpikeColor(v));
        };
        const auto table = MakeTable(loop.Encoding(), color, opacity, kUnit);
        for (int k = 0; k < settings.MaximumFrames; ++k)
        {
          loop.AccumulateFrame(table, mode);
        }
        errors[fineCodes][averaged] = Rmse(loop.Image(), reference);
      }
    std::cout << (mode == savr::BlendMode::Composite ? "point sampled" : "pre-integrated")
              << ", 8 frames, RMSE at integer levels: " << errors[0][0] << " (" << errors[0][1]
              << " averaged over each level); with fractional bits: " << errors[1][0] << " ("
              << errors[1][1] << " averaged)\n";
    // Point samples at one voxel over 8 frames still land in the spike by chance only: finer
    // codes help them less than they help pre-integrated segments, which get its whole integral.
    EXPECT_LT(errors[1][0], errors[0][0] / (mode == savr::BlendMode::Composite ? 1.4 : 10.0));
  }
}

// The same volume covering the whole window and a quarter of one twice as wide and high, on the
// same rays: the estimate is the same.
TEST(SubLevelFeatures, ErrorEstimateDoesNotDependOnCoverage)
{
  WaveGrid wave(16);
  const auto sampler = wave.Sampler();
  savr::FrameSettings settings;
  settings.SampleDistance = 0.3;
  settings.MaximumFrames = 4;
  settings.RotateOffsets = false; // a pixel's rotation depends on where it lies in the window
  double estimates[2] = { 0.0, 0.0 };
  double covered[2] = { 0.0, 0.0 };
  for (const int quarter : { 0, 1 })
  {
    const int size = quarter ? 64 : 32;
    const savr::View view = ParallelViewAlongX(size, quarter ? 2.0 : 1.0, -3.0, 3.0);
    savr::FrameLoop loop;
    loop.Reset(view, sampler, settings);
    const auto table = MakeTable(
      loop.Encoding(), [](double) { return Eigen::Vector3d(0.9, 0.6, 0.3); },
      [](double v) { return std::min(1.0, std::max(0.0, 0.5 * (v + 0.5))); }, 0.5);
    for (int k = 0; k < 3; ++k)
    {
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
    }
    estimates[quarter] = loop.ErrorEstimate();
    covered[quarter] = static_cast<double>(loop.PixelsCovered()) / (size * size);
  }
  std::cout << "estimate " << estimates[0] << " at " << covered[0] << " coverage, " << estimates[1]
            << " at " << covered[1] << "\n";
  EXPECT_GT(covered[0], 0.95);
  EXPECT_LT(covered[1], 0.3);
  EXPECT_GT(estimates[0], 0.0);
  EXPECT_NEAR(estimates[1], estimates[0], 1e-6 * estimates[0]);
}

#pragma once
// Scenes of the frame loop's tests: a view of the wave from the front, the wave's transfer
// function, the wave as 8-bit data, and refining a loop to completion.

#include "TestHelpers.h"
#include "frame/FrameLoop.h"
#include "image/GridSampler.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace savr_test
{
// The settings the opacity-horizon and ray-front tests compare: a step of 0.05 and 8 frames,
// with horizons and fronts (`Cut`) and with rays sampled whole (`Whole`).
struct CutAndWhole
{
  CutAndWhole()
  {
    this->Cut.SampleDistance = 0.05;
    this->Cut.MaximumFrames = 8;
    this->Whole = this->Cut;
    this->Whole.OpacityHorizons = false;
  }
  savr::FrameSettings Cut;
  savr::FrameSettings Whole;
};

inline savr::View HeadOnView(int size)
{
  return PerspectiveView(Eigen::Vector3d(0.3, -0.4, 4.0), Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(0, 1, 0), 40.0, size, size, 1.0, 10.0);
}

// Colour and opacity of the wave's value; of ByteWave's bytes (80 (value + 1.5)) when `bytes`.
inline savr::TransferFunctionTable WaveTable(
  const savr::SampleEncoding& e, double scale = 1.0, bool bytes = false)
{
  const auto value = [bytes](double v) { return bytes ? v / 80.0 - 1.5 : v; };
  return MakeTable(
    e,
    [value](double v) {
      return Eigen::Vector3d(0.5 + 0.4 * std::tanh(value(v)), 0.3, 0.8 - 0.3 * std::tanh(value(v)));
    },
    [scale, value](double v)
    { return scale * std::min(1.0, std::max(0.0, 0.6 * (value(v) + 0.5))); },
    0.5);
}
// The wave as 8-bit data, 80 (value + 1.5) rounded, in `bytes`.
inline std::shared_ptr<const savr::Sampler> ByteWave(
  const WaveGrid& wave, std::vector<std::uint8_t>& bytes)
{
  bytes.resize(wave.Values.size());
  for (std::size_t i = 0; i < bytes.size(); ++i)
  {
    bytes[i] = static_cast<std::uint8_t>(std::lround(80.0 * (wave.Values[i] + 1.5)));
  }
  savr::GridDescription grid = wave.Grid;
  grid.Data = bytes.data();
  grid.Type = savr::ScalarType::UInt8;
  std::string error;
  return savr::MakeGridSampler(grid, error);
}
// Composite frames until the loop is complete, each within `seconds` when > 0; the calls it
// took (at most 10,000).
inline int AccumulateAll(
  savr::FrameLoop& loop, const savr::TransferFunctionTable& tf, double seconds)
{
  int calls = 0;
  while (!loop.Complete() && calls < 10000)
  {
    loop.AccumulateFrame(tf, savr::BlendMode::Composite, seconds);
    ++calls;
  }
  return calls;
}
} // namespace savr_test

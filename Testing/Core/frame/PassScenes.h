#pragma once
// Scenes of the frame's parts' own tests: a view state set up by hand, and a slab of one value
// seen along its length, whose composite is known in closed form.

#include "TestHelpers.h"
#include "frame/FrameState.h"

#include <cmath>
#include <memory>

namespace savr_test
{
// A slab of length 2 and value 0.5 seen along x by a 32 x 32 parallel view; a transfer
// function of opacity `alpha` per unit distance, so every pixel's alpha is 1 - (1 - alpha)^2.
struct SlabScene
{
  explicit SlabScene(double step, double alpha = 0.3, int frames = 4)
    : Alpha(alpha)
  {
    this->Settings.SampleDistance = step;
    this->Settings.MaximumFrames = frames;
    this->State.Reset(ParallelViewAlongX(32, 0.9, -1.0, 3.0),
      std::make_shared<ConstantSlab>(2.0, 0.5f), this->Settings);
    this->TF = MakeTable(
      this->State.Encoder, [](double) { return Eigen::Vector3d(0.2, 0.6, 0.9); },
      [alpha](double) { return alpha; }, 1.0);
  }
  double ExpectedAlpha() const { return 1.0 - std::pow(1.0 - this->Alpha, 2.0); }

  double Alpha;
  savr::FrameSettings Settings;
  savr::FrameState State;
  savr::TransferFunctionTable TF;
};
} // namespace savr_test

#pragma once
// The accuracy reference every image is measured against: the composite emission-absorption
// integral of each pixel in double precision, with the transfer function evaluated as a function
// of the value (no tables, no quantization of samples), by the midpoint rule at a fine step.

#include "frame/View.h"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace savr
{

struct ReferenceTransferFunction
{
  std::function<Eigen::Vector3d(double)> Color;
  std::function<double(double)> Opacity; // per UnitDistance, in [0, 1]
  double UnitDistance = 1.0;
};

/// Premultiplied RGBA of every pixel of `view` (4 floats per pixel, rows from the bottom). Each
/// ray is cut into equal steps no longer than `step` and at least `minimumSteps` of them.
std::vector<float> ReferenceImage(const View& view, const Sampler& sampler,
  const ReferenceTransferFunction& tf, double step, int minimumSteps = 1);

} // namespace savr

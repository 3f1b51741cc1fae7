#include "vtkSAVRInputChecks.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkImplicitFunction.h"
#include "vtkMath.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace
{
// Inputs smaller than this (world units) are culled by VTK's camera and culler arithmetic.
constexpr double kSmallestExtent = 1e-20;
// Value spans below this cannot be scaled to 16-bit codes in double precision.
constexpr double kSmallestValueSpan = 1e-290;
}

namespace vtkSAVRInputChecks
{
// Numbers in messages: %g-like, so that tiny and huge values keep their digits.
std::string Number(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

// Why bounds VTK computed for the input leave nothing to draw, or empty when they are usable.
// VTK culls such a volume without calling Render, so this is found from GetBounds.
std::string BoundsProblem(const double bounds[6])
{
  if (!vtkMath::AreBoundsInitialized(bounds))
  {
    return std::string();
  }
  double largest = 0.0;
  double away = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    away = std::max({ away, std::abs(bounds[2 * a]), std::abs(bounds[2 * a + 1]) });
    if (!std::isfinite(bounds[2 * a]) || !std::isfinite(bounds[2 * a + 1]))
    {
      return "the input's bounds are not finite (NaN or Inf in its origin, spacing, direction or "
             "points)";
    }
    largest = std::max(largest, bounds[2 * a + 1] - bounds[2 * a]);
  }
  // Data so far from the origin that doubles hold fewer than 64 steps across it (an image at
  // 1e30).
  if (largest < 64.0 * std::numeric_limits<double>::epsilon() * away)
  {
    return "the input is too far from the origin (" + Number(away) +
           ") for double precision to resolve its extent (" + Number(largest) +
           "); move it nearer the origin";
  }
  if (largest > 0.0 && largest < kSmallestExtent)
  {
    return "the input is too small to render: its bounds span " + Number(largest) +
           " world units (at least " + Number(kSmallestExtent) + " are needed; scale the data)";
  }
  return std::string();
}

// Why `scalars` cannot be told apart once encoded, or empty. Only doubles can go wrong: a range
// whose span overflows (near +-1.7e308) or is too small to scale to 16 bits (denormals); the
// unstructured sampler stores floats, which hold less of either.
std::string ScalarRangeProblem(vtkDataArray* scalars, bool storedAsFloat)
{
  if (!scalars || scalars->GetDataType() != VTK_DOUBLE)
  {
    return std::string();
  }
  for (int c = 0; c < scalars->GetNumberOfComponents(); ++c)
  {
    double range[2];
    scalars->GetFiniteRange(range, c);
    if (!(range[0] <= range[1]))
    {
      continue; // no finite value: every sample is transparent, as NaN voxels are
    }
    const std::string values =
      "the scalars' range [" + Number(range[0]) + ", " + Number(range[1]) + "]" +
      (scalars->GetNumberOfComponents() > 1 ? " (component " + std::to_string(c) + ")" : "");
    const long double span = static_cast<long double>(range[1]) - range[0];
    const double largest = std::max(std::abs(range[0]), std::abs(range[1]));
    if (storedAsFloat && largest > std::numeric_limits<float>::max())
    {
      return values + " exceeds what a float holds (unstructured grids are sampled as floats); " +
             "rescale the data";
    }
    if (!storedAsFloat && scalars->GetNumberOfComponents() == 1)
    {
      continue; // checked by the values its codes cover
    }
    if (!std::isfinite(static_cast<double>(span)))
    {
      return values + " is too wide: its span overflows a double; rescale the data";
    }
    const double smallestSpan =
      storedAsFloat ? 1e4 * std::numeric_limits<float>::min() : kSmallestValueSpan;
    if (span > 0.0L && span < smallestSpan)
    {
      return values + " is too narrow to tell its values apart (a span below " +
             Number(smallestSpan) + "); rescale the data";
    }
  }
  return std::string();
}

std::string CodedRangeProblem(const double values[2], bool windowed)
{
  if (!(values[0] <= values[1]))
  {
    return std::string(); // no finite value: every sample is transparent, as NaN voxels are
  }
  const std::string which = "the range of values to tell apart [" + Number(values[0]) + ", " +
                            Number(values[1]) + "] (the scalars' range" +
                            (windowed ? " within the transfer functions' nodes)" : ")");
  const std::string remedy =
    windowed ? "rescale the data or narrow the transfer functions" : "rescale the data";
  const long double span = static_cast<long double>(values[1]) - values[0];
  if (!std::isfinite(static_cast<double>(span)))
  {
    return which + " is too wide: its span overflows a double; " + remedy;
  }
  // Samples are interpolated as floats (larger values are held at a float's largest).
  const double largest = std::max(std::abs(values[0]), std::abs(values[1]));
  if (largest > static_cast<double>(std::numeric_limits<float>::max()))
  {
    return which + " exceeds what a float sample holds (" +
           Number(static_cast<double>(std::numeric_limits<float>::max())) + "); " + remedy;
  }
  if (span > 0.0L && span < kSmallestValueSpan)
  {
    return which + " is too narrow to tell its values apart (a span below " +
           Number(kSmallestValueSpan) + "); rescale the data";
  }
  return std::string();
}

// Why one of the functions of `property` the mapper reads (for `components` components) has a
// node that is not finite, or empty. Such a node spoils the whole table, not just its range.
std::string TransferFunctionProblem(vtkVolumeProperty* property, int components)
{
  auto finite = [](const double* v, int n)
  { return std::all_of(v, v + n, [](double x) { return std::isfinite(x); }); };
  for (int c = 0; c < components; ++c)
  {
    const std::string which = " of component " + std::to_string(c);
    if (property->GetColorChannels(c) == 3)
    {
      vtkColorTransferFunction* color = property->GetRGBTransferFunction(c);
      for (int i = 0; i < color->GetSize(); ++i)
      {
        double node[6];
        color->GetNodeValue(i, node);
        if (!finite(node, 4))
        {
          return "the colour transfer function" + which +
                 " has a NaN or infinite value or "
                 "colour at node " +
                 std::to_string(i);
        }
      }
    }
    vtkPiecewiseFunction* functions[3] = {
      property->GetColorChannels(c) == 1 ? property->GetGrayTransferFunction(c) : nullptr,
      property->GetScalarOpacity(c),
      property->HasGradientOpacity(c) && !property->GetDisableGradientOpacity(c)
        ? property->GetGradientOpacity(c)
        : nullptr
    };
    const char* names[3] = { "gray", "scalar opacity", "gradient opacity" };
    for (int f = 0; f < 3; ++f)
    {
      for (int i = 0; functions[f] && i < functions[f]->GetSize(); ++i)
      {
        double node[4];
        functions[f]->GetNodeValue(i, node);
        if (!finite(node, 2))
        {
          return std::string("the ") + names[f] + " transfer function" + which +
                 " has a NaN or infinite value at node " + std::to_string(i);
        }
      }
    }
  }
  return std::string();
}

// Why the camera's projection cannot be inverted, as far as it can be told, for data whose
// bounds have the diagonal `dataSize`.
std::string CameraProblem(vtkCamera* camera, double dataSize)
{
  const double* position = camera->GetPosition();
  const double distance = camera->GetDistance();
  const double away =
    std::max({ std::abs(position[0]), std::abs(position[1]), std::abs(position[2]), 1.0 });
  const double* range = camera->GetClippingRange();
  double direction[3];
  camera->GetDirectionOfProjection(direction);
  double up[3];
  camera->GetViewUp(up);
  double side[3];
  vtkMath::Cross(direction, up, side);
  std::string reason;
  // Far from the origin, doubles cannot place the camera within a thousandth of the data.
  if (away * std::numeric_limits<double>::epsilon() > 1e-3 * dataSize)
  {
    reason = "the camera is too far from the origin (" + Number(away) +
             ") for double precision at its distance to the focal point (" + Number(distance) +
             "); move the data and the camera nearer the origin";
  }
  else if (distance <= 1e-20) // VTK keeps a camera at its focal point 1e-20 away
  {
    reason = "the camera's position and focal point coincide";
  }
  else if (vtkMath::Norm(side) < 1e-12 * vtkMath::Norm(up))
  {
    reason = "the camera's view-up is parallel to the view direction";
  }
  else if (!camera->GetParallelProjection() && range[0] < 1e-12 * range[1])
  {
    reason = "the camera's near plane is at " + Number(range[0]) +
             ", too close to the camera for its far plane at " + Number(range[1]);
  }
  else
  {
    reason = "the camera's matrices are degenerate";
  }
  return "the camera's projection cannot be inverted: " + reason;
}

std::string CoarsenedStepNote(double asked, double used, unsigned long long limit)
{
  return "the sample distance " + Number(asked) + " would take more than " + std::to_string(limit) +
         " samples in one frame: frames sample " + Number(used) +
         " apart, and accumulating them refines towards " + Number(asked) +
         " as far as MaximumNumberOfFrames and MemoryBudget allow";
}

std::string SliceProblem(vtkVolumeProperty* property)
{
  vtkImplicitFunction* function = property->GetSliceFunction();
  auto* plane = vtkPlane::SafeDownCast(function);
  if (!plane)
  {
    return std::string("slice blending needs a vtkPlane as the volume property's slice function "
                       "(SetSliceFunction), not ") +
           (function ? function->GetClassName() : "none");
  }
  const double* o = plane->GetOrigin();
  const double* n = plane->GetNormal();
  const auto finite = [](const double* v)
  { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
  if (!finite(o) || !finite(n) || (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0))
  {
    return "the slice plane's origin or normal is not finite, or its normal is zero";
  }
  return std::string();
}

std::string BudgetProblem(
  int width, int height, unsigned long long needed, unsigned long long budget)
{
  return "the images of a " + std::to_string(width) + "x" + std::to_string(height) +
         " viewport (and, while shading or gradient opacity is on, the data's per-voxel "
         "gradients) need " +
         std::to_string(needed) + " bytes, more than the MemoryBudget of " +
         std::to_string(budget) + " bytes: raise MemoryBudget or render fewer pixels";
}
} // namespace vtkSAVRInputChecks

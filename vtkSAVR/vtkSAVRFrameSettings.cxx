#include "vtkSAVRFrameSettings.h"

#include "encoding/SampleEncoding.h"
#include "frame/FrameLoop.h"
#include "sampler/ComponentSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRImageDisplay.h"
#include "vtkSAVRInputChecks.h"
#include "vtkSAVRMapperSettings.h"
#include "vtkSAVRPropertyTables.h"

#include "vtkColorTransferFunction.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace
{
// The engine's blend mode for the mapper's, or false when it has none.
bool ChooseMode(const vtkSAVRMapperSettings& mapper, savr::BlendMode& mode)
{
  if (!vtkSAVRConversions::ToBlendMode(mapper.BlendMode, mode))
  {
    return false;
  }
  if (mode == savr::BlendMode::Composite && mapper.PreIntegration)
  {
    mode = savr::BlendMode::PreIntegrated;
  }
  if (mode == savr::BlendMode::Average && mapper.IntensityAsGrey)
  {
    mode = savr::BlendMode::AverageGrey;
  }
  if (mode == savr::BlendMode::Additive && mapper.IntensityAsGrey)
  {
    mode = savr::BlendMode::AdditiveGrey;
  }
  return true;
}

// What the mode, the components and the property allow: empty, or why the frame cannot be drawn.
std::string ModeProblem(const vtkSAVRMapperSettings& mapper, vtkVolumeProperty* property,
  savr::BlendMode mode, int components)
{
  // Several components are composited, take their maximum or minimum per component, or their
  // grey average or sum (VTK's); their packed codes have no order for the other modes.
  const bool componentMode = mode == savr::BlendMode::Composite ||
                             mode == savr::BlendMode::Maximum || mode == savr::BlendMode::Minimum ||
                             mode == savr::BlendMode::AverageGrey ||
                             mode == savr::BlendMode::AdditiveGrey;
  if (components > 1 && (!componentMode || mapper.PreIntegration))
  {
    return "multi-component scalars render with composite, maximum, minimum, and (with "
           "IntensityAsGrey) average and additive intensity blending only (not with "
           "pre-integration, isosurface or slice blending)";
  }
  if (mode == savr::BlendMode::Slice)
  {
    const std::string sliceProblem = vtkSAVRInputChecks::SliceProblem(property);
    if (!sliceProblem.empty())
    {
      return sliceProblem;
    }
  }
  const std::string functionProblem =
    vtkSAVRInputChecks::TransferFunctionProblem(property, components);
  if (!functionProblem.empty())
  {
    return functionProblem;
  }
  if (mapper.Cropping &&
      !vtkSAVRFrameSettings::CroppingPlanesFinite(mapper.CroppingRegionPlanes.data()))
  {
    return "the cropping region planes are not all finite";
  }
  return std::string();
}

// The step (SampleDistance, or the input's default), the frames that refine it (the mapper's
// limit, or enough to reach the finest step), and what the step must not exceed.
std::string Sampling(const vtkSAVRMapperSettings& mapper, const vtkSAVRFrameSettings::Data& data,
  vtkSAVRFrameSettings::Result& result)
{
  savr::FrameSettings& settings = result.Settings;
  const double asked = mapper.SampleDistance;
  settings.SampleDistance = asked > 0.0 ? asked : data.DefaultStep;
  const double step = settings.SampleDistance;
  // Anchored to the default step, so that K frames at SampleDistance s take the samples of one
  // frame at s / K, and at the default step the rotation is each pixel's own.
  settings.PhaseLength = data.DefaultStep;
  settings.MaximumFrames = mapper.MaximumNumberOfFrames;
  if (settings.MaximumFrames <= 0)
  {
    settings.MaximumFrames = 1;
    while (step / settings.MaximumFrames > data.FinestStep && settings.MaximumFrames < (1 << 16))
    {
      settings.MaximumFrames *= 2;
    }
  }
  const double* b = data.Bounds;
  result.Diagonal = std::sqrt(
    (b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  if (!(step > 0.0) || !std::isfinite(step) || result.Diagonal / step > savr::kMaxSamplesPerRay)
  {
    return "the sample distance " + vtkSAVRInputChecks::Number(step) + " would take more than " +
           std::to_string(static_cast<long long>(savr::kMaxSamplesPerRay)) + " samples per ray";
  }
  // A longer step samples a ray once at most, and the frames to refine it would be unbounded.
  if (step > result.Diagonal)
  {
    return "the sample distance " + vtkSAVRInputChecks::Number(step) +
           " is longer than the data's diagonal (" + vtkSAVRInputChecks::Number(result.Diagonal) +
           ")";
  }
  return std::string();
}

// The values the transfer functions of one component tell apart: the span of their nodes, where
// the blend reads a sample through them alone (composite, pre-integrated, maximum, minimum,
// slice), so that a sample clamped to it blends as the sample does. Functions that do not clamp
// fall to zero beyond their nodes: the window reaches a little further, so that codes there
// stand for values outside. The whole line where the blend reads values themselves (average,
// additive, isosurfaces) or components combine.
std::array<double, 2> CodedWindow(vtkVolumeProperty* property, savr::BlendMode mode, int components)
{
  using savr::BlendMode;
  const bool readThroughFunctions =
    mode == BlendMode::Composite || mode == BlendMode::PreIntegrated ||
    mode == BlendMode::Maximum || mode == BlendMode::Minimum || mode == BlendMode::Slice;
  if (components > 1 || !readThroughFunctions)
  {
    return savr::SampleEncoding::kWholeLine;
  }
  double window[2] = { std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity() };
  bool clamped = true;
  const auto include = [&](const double* range, int nodes, bool clamping)
  {
    if (nodes > 0)
    {
      window[0] = std::min(window[0], range[0]);
      window[1] = std::max(window[1], range[1]);
      clamped = clamped && clamping;
    }
  };
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  include(opacity->GetRange(), opacity->GetSize(), opacity->GetClamping() != 0);
  if (property->GetColorChannels(0) == 3)
  {
    vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);
    include(color->GetRange(), color->GetSize(), color->GetClamping() != 0);
  }
  else
  {
    vtkPiecewiseFunction* gray = property->GetGrayTransferFunction(0);
    include(gray->GetRange(), gray->GetSize(), gray->GetClamping() != 0);
  }
  const double span = window[1] - window[0];
  if (!(span > 0.0) || !std::isfinite(span))
  {
    return savr::SampleEncoding::kWholeLine; // one node, or none: nothing to narrow to
  }
  const double reach = clamped ? 0.0 : span / 4096.0;
  return { window[0] - reach, window[1] + reach };
}

// What is stored with each sample besides its value: gradient magnitudes for gradient opacity,
// normals for shading, fractional bits for narrow features (which also pre-integrate).
void Attributes(const vtkSAVRMapperSettings& mapper, vtkVolumeProperty* property,
  const vtkSAVRFrameSettings::Data& data, vtkSAVRPropertyTables& tables,
  vtkSAVRFrameSettings::Result& result)
{
  savr::FrameSettings& settings = result.Settings;
  // Gradient opacity needs gradient magnitudes, stored with the samples: of the one component,
  // or of each independent component.
  const auto valueRange =
    data.Sampler ? data.Sampler->ValueRange() : std::array<double, 2>{ 0.0, 1.0 };
  result.GradientOpacity =
    tables.TabulateGradientOpacity(property, data.Components, valueRange, data.SmallestSpacing);
  settings.GradientMagnitudes = result.GradientOpacity && !data.Components;
  settings.MagnitudeScale = tables.GetMagnitudeScales()[0];
  settings.ComponentMagnitudes = result.GradientOpacity && data.Components;
  settings.ComponentMagnitudeScales = tables.GetMagnitudeScales();
  settings.Shade = property->GetShade(0) != 0;
  // Independent components are each lit by their own gradient, as VTK's mappers light them.
  settings.ComponentNormals =
    settings.Shade && data.Components && property->GetIndependentComponents();
  // Integral data keeps fractional bits in its stored samples while the transfer functions have
  // features narrower than one of its levels: an edit that needs them starts over; one that no
  // longer does re-blends the finer samples, which are dropped at the next start.
  settings.CodedWindow = CodedWindow(property, result.Mode, data.NumberOfComponents);
  const bool narrowFeatures =
    data.NumberOfComponents <= 1 && data.Sampler &&
    vtkSAVRPropertyTables::NeedsFineCodes(
      property, savr::SampleEncoding::ForSampler(*data.Sampler, false, settings.CodedWindow));
  settings.FineCodes =
    narrowFeatures &&
    savr::SampleEncoding::ForSampler(*data.Sampler, true, settings.CodedWindow).FractionBits > 0;
  // Such features are narrower than any step over data that changes by a level or more per
  // step: point samples hit them by chance (speckles), segments integrate them.
  if (result.Mode == savr::BlendMode::Composite && mapper.AutoPreIntegration && narrowFeatures &&
      !result.GradientOpacity)
  {
    result.Mode = savr::BlendMode::PreIntegrated;
  }
}
} // namespace

bool vtkSAVRFrameSettings::CroppingPlanesFinite(const double planes[6])
{
  return std::all_of(planes, planes + 6, [](double v) { return std::isfinite(v); });
}

vtkSAVRFrameSettings::Result vtkSAVRFrameSettings::Resolve(const vtkSAVRMapperSettings& mapper,
  vtkVolumeProperty* property, const Data& data, vtkSAVRPropertyTables& tables)
{
  Result result;
  if (!ChooseMode(mapper, result.Mode))
  {
    result.Error = "blend mode " + std::to_string(mapper.BlendMode) + " is not supported";
    return result;
  }
  result.Error = ModeProblem(mapper, property, result.Mode, data.NumberOfComponents);
  if (result.Error.empty())
  {
    result.Error = Sampling(mapper, data, result);
  }
  if (!result.Error.empty())
  {
    return result;
  }
  Attributes(mapper, property, data, tables, result);
  if (data.Sampler && data.NumberOfComponents <= 1)
  {
    const std::array<double, 2> coded =
      savr::SampleEncoding::ValuesToCode(*data.Sampler, result.Settings.CodedWindow);
    result.Error = vtkSAVRInputChecks::CodedRangeProblem(
      coded.data(), result.Settings.CodedWindow != savr::SampleEncoding::kWholeLine);
    if (!result.Error.empty())
    {
      return result;
    }
  }
  // The budget covers the mapper's own per-pixel buffers besides the loop's: those of the
  // display per pixel shown here, the image and depth buffers as the view reserves them.
  savr::FrameSettings& settings = result.Settings;
  settings.MemoryBudget = static_cast<std::size_t>(
    std::min<vtkTypeUInt64>(mapper.MemoryBudget, std::numeric_limits<std::size_t>::max()));
  settings.ReservedBytesPerShownPixel = vtkSAVRImageDisplay::BytesPerShownPixel;
  settings.MaximumSamplesPerFrame = kMaxSamplesPerFrame;
  settings.Threads = mapper.NumberOfThreads;
  return result;
}

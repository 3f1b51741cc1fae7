// vtkSAVRVolumeMapper's stages that turn VTK's state into the engine's: the input as a sampler
// (with the checks that refuse what cannot be drawn), the view and the frame settings, and the
// volume property's tables.
#include "vtkSAVRVolumeMapperInternals.h"

#include "sampler/ComponentSampler.h"
#include "sampler/CroppingSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRInputChecks.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRRenderState.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkPlane.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStructuredGrid.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

using vtkSAVRLimits::kMaxSamplesPerFrame;

// The input as a sampler: rebuilt when the input, its scalars, the volume's placement or the
// interpolation change, and wrapped in cropping when that is on.
bool vtkSAVRVolumeMapper::UpdateSampler(Frame& frame)
{
  Internals& s = *this->State;
  this->GetBounds(); // reports inputs VTK would cull, as when it does not call Render
  if (s.UnusableBounds)
  {
    this->Fail(frame, s.LastError);
    return false;
  }
  if (this->GetNumberOfInputConnections(0) == 0 && !this->GetInput())
  {
    this->Fail(frame, "no input: call SetInputData or SetInputConnection");
    return false;
  }
  if (vtkAlgorithm* producer = this->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  frame.Input = input;
  vtkImageData* image = vtkImageData::SafeDownCast(input);
  if (!vtkSAVRInputSamplers::Supported(input))
  {
    this->Fail(
      frame, std::string("the input must be vtkImageData, vtkOverlappingAMR, vtkUnstructuredGrid, "
                         "vtkStructuredGrid, vtkRectilinearGrid or vtkPolyData, not ") +
               (input ? input->GetClassName() : "nothing"));
    return false;
  }
  frame.Property = frame.Volume->GetProperty();
  if (!vtkSAVRConversions::ToBlendMode(this->BlendMode, frame.Mode))
  {
    this->Fail(frame, "blend mode " + std::to_string(this->BlendMode) + " is not supported");
    return false;
  }
  if (frame.Mode == savr::BlendMode::Composite && this->PreIntegration)
  {
    frame.Mode = savr::BlendMode::PreIntegrated;
  }
  if (frame.Mode == savr::BlendMode::Average && this->IntensityAsGrey)
  {
    frame.Mode = savr::BlendMode::AverageGrey;
  }
  if (frame.Mode == savr::BlendMode::Additive && this->IntensityAsGrey)
  {
    frame.Mode = savr::BlendMode::AdditiveGrey;
  }

  vtkMatrix4x4* volumeMatrix = frame.Volume->GetMatrix();
  if (auto* dataSet = vtkDataSet::SafeDownCast(input))
  {
    frame.Scalars = vtkAbstractMapper::GetScalars(dataSet, this->ScalarMode, this->ArrayAccessMode,
      this->ArrayId, this->ArrayName, frame.CellFlag);
  }
  switch (s.Changes.CompareInput(
    this, input, frame.Scalars, frame.CellFlag, frame.Property, volumeMatrix))
  {
    case vtkSAVRFrameChanges::Input::KnownBad:
      this->Fail(frame, s.LastError); // the same input again: fail without rescanning it
      return false;
    case vtkSAVRFrameChanges::Input::Changed:
      if (!this->BuildSampler(frame))
      {
        return false;
      }
      break;
    case vtkSAVRFrameChanges::Input::Unchanged:
      break;
  }

  // Several components are composited, take their maximum or minimum per component, or their
  // grey average or sum (VTK's); their packed codes have no order for the other modes.
  frame.Components = image ? s.Inputs.GetNumberOfImageComponents() : 1;
  const bool componentMode =
    frame.Mode == savr::BlendMode::Composite || frame.Mode == savr::BlendMode::Maximum ||
    frame.Mode == savr::BlendMode::Minimum || frame.Mode == savr::BlendMode::AverageGrey ||
    frame.Mode == savr::BlendMode::AdditiveGrey;
  if (frame.Components > 1 && (!componentMode || this->PreIntegration))
  {
    this->Fail(frame, "multi-component scalars render with composite, maximum, minimum, and (with "
                      "IntensityAsGrey) average and additive intensity blending only (not with "
                      "pre-integration, isosurface or slice blending)");
    return false;
  }
  if (frame.Mode == savr::BlendMode::Slice)
  {
    const std::string sliceProblem = vtkSAVRInputChecks::SliceProblem(frame.Property);
    if (!sliceProblem.empty())
    {
      this->Fail(frame, sliceProblem);
      return false;
    }
    auto* plane = vtkPlane::SafeDownCast(frame.Property->GetSliceFunction());
    s.Loop.SetSlicePlane(Eigen::Vector3d(plane->GetOrigin()), Eigen::Vector3d(plane->GetNormal()));
  }

  const std::string functionProblem =
    vtkSAVRInputChecks::TransferFunctionProblem(frame.Property, frame.Components);
  if (!functionProblem.empty())
  {
    this->Fail(frame, functionProblem);
    return false;
  }
  // A NaN plane would make every frame look changed and start over.
  if (this->Cropping && !std::all_of(this->CroppingRegionPlanes, this->CroppingRegionPlanes + 6,
                          [](double v) { return std::isfinite(v); }))
  {
    this->Fail(frame, "the cropping region planes are not all finite");
    return false;
  }
  // Cropping wraps the image's sampler; changing it does not rescan the data.
  if (s.Changes.CroppingChanged(this, volumeMatrix))
  {
    s.Sampler = s.DataSampler;
    if (this->Cropping)
    {
      s.Sampler = std::make_shared<savr::CroppingSampler>(s.Sampler,
        Eigen::Affine3d(vtkSAVRConversions::ToEigen(volumeMatrix)).inverse(),
        this->CroppingRegionPlanes, static_cast<std::uint32_t>(this->CroppingRegionFlags));
    }
  }
  return true;
}

// Builds the sampler of the input CompareInput found changed, with its spacings.
bool vtkSAVRVolumeMapper::BuildSampler(Frame& frame)
{
  Internals& s = *this->State;
  vtkSAVRInputSamplers::Request request;
  request.Scalars = frame.Scalars;
  request.CellData = frame.CellFlag == 1;
  request.VolumeMatrix = frame.Volume->GetMatrix();
  request.Interpolation = frame.Property->GetInterpolationType();
  request.IndependentComponents = frame.Property->GetIndependentComponents() != 0;
  request.ScalarMode = this->ScalarMode;
  request.ArrayAccessMode = this->ArrayAccessMode;
  request.ArrayId = this->ArrayId;
  request.ArrayName = this->ArrayName;
  request.ParticleRadius = this->ParticleRadius;
  request.ParticleRadiusArrayName = this->ParticleRadiusArrayName;
  request.ParticleKernel = this->ParticleKernel;
  request.ParticleNormalized = this->ParticleNormalized;
  vtkSAVRInputSamplers::Result built = s.Inputs.Build(frame.Input, request);
  for (const std::string& warning : built.Warnings)
  {
    vtkErrorMacro(<< warning);
  }
  if (!built.Sampler)
  {
    this->Fail(frame, "cannot render this input: " + built.Error);
    s.Changes.RejectInput();
    s.DataSampler.reset();
    return false;
  }
  s.DataSampler = built.Sampler;
  s.SmallestSpacing = built.SmallestSpacing;
  s.DefaultStep = built.DefaultStep;
  s.FinestStep = built.FinestStep;
  s.Changes.AcceptInput();
  s.LastError.clear();
  return true;
}

// The sampling settings, the viewport, the camera's rays, the depth of geometry drawn already and
// the clipping planes: when any of them changed, the stored samples start over.
bool vtkSAVRVolumeMapper::UpdateView(Frame& frame)
{
  Internals& s = *this->State;
  vtkRenderer* ren = frame.Renderer;
  vtkVolumeProperty* property = frame.Property;
  savr::FrameSettings settings;
  settings.SampleDistance = this->SampleDistance > 0.0 ? this->SampleDistance : s.DefaultStep;
  const double step = settings.SampleDistance;
  // Anchored to the default step, so that K frames at SampleDistance s take the samples of one
  // frame at s / K, and at the default step the rotation is each pixel's own.
  settings.PhaseLength = s.DefaultStep;
  settings.MaximumFrames = this->MaximumNumberOfFrames;
  if (settings.MaximumFrames <= 0)
  {
    settings.MaximumFrames = 1;
    while (step / settings.MaximumFrames > s.FinestStep && settings.MaximumFrames < (1 << 16))
    {
      settings.MaximumFrames *= 2;
    }
  }
  const double* bounds = frame.Volume->GetBounds();
  std::copy(bounds, bounds + 6, frame.Bounds);
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
                                    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
                                    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(step > 0.0) || !std::isfinite(step) || diagonal / step > savr::kMaxSamplesPerRay)
  {
    this->Fail(frame,
      "the sample distance " + vtkSAVRInputChecks::Number(step) + " would take more than " +
        std::to_string(static_cast<long long>(savr::kMaxSamplesPerRay)) + " samples per ray");
    return false;
  }
  // A longer step samples a ray once at most, and the frames to refine it would be unbounded.
  if (step > diagonal)
  {
    this->Fail(frame, "the sample distance " + vtkSAVRInputChecks::Number(step) +
                        " is longer than the data's diagonal (" +
                        vtkSAVRInputChecks::Number(diagonal) + ")");
    return false;
  }
  s.Step = step;

  savr::View& view = frame.View;
  ren->GetTiledSizeAndOrigin(&view.Width, &view.Height, &frame.Origin[0], &frame.Origin[1]);
  if (view.Width <= 0 || view.Height <= 0)
  {
    s.NothingToRefine = true;
    return false;
  }
  s.NothingToRefine = false;
  vtkNew<vtkMatrix4x4> worldToNDC;
  worldToNDC->DeepCopy(ren->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    ren->GetTiledAspectRatio(), -1, 1));
  view.NDCToWorld = vtkSAVRConversions::ToEigen(worldToNDC).inverse();
  if (!view.NDCToWorld.allFinite())
  {
    this->Fail(frame, vtkSAVRInputChecks::CameraProblem(ren->GetActiveCamera(), diagonal));
    return false;
  }
  if (vtkSAVRRenderState::DepthMayHoldGeometry(ren))
  {
    view.Depth.resize(static_cast<std::size_t>(view.Width) * view.Height);
    ren->GetRenderWindow()->GetZbufferData(frame.Origin[0], frame.Origin[1],
      frame.Origin[0] + view.Width - 1, frame.Origin[1] + view.Height - 1, view.Depth.data());
  }
  if (!vtkSAVRConversions::ToPlanes(this->ClippingPlanes, view.ClippingPlanes))
  {
    this->Fail(frame, "a clipping plane's normal or origin is not finite");
    return false;
  }

  // Gradient opacity needs gradient magnitudes, stored with the samples: of the one component,
  // or of each independent component.
  const auto valueRange = s.Sampler ? s.Sampler->ValueRange() : std::array<double, 2>{ 0.0, 1.0 };
  const savr::ComponentSampler* components =
    frame.Components > 1 ? static_cast<const savr::ComponentSampler*>(s.DataSampler.get())
                         : nullptr;
  frame.GradientOpacity =
    s.Tables.TabulateGradientOpacity(property, components, valueRange, s.SmallestSpacing);
  settings.GradientMagnitudes = frame.GradientOpacity && !components;
  settings.MagnitudeScale = s.Tables.GetMagnitudeScales()[0];
  settings.ComponentMagnitudes = frame.GradientOpacity && components;
  settings.ComponentMagnitudeScales = s.Tables.GetMagnitudeScales();
  // The budget covers the mapper's own per-pixel buffers besides the loop's: the 8-bit image,
  // the depth buffer read (and the copy kept to compare with the next), the display's.
  settings.MemoryBudget = static_cast<std::size_t>(
    std::min<vtkTypeUInt64>(this->MemoryBudget, std::numeric_limits<std::size_t>::max()));
  settings.ReservedBytes =
    static_cast<std::size_t>(view.Width) * view.Height * 4 + 2 * view.Depth.size() * sizeof(float);
  settings.ReservedBytesPerShownPixel = vtkSAVRImageDisplay::BytesPerShownPixel;
  settings.MaximumSamplesPerFrame = kMaxSamplesPerFrame;
  settings.Threads = this->NumberOfThreads;
  settings.Shade = property->GetShade(0) != 0;
  // Independent components are each lit by their own gradient, as VTK's mappers light them.
  settings.ComponentNormals = settings.Shade && components && property->GetIndependentComponents();
  // Integral data keeps fractional bits in its stored samples while the transfer functions have
  // features narrower than one of its levels: an edit that needs them starts over; one that no
  // longer does re-blends the finer samples, which are dropped at the next start.
  const bool narrowFeatures =
    frame.Components <= 1 && s.Sampler &&
    vtkSAVRPropertyTables::NeedsFineCodes(property, savr::SampleEncoding::ForSampler(*s.Sampler));
  settings.FineCodes =
    narrowFeatures && savr::SampleEncoding::ForSampler(*s.Sampler, true).FractionBits > 0;
  // Such features are narrower than any step over data that changes by a level or more per
  // step: point samples hit them by chance (speckles), segments integrate them.
  if (frame.Mode == savr::BlendMode::Composite && this->AutoPreIntegration && narrowFeatures &&
      !frame.GradientOpacity)
  {
    frame.Mode = savr::BlendMode::PreIntegrated;
  }
  s.PreIntegrating = frame.Mode == savr::BlendMode::PreIntegrated;
  const bool finerCodes = settings.FineCodes && s.Loop.Encoding().FractionBits == 0;
  if (s.Changes.ViewChanged(
        this, property, view, worldToNDC, frame.Bounds, frame.Origin, settings) ||
      finerCodes)
  {
    s.Loop.Reset(view, s.Sampler, settings);
    s.HaveImage = false;
  }
  if (s.Loop.OverBudget())
  {
    this->Fail(frame, vtkSAVRInputChecks::BudgetProblem(
                        view.Width, view.Height, s.Loop.FixedBytes(), this->MemoryBudget));
    return false;
  }
  s.Step = s.Loop.SampleDistance();
  if (s.Step > step && s.CoarsenedStep != step)
  {
    vtkWarningMacro(<< vtkSAVRInputChecks::CoarsenedStepNote(step, s.Step, kMaxSamplesPerFrame));
    s.CoarsenedStep = step;
  }
  return true;
}

// The volume property's tables: each retabulated when what it depends on changed, which then
// re-blends the stored samples.
void vtkSAVRVolumeMapper::UpdateTables(Frame& frame)
{
  Internals& s = *this->State;
  vtkSAVRPropertyTables::FrameInputs inputs;
  inputs.Property = frame.Property;
  inputs.Renderer = frame.Renderer;
  inputs.Components = frame.Components > 1
                        ? static_cast<const savr::ComponentSampler*>(s.DataSampler.get())
                        : nullptr;
  // Dependent RGBA colours are normalized as textures are: integers over their type's maximum.
  vtkDataArray* scalars = frame.Scalars;
  inputs.ColorScale =
    scalars && scalars->GetDataType() != VTK_FLOAT && scalars->GetDataType() != VTK_DOUBLE
      ? 1.0 / scalars->GetDataTypeMax()
      : 1.0;
  inputs.Mode = frame.Mode;
  inputs.GradientOpacity = frame.GradientOpacity;
  inputs.PreIntegration = frame.Mode == savr::BlendMode::PreIntegrated;
  // Unstructured and curvilinear grids (not particles) read opacity as VTK's unstructured
  // mappers do, unless asked otherwise.
  inputs.OpacityIsAttenuation = this->MeshOpacityAsAttenuation &&
                                (vtkUnstructuredGrid::SafeDownCast(frame.Input) ||
                                  vtkStructuredGrid::SafeDownCast(frame.Input)) &&
                                !vtkSAVRParticleSampler::Particles(frame.Input);
  s.Tables.Update(inputs, s.Changes, s.Loop);
}

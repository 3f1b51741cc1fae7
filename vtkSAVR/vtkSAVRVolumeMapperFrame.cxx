// vtkSAVRVolumeMapper's stages that turn VTK's state into the engine's: the input as a sampler,
// the frame settings (vtkSAVRFrameSettings holds the checks and defaults), the view, and the
// volume property's tables.
#include "vtkSAVRVolumeMapperInternals.h"

#include "sampler/ComponentSampler.h"
#include "sampler/CroppingSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRFrameSettings.h"
#include "vtkSAVRInputChecks.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRRenderState.h"
#include "vtkSAVRVectorSelection.h"

vtkSAVRMapperSettings vtkSAVRMapperSettingsOf(vtkSAVRVolumeMapper* mapper)
{
  vtkSAVRMapperSettings settings;
  settings.BlendMode = mapper->GetBlendMode();
  settings.Cropping = mapper->GetCropping() != 0;
  const double* planes = mapper->GetCroppingRegionPlanes();
  std::copy(planes, planes + 6, settings.CroppingRegionPlanes.begin());
  settings.CroppingRegionFlags = mapper->GetCroppingRegionFlags();
  settings.ScalarMode = mapper->GetScalarMode();
  settings.ArrayAccessMode = mapper->GetArrayAccessMode();
  settings.ArrayId = mapper->GetArrayId();
  settings.ArrayName = mapper->GetArrayName() ? mapper->GetArrayName() : "";
  settings.SampleDistance = mapper->GetSampleDistance();
  settings.MaximumNumberOfFrames = mapper->GetMaximumNumberOfFrames();
  settings.MemoryBudget = mapper->GetMemoryBudget();
  settings.NumberOfThreads = mapper->GetNumberOfThreads();
  settings.IntensityAsGrey = mapper->GetIntensityAsGrey();
  settings.PreIntegration = mapper->GetPreIntegration();
  settings.AutoPreIntegration = mapper->GetAutoPreIntegration();
  settings.VectorMode = mapper->GetVectorMode();
  settings.VectorComponent = mapper->GetVectorComponent();
  settings.ParticleRadius = mapper->GetParticleRadius();
  settings.ParticleRadiusArrayName =
    mapper->GetParticleRadiusArrayName() ? mapper->GetParticleRadiusArrayName() : "";
  settings.ParticleKernel = mapper->GetParticleKernel();
  settings.ParticleNormalized = mapper->GetParticleNormalized();
  return settings;
}

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
  frame.Mapper.VectorMode =
    vtkSAVRVectorSelection::Effective(frame.Mapper.VectorMode, frame.Property);

  vtkMatrix4x4* volumeMatrix = frame.Volume->GetMatrix();
  if (auto* dataSet = vtkDataSet::SafeDownCast(input))
  {
    // A vector array as the one component its vector mode draws (AMR blocks: in their sampler).
    frame.Scalars =
      s.Vectors.Select(vtkAbstractMapper::GetScalars(dataSet, this->ScalarMode,
                         this->ArrayAccessMode, this->ArrayId, this->ArrayName, frame.CellFlag),
        frame.Mapper.VectorMode, frame.Mapper.VectorComponent);
  }
  switch (s.Changes.CompareInput(
    frame.Mapper, input, frame.Scalars, frame.CellFlag, frame.Property, volumeMatrix))
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

  frame.Components = image ? s.Inputs.GetNumberOfImageComponents() : 1;
  // Cropping wraps the image's sampler; changing it does not rescan the data. (Planes that are
  // not all finite are refused by ResolveSettings.)
  if (vtkSAVRFrameSettings::CroppingPlanesFinite(this->CroppingRegionPlanes) &&
      s.Changes.CroppingChanged(frame.Mapper, volumeMatrix))
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
  request.VectorMode = frame.Mapper.VectorMode;
  request.VectorComponent = frame.Mapper.VectorComponent;
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

// The mapper's checks and defaults (vtkSAVRFrameSettings): the blend mode and the engine's frame
// settings, or the reason the frame cannot be drawn.
bool vtkSAVRVolumeMapper::ResolveSettings(Frame& frame)
{
  Internals& s = *this->State;
  vtkSAVRFrameSettings::Data data;
  data.Sampler = s.Sampler.get();
  data.Components = frame.Components > 1
                      ? static_cast<const savr::ComponentSampler*>(s.DataSampler.get())
                      : nullptr;
  data.NumberOfComponents = frame.Components;
  data.SmallestSpacing = s.SmallestSpacing;
  data.DefaultStep = s.DefaultStep;
  data.FinestStep = s.FinestStep;
  const double* bounds = frame.Volume->GetBounds();
  std::copy(bounds, bounds + 6, frame.Bounds);
  data.Bounds = frame.Bounds;
  vtkSAVRFrameSettings::Result resolved =
    vtkSAVRFrameSettings::Resolve(frame.Mapper, frame.Property, data, s.Tables);
  if (!resolved.Error.empty())
  {
    this->Fail(frame, resolved.Error);
    return false;
  }
  frame.Mode = resolved.Mode;
  frame.Settings = resolved.Settings;
  frame.GradientOpacity = resolved.GradientOpacity;
  frame.Diagonal = resolved.Diagonal;
  if (frame.Mode == savr::BlendMode::Slice)
  {
    auto* plane = vtkPlane::SafeDownCast(frame.Property->GetSliceFunction());
    s.Loop.SetSlicePlane(Eigen::Vector3d(plane->GetOrigin()), Eigen::Vector3d(plane->GetNormal()));
  }
  s.Step = frame.Settings.SampleDistance;
  s.PreIntegrating = frame.Mode == savr::BlendMode::PreIntegrated;
  return true;
}

// The viewport, the camera's rays, the depth of geometry drawn already and the clipping planes:
// when any of them or the frame settings changed, the stored samples start over.
bool vtkSAVRVolumeMapper::UpdateView(Frame& frame)
{
  Internals& s = *this->State;
  vtkRenderer* ren = frame.Renderer;
  savr::FrameSettings& settings = frame.Settings;
  const double step = settings.SampleDistance;

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
    this->Fail(frame, vtkSAVRInputChecks::CameraProblem(ren->GetActiveCamera(), frame.Diagonal));
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

  // What the view reserves of the budget: the 8-bit image, the depth buffer read and the copy
  // kept to compare with the next.
  settings.ReservedBytes =
    static_cast<std::size_t>(view.Width) * view.Height * 4 + 2 * view.Depth.size() * sizeof(float);
  // Codes that do not cover what the transfer functions now tell apart, or only coarsely (their
  // domain widened, or narrowed to a few of the codes), or that lack the fractional bits narrow
  // features need, start over; other edits re-blend the samples stored.
  const bool finerCodes = settings.FineCodes && s.Loop.Encoding().FractionBits == 0;
  const bool codesServe = !s.Sampler || s.Loop.Encoding().Serves(savr::SampleEncoding::ForSampler(
                                          *s.Sampler, settings.FineCodes, settings.CodedWindow));
  if (s.Changes.ViewChanged(
        frame.Mapper, frame.Property, view, worldToNDC, frame.Bounds, frame.Origin, settings) ||
      finerCodes || !codesServe)
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
  // A step the user set that one frame cannot take is worth a warning; one the mapper chose
  // itself (SampleDistance 0) is state only (GetEffectiveSampleDistance).
  if (s.Step > step && s.CoarsenedStep != step && this->SampleDistance > 0.0)
  {
    vtkWarningMacro(<< vtkSAVRInputChecks::CoarsenedStepNote(
                      step, s.Step, settings.MaximumSamplesPerFrame));
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

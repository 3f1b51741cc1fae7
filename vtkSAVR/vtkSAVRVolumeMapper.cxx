#include "vtkSAVRVolumeMapper.h"

#include "sampler/ComponentSampler.h"
#include "sampler/CroppingSampler.h"
#include "frame/FrameLoop.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRDualPeeling.h"
#include "vtkSAVRFrameChanges.h"
#include "vtkSAVRImageDisplay.h"
#include "vtkSAVRInputChecks.h"
#include "vtkSAVRInputSamplers.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRPropertyTables.h"
#include "vtkSAVRRenderState.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkRectilinearGrid.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkStructuredGrid.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <new>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSAVRVolumeMapper);

namespace
{
// Samples one frame takes at most over the rays' lengths (plus one per ray): as many as a
// 512x512 view filled by a 256^3 image takes face-on at its voxel spacing, about a second on two
// cores. Finer steps are coarsened for each frame.
constexpr std::size_t kMaxSamplesPerFrame = std::size_t(1) << 26;

} // namespace

struct vtkSAVRVolumeMapper::Internals
{
  savr::FrameLoop Loop;
  vtkSAVRPropertyTables Tables;
  vtkSAVRFrameChanges Changes;
  vtkSAVRImageDisplay Display;
  // Dual depth peeling for volumes: the stage calling Render, and what its later stages draw
  // from (the frame of the first stage: its blend mode, and whether it made an image).
  vtkSAVRDualPeeling Peeling;
  savr::BlendMode PeelingMode = savr::BlendMode::Composite;
  bool PeelingImage = false;
  vtkSAVRInputSamplers Inputs;
  std::shared_ptr<const savr::Sampler> DataSampler; // the input's, as built
  std::shared_ptr<const savr::Sampler> Sampler;     // the image's, cropped when cropping is on
  std::vector<unsigned char> Bytes;
  std::string LastError;
  double Step = 0.0;
  double SmallestSpacing = 0.0; // the finest cell edge, in world units
  double DefaultStep = 0.0;     // SampleDistance's default
  double CoarsenedStep = 0.0;   // the step asked that was last reported coarsened
  bool HaveImage = false;
  bool PreIntegrating = false; // the last frame's composite was pre-integrated
  // The step of interactive single passes, in base steps (a power of two, 1 to 8).
  double InteractiveStepFactor = 1.0;
  // Nothing can be drawn (bad input, empty viewport): further frames would add nothing.
  bool NothingToRefine = false;
  // The input's bounds leave nothing to draw (found by GetBounds: VTK then never calls Render).
  bool UnusableBounds = false;

  // Every frame is taken, or the error estimate is below the tolerance, and the image shown is
  // their blend (not an interacting pass).
  bool Complete(double tolerance) const
  {
    const double estimate = this->Loop.ErrorEstimate();
    return (this->Loop.Complete() || (tolerance > 0.0 && estimate >= 0.0 && estimate < tolerance));
  }

  void ClearImage()
  {
    this->Loop.Reset(savr::View(), nullptr, savr::FrameSettings());
    this->Changes.ForgetView();
    this->HaveImage = false;
  }
};

struct vtkSAVRVolumeMapper::Frame
{
  vtkRenderer* Renderer = nullptr;
  vtkVolume* Volume = nullptr;
  vtkVolumeProperty* Property = nullptr;
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
  /// Seconds since Start.
  double Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }
  vtkDataObject* Input = nullptr;
  vtkDataArray* Scalars = nullptr; // of an image or a mesh
  int CellFlag = 0;
  savr::BlendMode Mode = savr::BlendMode::Composite;
  int Components = 1;
  bool GradientOpacity = false;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  int Origin[2] = { 0, 0 }; // of the viewport in the window
  savr::View View;
  bool Peeling = false; // made at dual depth peeling's first volume stage
};

vtkSAVRVolumeMapper::vtkSAVRVolumeMapper()
  : State(new Internals)
{
}

vtkSAVRVolumeMapper::~vtkSAVRVolumeMapper()
{
  this->SetParticleRadiusArrayName(nullptr);
}

int vtkSAVRVolumeMapper::GetNumberOfFramesAccumulated() const
{
  return this->State->Loop.FrameLimit() > 0 ? this->State->Loop.Frames() : 0;
}

double vtkSAVRVolumeMapper::GetInteractiveSampleDistance() const
{
  const Internals& s = *this->State;
  return s.Step * (this->AutoAdjustSampleDistances ? s.InteractiveStepFactor : 1.0);
}

void vtkSAVRVolumeMapper::AdaptInteractiveStep(Frame& frame)
{
  Internals& s = *this->State;
  const double target = frame.Volume ? frame.Volume->GetAllocatedRenderTime() : 0.0;
  if (!this->AutoAdjustSampleDistances || !(target > 0.0) || !std::isfinite(target))
  {
    return;
  }
  const double spent = frame.Seconds();
  if (spent > target)
  {
    s.InteractiveStepFactor = std::min(2.0 * s.InteractiveStepFactor, 8.0);
  }
  else if (spent < 0.4 * target)
  {
    s.InteractiveStepFactor = std::max(0.5 * s.InteractiveStepFactor, 1.0);
  }
}

double vtkSAVRVolumeMapper::GetFrameInProgress() const
{
  return this->State->Loop.FrameProgress();
}

int vtkSAVRVolumeMapper::GetFrameLimit() const
{
  return this->State->Loop.FrameLimit();
}

bool vtkSAVRVolumeMapper::GetRefinementComplete() const
{
  const Internals& s = *this->State;
  if (s.NothingToRefine || s.UnusableBounds || this->HasNoInput())
  {
    return true;
  }
  return s.HaveImage && !this->Interactive && s.Loop.CurrentPhase() != savr::Phase::Interacting &&
         s.Complete(this->ErrorTolerance);
}

double vtkSAVRVolumeMapper::GetErrorEstimate() const
{
  return this->State->Loop.ErrorEstimate();
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetMemoryInUse() const
{
  return this->State->Loop.MemoryInUse();
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetImageMemoryInUse() const
{
  return this->State->Loop.FixedBytes();
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetNumberOfSamplesTaken() const
{
  return static_cast<vtkTypeUInt64>(this->State->Loop.SamplesTaken());
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetNumberOfStoredSamples() const
{
  return static_cast<vtkTypeUInt64>(this->State->Loop.SamplesPerFrame()) *
         this->GetNumberOfFramesAccumulated();
}

double vtkSAVRVolumeMapper::GetEffectiveSampleDistance() const
{
  return this->State->Step;
}

void vtkSAVRVolumeMapper::SetInputData(vtkOverlappingAMR* amr)
{
  this->SetInputDataInternal(0, amr);
}

int vtkSAVRVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
  {
    return 0;
  }
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkOverlappingAMR");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkStructuredGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkRectilinearGrid");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

bool vtkSAVRVolumeMapper::HasNoInput() const
{
  auto* self = const_cast<vtkSAVRVolumeMapper*>(this);
  return self->GetNumberOfInputConnections(0) == 0 || !self->GetInputDataObject(0, 0);
}

void vtkSAVRVolumeMapper::SetInputData(vtkDataSet* input)
{
  this->SetInputDataObject(0, input);
}

void vtkSAVRVolumeMapper::SetInputData(vtkUnstructuredGrid* grid)
{
  this->SetInputDataObject(0, grid);
}

// VTK asks every visible volume for its bounds before deciding whether to render it: the one
// place to find the inputs it will never call Render for.
double* vtkSAVRVolumeMapper::GetBounds()
{
  double* bounds = this->InputBounds();
  Internals& s = *this->State;
  const std::string problem = this->HasNoInput()
                                ? std::string("no input: call SetInputData or SetInputConnection")
                                : vtkSAVRInputChecks::BoundsProblem(bounds);
  s.UnusableBounds = !problem.empty();
  if (s.UnusableBounds)
  {
    this->ReportError(problem);
  }
  return bounds;
}

void vtkSAVRVolumeMapper::ReportError(const std::string& message)
{
  Internals& s = *this->State;
  if (message != s.LastError)
  {
    vtkErrorMacro(<< message);
    s.LastError = message;
  }
}

double* vtkSAVRVolumeMapper::InputBounds()
{
  if (vtkOverlappingAMR::SafeDownCast(this->GetInputDataObject(0, 0)))
  {
    vtkAlgorithm* producer = this->GetInputAlgorithm();
    if (producer)
    {
      producer->Update();
    }
    auto* amr = vtkOverlappingAMR::SafeDownCast(this->GetInputDataObject(0, 0));
    if (amr && amr->GetAMRInfo() && amr->GetNumberOfLevels() > 0)
    {
      amr->GetBounds(this->Bounds);
    }
    else
    {
      vtkMath::UninitializeBounds(this->Bounds); // an empty hierarchy (VTK would crash)
    }
    return this->Bounds;
  }
  if (vtkPointSet::SafeDownCast(this->GetInputDataObject(0, 0)))
  {
    // Whether an unstructured grid holds particles depends on its cells: update it first.
    if (vtkAlgorithm* producer = this->GetInputAlgorithm())
    {
      producer->Update();
    }
    if (vtkPointSet* particles = vtkSAVRParticleSampler::Particles(this->GetInputDataObject(0, 0)))
    {
      // What the particles' kernels reach, beyond their points.
      vtkSAVRParticleSampler::SupportBounds(particles, this->ParticleRadius,
        this->ParticleRadiusArrayName, this->ParticleKernel, this->Bounds);
      return this->Bounds;
    }
  }
  return this->Superclass::GetBounds();
}

void vtkSAVRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->State->Display.ReleaseGraphicsResources(window);
  this->State->Peeling.ReleaseGraphicsResources(window);
}

void vtkSAVRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  if (!ren || !vol || !ren->GetActiveCamera() || !ren->GetRenderWindow())
  {
    return;
  }
  // A hardware selector's passes read ids from the colours drawn: the volume's image would read
  // as thousands of junk ids. vtkVolumePicker picks volumes without drawing.
  if (ren->GetSelector())
  {
    return;
  }
  // Under dual depth peeling for volumes, VTK calls Render once before peeling, once per peel
  // and once at the end: the frame is made at the first call; each call draws its parts of it.
  using Stage = vtkSAVRDualPeeling::Stage;
  const Stage stage = this->State->Peeling.Find(vol);
  if (stage == Stage::Peeling || stage == Stage::AlphaBlending)
  {
    const auto start = std::chrono::steady_clock::now();
    this->DrawPeelingStage(ren);
    this->LastFrameTime +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return;
  }
  this->State->PeelingImage = false;
  ++this->NumberOfRenders;
  Frame frame;
  frame.Peeling = stage == Stage::Initializing;
  frame.Renderer = ren;
  frame.Volume = vol;
  // No exception may leave Render (VTK's render loop does not expect one, and an uncaught
  // std::bad_alloc ends the process): whatever throws ends this input like bad input does.
  try
  {
    this->State->Changes.BeginFrame();
    if (!this->UpdateSampler(frame) || !this->UpdateView(frame))
    {
      return;
    }
    this->UpdateTables(frame);
    bool imageChanged = this->SampleOrBlend(frame);
    if (this->CompleteEachRender)
    {
      imageChanged = this->RefineToCompletion(frame, imageChanged);
    }
    this->DisplayImage(frame, imageChanged);
    this->FinishFrame(frame, imageChanged);
  }
  catch (const std::bad_alloc&)
  {
    this->Fail(frame, "rendering stopped: out of memory (std::bad_alloc)");
  }
  catch (const std::exception& e)
  {
    this->Fail(frame, std::string("rendering stopped by an exception: ") + e.what());
  }
}

void vtkSAVRVolumeMapper::Fail(Frame& frame, const std::string& message)
{
  Internals& s = *this->State;
  this->ReportError(message);
  s.ClearImage();
  s.NothingToRefine = true;
  this->LastFrameTime = frame.Seconds();
}

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
    this->Fail(frame,
      "multi-component scalars render with composite, maximum, minimum, and (with "
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
    while (step / settings.MaximumFrames > 0.25 * s.SmallestSpacing &&
           settings.MaximumFrames < (1 << 16))
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

  // Gradient opacity needs gradient magnitudes, stored with the samples.
  const auto valueRange = s.Sampler ? s.Sampler->ValueRange() : std::array<double, 2>{ 0.0, 1.0 };
  frame.GradientOpacity =
    s.Tables.TabulateGradientOpacity(property, frame.Components > 1, valueRange, s.SmallestSpacing);
  settings.GradientMagnitudes = frame.GradientOpacity;
  settings.MagnitudeScale = s.Tables.GetMagnitudeScale();
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

// One frame of the current phase; returns whether the image changed.
bool vtkSAVRVolumeMapper::SampleOrBlend(Frame& frame)
{
  Internals& s = *this->State;
  const savr::TransferFunctionTable& table = s.Tables.GetTransferFunction();
  switch (s.Changes.NextAction(
    this->Interactive, s.Complete(this->ErrorTolerance), s.Loop.CurrentPhase()))
  {
    case vtkSAVRFrameChanges::Action::SinglePass:
    {
      // Nothing of this frame is kept: skip what the transfer function hides, and stop rays once
      // what lies behind could change a pixel by less than one 8-bit level.
      savr::PassOptions fast;
      fast.SkipTransparent = true;
      fast.Termination = 1.0 / 256.0;
      s.Loop.RenderSinglePass(table, frame.Mode, this->GetInteractiveSampleDistance(), 0.0, fast);
      this->AdaptInteractiveStep(frame);
      return true;
    }
    case vtkSAVRFrameChanges::Action::Accumulate:
    {
      // What is left of the render's bound (at least one group of tiles is always done).
      double seconds = 0.0;
      if (this->MaximumRenderTime > 0.0 && !this->CompleteEachRender)
      {
        const double spent = frame.Seconds();
        seconds = std::max(this->MaximumRenderTime - spent, 1e-9);
      }
      s.Loop.AccumulateFrame(table, frame.Mode, seconds);
      return true;
    }
    case vtkSAVRFrameChanges::Action::Reblend:
      s.Loop.Reblend(table, frame.Mode);
      return true;
    case vtkSAVRFrameChanges::Action::Reuse:
      break;
  }
  return false;
}

// The frames left before completion, in this Render; the image is drawn once, after them.
bool vtkSAVRVolumeMapper::RefineToCompletion(Frame& frame, bool imageChanged)
{
  Internals& s = *this->State;
  // Bounded by the frame limit whatever NextAction answers.
  for (int frames = 0; imageChanged && !this->Interactive && !s.Complete(this->ErrorTolerance) &&
                       frames < this->GetFrameLimit();
       ++frames)
  {
    this->FinishFrame(frame, true);
    frame.Start = std::chrono::steady_clock::now();
    if (!this->SampleOrBlend(frame))
    {
      break;
    }
  }
  return imageChanged;
}

void vtkSAVRVolumeMapper::DisplayImage(Frame& frame, bool imageChanged)
{
  Internals& s = *this->State;
  if (imageChanged)
  {
    s.Loop.ImageBytes(s.Bytes);
    int rectangle[4];
    s.Loop.ImageRectangle(rectangle);
    s.Display.SetImage(s.Bytes, frame.View.Width, frame.View.Height, rectangle);
    s.HaveImage = true;
  }
  if (s.HaveImage)
  {
    if (frame.Peeling)
    {
      s.PeelingMode = frame.Mode;
      s.PeelingImage = true;
      this->DrawPeelingStage(frame.Renderer);
    }
    else
    {
      s.Display.Draw(
        frame.Renderer, frame.Volume, frame.Bounds, frame.View.Width, frame.View.Height);
    }
  }
}

// The peeling stage's part of the frame the first stage made (see vtkSAVRDualPeeling::DrawStage).
void vtkSAVRVolumeMapper::DrawPeelingStage(vtkRenderer* ren)
{
  Internals& s = *this->State;
  if (s.PeelingImage && s.HaveImage)
  {
    s.Peeling.DrawStage(ren, s.Loop, s.Tables.GetTransferFunction(), s.PeelingMode, s.Bytes);
  }
}

void vtkSAVRVolumeMapper::FinishFrame(Frame& frame, bool imageChanged)
{
  this->LastFrameTime = frame.Seconds();
  if (imageChanged && !this->Interactive)
  {
    FrameInfo info{ this->GetNumberOfFramesAccumulated(), this->GetFrameLimit(),
      this->GetErrorEstimate(), this->LastFrameTime, this->GetRefinementComplete() };
    this->InvokeEvent(RefinementFrameEvent, &info);
    // VTK's own progress (a named event whose double Python can read): frames over the limit,
    // 1 once complete, ErrorTolerance met included.
    this->UpdateProgress(info.Complete ? 1.0
                                       : (info.FramesAccumulated + this->GetFrameInProgress()) /
                                           std::max(info.FrameLimit, 1));
  }
}

bool vtkSAVRVolumeMapper::GetPreIntegrating() const
{
  return this->State->PreIntegrating;
}

void vtkSAVRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "ParticleRadius: " << this->ParticleRadius << "\n";
  os << indent << "ParticleRadiusArrayName: "
     << (this->ParticleRadiusArrayName ? this->ParticleRadiusArrayName : "(none)") << "\n";
  os << indent << "ParticleKernel: " << this->ParticleKernel << "\n";
  os << indent << "ParticleNormalized: " << this->ParticleNormalized << "\n";
  os << indent << "MaximumNumberOfFrames: " << this->MaximumNumberOfFrames << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << "\n";
  os << indent << "Interactive: " << this->Interactive << "\n";
  os << indent << "CompleteEachRender: " << this->CompleteEachRender << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "MaximumRenderTime: " << this->MaximumRenderTime << "\n";
  os << indent << "MeshOpacityAsAttenuation: " << this->MeshOpacityAsAttenuation << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "IntensityAsGrey: " << this->IntensityAsGrey << "\n";
  os << indent << "PreIntegration: " << this->PreIntegration << "\n";
  os << indent << "AutoPreIntegration: " << this->AutoPreIntegration << "\n";
  os << indent << "ErrorEstimate: " << this->GetErrorEstimate() << "\n";
  os << indent << "FramesAccumulated: " << this->GetNumberOfFramesAccumulated() << "\n";
  os << indent << "MemoryInUse: " << this->GetMemoryInUse() << "\n";
  os << indent << "LastFrameTime: " << this->LastFrameTime << "\n";
}

#include "vtkSAVRVolumeMapperInternals.h"

#include "frame/FrameLoop.h"
#include "sampler/ComponentSampler.h"
#include "sampler/CroppingSampler.h"
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
    // As many halvings of the cost as the pass was over its time: the step's first (each about
    // halves it), then the pixels' (each about quarters it), so that a drag over a slow scene
    // is slow for one pass, not six.
    int halvings = static_cast<int>(std::ceil(std::log2(spent / target)));
    while (halvings > 0 && (s.InteractiveStepFactor < 8.0 || s.InteractivePixelStride < 8))
    {
      if (s.InteractiveStepFactor < 8.0)
      {
        s.InteractiveStepFactor *= 2.0;
        halvings -= 1;
      }
      else
      {
        s.InteractivePixelStride *= 2;
        halvings -= 2;
      }
    }
  }
  else if (spent < 0.4 * target)
  {
    if (s.InteractivePixelStride > 1)
    {
      s.InteractivePixelStride /= 2;
    }
    else
    {
      s.InteractiveStepFactor = std::max(0.5 * s.InteractiveStepFactor, 1.0);
    }
  }
}

int vtkSAVRVolumeMapper::GetInteractivePixelStride() const
{
  return this->AutoAdjustSampleDistances ? this->State->InteractivePixelStride : 1;
}

// The first frame after a start-over ran past MaximumRenderTime: the tiles it has not reached
// show single passes with one ray per block of pixels until the frame reaches them. Blocks of
// 16x16 pixels first, then each pass at half the block's side, while the last pass, four
// times over, fits what is left of half the bound (so the time a pass takes, not an estimate,
// decides: a pass costs about four times the one before).
void vtkSAVRVolumeMapper::PreviewFirstFrame(Frame& frame)
{
  Internals& s = *this->State;
  using Clock = std::chrono::steady_clock;
  double left = 0.5 * this->MaximumRenderTime;
  for (int stride = 16; stride >= 2; stride /= 2)
  {
    const auto start = Clock::now();
    s.Loop.PreviewRemainingTiles(s.Tables.GetTransferFunction(), frame.Mode, stride);
    const double took = std::chrono::duration<double>(Clock::now() - start).count();
    left -= took;
    if (4.0 * took > left)
    {
      break;
    }
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
  return static_cast<vtkTypeUInt64>(this->State->Loop.StoredSamples());
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
      // Found again only when what they depend on changed: finding them scans every particle,
      // and VTK asks for the bounds several times a render.
      Internals& s = *this->State;
      if (s.Changes.ParticleBoundsChanged(vtkSAVRMapperSettingsOf(this), particles))
      {
        vtkSAVRParticleSampler::SupportBounds(particles, this->ParticleRadius,
          this->ParticleRadiusArrayName, this->ParticleKernel, s.ParticleBounds);
      }
      std::copy(s.ParticleBounds, s.ParticleBounds + 6, this->Bounds);
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
  frame.Mapper = vtkSAVRMapperSettingsOf(this);
  // No exception may leave Render (VTK's render loop does not expect one, and an uncaught
  // std::bad_alloc ends the process): whatever throws ends this input like bad input does.
  try
  {
    this->State->Changes.BeginFrame();
    if (!this->UpdateSampler(frame) || !this->ResolveSettings(frame) || !this->UpdateView(frame))
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

// One frame of the current phase; returns whether the image changed.
bool vtkSAVRVolumeMapper::SampleOrBlend(Frame& frame)
{
  Internals& s = *this->State;
  const savr::TransferFunctionTable& table = s.Tables.GetTransferFunction();
  // Tiles whose own estimate is below the tolerance stop taking samples.
  s.Loop.SetTileTolerance(this->ErrorTolerance);
  switch (s.Changes.NextAction(
    this->Interactive, s.Complete(this->ErrorTolerance), s.Loop.CurrentPhase()))
  {
    case vtkSAVRFrameChanges::Action::SinglePass:
    {
      // Nothing of this frame is kept: a fast pass (skips what the transfer function hides, stops
      // rays at an 8-bit level) with the pixels per ray of AutoAdjustSampleDistances.
      s.Loop.RenderSinglePass(table, frame.Mode, this->GetInteractiveSampleDistance(), 0.0,
        savr::PassOptions::Fast(this->GetInteractivePixelStride()));
      this->AdaptInteractiveStep(frame);
      return true;
    }
    case vtkSAVRFrameChanges::Action::Accumulate:
    {
      // What is left of the render's bound (at least one tile is always done).
      double seconds = 0.0;
      if (this->MaximumRenderTime > 0.0 && !this->CompleteEachRender)
      {
        const double spent = frame.Seconds();
        seconds = std::max(this->MaximumRenderTime - spent, 1e-9);
      }
      const bool starts = s.Loop.FrameProgress() == 0.0;
      if (!s.Loop.AccumulateFrame(table, frame.Mode, seconds) && starts)
      {
        this->PreviewFirstFrame(frame);
      }
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

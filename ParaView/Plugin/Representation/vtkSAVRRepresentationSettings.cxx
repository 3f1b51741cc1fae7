#include "vtkSAVRRepresentationSettings.h"

#include "vtkAlgorithm.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPVDataRepresentation.h"
#include "vtkPVRenderView.h"
#include "vtkPVView.h"
#include "vtkRenderer.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkScalarsToColors.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

vtkStandardNewMacro(vtkSAVRRepresentationSettings);

vtkSAVRRepresentationSettings::vtkSAVRRepresentationSettings() = default;

vtkSAVRRepresentationSettings::~vtkSAVRRepresentationSettings()
{
  this->ForgetView();
  this->SetMapper(nullptr);
}

void vtkSAVRRepresentationSettings::SetVectorMode(
  vtkSAVRVolumeMapper* mapper, vtkVolumeProperty* property, vtkScalarsToColors* color)
{
  if (!mapper)
  {
    return;
  }
  int mode = vtkSAVRVolumeMapper::DISABLED;
  if (property && property->GetIndependentComponents() && color)
  {
    if (color->GetVectorMode() == vtkScalarsToColors::MAGNITUDE)
    {
      mode = vtkSAVRVolumeMapper::MAGNITUDE;
    }
    else if (color->GetVectorMode() == vtkScalarsToColors::COMPONENT)
    {
      mode = vtkSAVRVolumeMapper::COMPONENT;
    }
  }
  mapper->SetVectorMode(mode);
  mapper->SetVectorComponent(color ? std::max(color->GetVectorComponent(), 0) : 0);
}

void vtkSAVRRepresentationSettings::DeclareVolumeInPlace(vtkInformation* inInfo,
  vtkInformation* outInfo, vtkPVDataRepresentation* representation, const double* region,
  const double dataBounds[6], vtkMatrix4x4* matrix)
{
  vtkPVRenderView::SetGeometryBounds(inInfo, representation, region ? region : dataBounds, matrix);
  vtkPVRenderView::SetDeliverToClientAndRenderingProcesses(inInfo, representation, false, false);
  vtkPVRenderView::SetRequiresDistributedRendering(inInfo, representation, true);
  if (region)
  {
    outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 1);
    vtkPVRenderView::SetOrderedCompositingConfiguration(inInfo, representation,
      vtkPVRenderView::USE_BOUNDS_FOR_REDISTRIBUTION, const_cast<double*>(region));
  }
}

void vtkSAVRRepresentationSettings::Install(vtkSmartPointer<vtkSAVRRepresentationSettings>& holder,
  vtkSAVRRepresentationSettings* settings, vtkSAVRVolumeMapper* mapper, vtkAlgorithm* owner)
{
  vtkSmartPointer<vtkSAVRRepresentationSettings> installed = settings;
  if (!installed)
  {
    installed = vtkSmartPointer<vtkSAVRRepresentationSettings>::New();
  }
  if (holder && holder != installed)
  {
    holder->ForgetView();
  }
  installed->SetMapper(mapper);
  installed->Owner = owner;
  holder = installed;
}

void vtkSAVRRepresentationSettings::SetMapper(vtkSAVRVolumeMapper* mapper)
{
  if (this->Mapper != mapper)
  {
    if (this->Mapper)
    {
      this->Mapper->RemoveObserver(this->MapperObserver);
      this->MapperObserver = 0;
    }
    this->Mapper = mapper;
    if (mapper)
    {
      this->MapperObserver = mapper->AddObserver(
        vtkCommand::ProgressEvent, this, &vtkSAVRRepresentationSettings::OnMapperProgress);
    }
    this->RendersBeforeViewRender = mapper ? mapper->GetNumberOfRenders() : 0;
    // What was set before (ParaView pushes the properties' defaults before it hands the
    // settings to their representation) reaches this mapper too.
    if (mapper)
    {
      for (const auto& kept : this->Kept)
      {
        kept.second(mapper);
      }
    }
    this->Modified();
  }
}

void vtkSAVRRepresentationSettings::OnMapperProgress()
{
  // The frame's progress is not passed on as the representation's: the mapper reports it from
  // inside the view's render, and the GUI answers progress by processing its events, which can
  // make another OpenGL context current in the middle of the render (every cached GL state then
  // reads wrong, and depth peeling's framebuffers are lost). The information properties carry
  // the state instead; vtkSMSAVRRefinementScheduler reads them between renders.
  this->InvokeEvent(StateChangedEvent);
}

void vtkSAVRRepresentationSettings::SetSampleDistance(double distance)
{
  this->Keep("SampleDistance", &vtkSAVRVolumeMapper::SetSampleDistance, distance);
}

void vtkSAVRRepresentationSettings::SetMaximumNumberOfFrames(int frames)
{
  this->Keep("MaximumNumberOfFrames", &vtkSAVRVolumeMapper::SetMaximumNumberOfFrames, frames);
}

void vtkSAVRRepresentationSettings::SetErrorTolerance(double tolerance)
{
  this->Keep("ErrorTolerance", &vtkSAVRVolumeMapper::SetErrorTolerance, tolerance);
}

void vtkSAVRRepresentationSettings::SetMaximumRenderTime(double seconds)
{
  this->Keep("MaximumRenderTime", &vtkSAVRVolumeMapper::SetMaximumRenderTime, seconds);
}

void vtkSAVRRepresentationSettings::SetMeshOpacityAsAttenuation(bool attenuation)
{
  this->Keep(
    "MeshOpacityAsAttenuation", &vtkSAVRVolumeMapper::SetMeshOpacityAsAttenuation, attenuation);
}

void vtkSAVRRepresentationSettings::SetPreIntegration(bool preIntegrate)
{
  this->Keep("PreIntegration", &vtkSAVRVolumeMapper::SetPreIntegration, preIntegrate);
}

void vtkSAVRRepresentationSettings::SetNumberOfThreads(int threads)
{
  this->Keep("NumberOfThreads", &vtkSAVRVolumeMapper::SetNumberOfThreads, threads);
}

void vtkSAVRRepresentationSettings::SetParticleRadius(double radius)
{
  if (this->Mapper && radius != this->Mapper->GetParticleRadius())
  {
    this->Mapper->SetParticleRadius(radius);
    this->OwnerChanged();
  }
}

void vtkSAVRRepresentationSettings::SetParticleRadiusArray(const char* name)
{
  // The panel's array list offers "None" for no array.
  const std::string radii = (!name || std::strcmp(name, "None") == 0) ? "" : name;
  const char* current = this->Mapper ? this->Mapper->GetParticleRadiusArrayName() : nullptr;
  if (this->Mapper && radii != (current ? current : ""))
  {
    this->Mapper->SetParticleRadiusArrayName(radii.c_str());
    this->OwnerChanged();
  }
}

void vtkSAVRRepresentationSettings::SetParticleKernel(int kernel)
{
  if (this->Mapper && kernel != this->Mapper->GetParticleKernel())
  {
    this->Mapper->SetParticleKernel(kernel);
    this->OwnerChanged();
  }
}

void vtkSAVRRepresentationSettings::SetParticleNormalized(bool normalized)
{
  this->ParticleNormalized = normalized;
  this->Keep("ParticleNormalized", &vtkSAVRVolumeMapper::SetParticleNormalized, normalized);
}

void vtkSAVRRepresentationSettings::OwnerChanged()
{
  if (auto* representation = vtkPVDataRepresentation::SafeDownCast(this->Owner))
  {
    representation->MarkModified();
  }
}

void vtkSAVRRepresentationSettings::SetMemoryBudget(double mebibytes)
{
  const double bytes = mebibytes * 1048576.0; // exact: a power of two
  // 2^64 itself does not fit: everything from there on is the largest budget.
  const double limit = 18446744073709551616.0;
  vtkTypeUInt64 budget = 0;
  if (bytes >= limit)
  {
    budget = ~vtkTypeUInt64(0);
  }
  else if (bytes > 0) // false for NaN
  {
    budget = static_cast<vtkTypeUInt64>(std::floor(bytes + 0.5));
  }
  this->Keep("MemoryBudget", &vtkSAVRVolumeMapper::SetMemoryBudget, budget);
}

int vtkSAVRRepresentationSettings::GetNumberOfFramesAccumulated()
{
  return this->Mapper ? this->Mapper->GetNumberOfFramesAccumulated() : 0;
}

int vtkSAVRRepresentationSettings::GetFrameLimit()
{
  return this->Mapper ? this->Mapper->GetFrameLimit() : 0;
}

int vtkSAVRRepresentationSettings::GetRefinementComplete()
{
  return this->Mapper && this->Mapper->GetRefinementComplete() ? 1 : 0;
}

double vtkSAVRRepresentationSettings::GetErrorEstimate()
{
  return this->Mapper ? this->Mapper->GetErrorEstimate() : 0.0;
}

double vtkSAVRRepresentationSettings::GetLastFrameTime()
{
  return this->Mapper ? this->Mapper->GetLastFrameTime() : 0.0;
}

double vtkSAVRRepresentationSettings::GetMemoryInUse()
{
  return this->Mapper ? static_cast<double>(this->Mapper->GetMemoryInUse()) : 0.0;
}

double vtkSAVRRepresentationSettings::GetEffectiveSampleDistance()
{
  return this->Mapper ? this->Mapper->GetEffectiveSampleDistance() : 0.0;
}

void vtkSAVRRepresentationSettings::SetInteractive(int interactive)
{
  if (this->Mapper)
  {
    this->Mapper->SetInteractive(interactive != 0);
  }
}

int vtkSAVRRepresentationSettings::GetRefinementPending()
{
  // The mapper drew in the view's latest render: its count moved since that render began.
  const bool drew =
    this->Mapper && this->Mapper->GetNumberOfRenders() > this->RendersBeforeViewRender;
  return drew && !this->Mapper->GetRefinementComplete() ? 1 : 0;
}

void vtkSAVRRepresentationSettings::OnViewRenderStart()
{
  this->RendersBeforeViewRender = this->Mapper ? this->Mapper->GetNumberOfRenders() : 0;
}

void vtkSAVRRepresentationSettings::ForgetView()
{
  if (this->WatchedRenderer)
  {
    this->WatchedRenderer->RemoveObserver(this->RendererObserver);
  }
  this->WatchedRenderer = nullptr;
  this->RendererObserver = 0;
}

namespace
{
// vtkPVView::GetInCaptureScreenshot() is protected in ParaView 5.11 (set between
// PrepareForScreenshot and CleanupAfterScreenshot, which SaveScreenshot and SaveAnimation call on
// every process); a derived class may name it, and the pointer it names calls it on any view.
struct CaptureState : vtkPVView
{
  static bool InCapture(vtkPVView* view)
  {
    bool (vtkPVView::*get)() = &CaptureState::GetInCaptureScreenshot;
    return (view->*get)();
  }
};
} // namespace

void vtkSAVRRepresentationSettings::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkView* view)
{
  if (request == vtkPVView::REQUEST_RENDER())
  {
    // Every render of the view's renderer is watched from then on, the ones the representation
    // takes no part in (hidden, inactive) included: those leave nothing pending.
    auto* renderView = vtkPVRenderView::SafeDownCast(view);
    vtkObject* renderer = renderView ? renderView->GetRenderer() : nullptr;
    if (renderer != this->WatchedRenderer)
    {
      this->ForgetView();
      if (renderer)
      {
        this->WatchedRenderer = renderer;
        this->RendererObserver = renderer->AddObserver(
          vtkCommand::StartEvent, this, &vtkSAVRRepresentationSettings::OnViewRenderStart);
      }
      this->OnViewRenderStart();
    }
    // A saved image (SaveScreenshot, each frame of SaveAnimation, at any resolution) is the
    // refined one: ParaView captures it with one render after resizing the view.
    auto* pvView = vtkPVView::SafeDownCast(view);
    if (this->Mapper)
    {
      this->Mapper->SetCompleteEachRender(
        this->RefineSavedImages && pvView && CaptureState::InCapture(pvView));
    }
  }
}

void vtkSAVRRepresentationSettings::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Mapper:";
  if (this->Mapper)
  {
    os << "\n";
    this->Mapper->PrintSelf(os, indent.GetNextIndent());
  }
  else
  {
    os << " (none)\n";
  }
  os << indent << "WatchingView: " << (this->WatchedRenderer ? "yes" : "no") << "\n";
}

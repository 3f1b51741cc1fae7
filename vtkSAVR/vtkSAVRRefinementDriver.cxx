#include "vtkSAVRRefinementDriver.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkInteractorObserver.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSAVRVolumeMapper.h"

#include <algorithm>

vtkStandardNewMacro(vtkSAVRRefinementDriver);

vtkSAVRRefinementDriver::vtkSAVRRefinementDriver() = default;

vtkSAVRRefinementDriver::~vtkSAVRRefinementDriver()
{
  this->Detach();
  this->SetMapper(nullptr);
}

void vtkSAVRRefinementDriver::SetMapper(vtkSAVRVolumeMapper* mapper)
{
  if (this->Mapper)
  {
    this->Mapper->RemoveObserver(this->MapperObserver);
  }
  this->Mapper = mapper;
  this->MapperObserver = mapper ? mapper->AddObserver(vtkSAVRVolumeMapper::RefinementFrameEvent,
                                    this, &vtkSAVRRefinementDriver::OnRefinementFrame)
                                : 0;
  this->StartTimer(); // the new mapper may have refinement to do
  this->Modified();
}

vtkSAVRVolumeMapper* vtkSAVRRefinementDriver::GetMapper() const
{
  return this->Mapper;
}

void vtkSAVRRefinementDriver::Detach()
{
  this->StopTimer();
  if (this->Interactor)
  {
    this->Interactor->RemoveObserver(this->InteractorObserver);
  }
  if (this->Style)
  {
    for (unsigned long tag : this->StyleObservers)
    {
      this->Style->RemoveObserver(tag);
    }
  }
  this->Interactor = nullptr;
  this->Style = nullptr;
  this->HostTicks = false;
}

// One shot at a time, armed again after each refinement render: a repeating timer could not be
// stopped from its own tick (the X interactor walks its timers while it fires them, and
// destroying the one it is at breaks that walk).
void vtkSAVRRefinementDriver::StartTimer()
{
  if (this->Interactor && !this->TimerId && !this->HostTicks)
  {
    this->TimerId = this->Interactor->CreateOneShotTimer(this->TimerInterval);
    // A generic interactor whose host makes no timers (pvbatch's) gives none: its host's
    // TimerEvents, which name no timer, are then the ticks.
    this->HostTicks = this->TimerId == 0;
  }
}

void vtkSAVRRefinementDriver::StopTimer()
{
  if (this->Interactor && this->TimerId)
  {
    this->Interactor->DestroyTimer(this->TimerId);
  }
  this->TimerId = 0;
}

void vtkSAVRRefinementDriver::SetInteractor(vtkRenderWindowInteractor* interactor)
{
  this->Detach();
  if (!interactor)
  {
    return;
  }
  this->Interactor = interactor;
  this->Style = interactor->GetInteractorStyle();

  auto observe =
    [this](vtkObject* subject, unsigned long event, void (vtkSAVRRefinementDriver::*method)())
  { return subject->AddObserver(event, this, method); };
  this->InteractorObserver =
    interactor->AddObserver(vtkCommand::TimerEvent, this, &vtkSAVRRefinementDriver::OnTimer);
  if (this->Style)
  {
    this->StyleObservers[0] = observe(
      this->Style, vtkCommand::StartInteractionEvent, &vtkSAVRRefinementDriver::OnStartInteraction);
    this->StyleObservers[1] = observe(
      this->Style, vtkCommand::EndInteractionEvent, &vtkSAVRRefinementDriver::OnEndInteraction);
  }
  // Timers exist only once the interactor is initialized.
  if (!interactor->GetInitialized())
  {
    interactor->Initialize();
  }
  this->StartTimer();
  this->Modified();
}

vtkRenderWindowInteractor* vtkSAVRRefinementDriver::GetInteractor() const
{
  return this->Interactor;
}

void vtkSAVRRefinementDriver::OnStartInteraction()
{
  if (this->Mapper)
  {
    this->Mapper->SetInteractive(true);
  }
}

void vtkSAVRRefinementDriver::OnEndInteraction()
{
  if (this->Mapper)
  {
    this->Mapper->SetInteractive(false);
  }
  this->StartTimer();
  if (this->Mapper && !this->Mapper->GetRefinementComplete())
  {
    this->RenderWindow();
  }
}

void vtkSAVRRefinementDriver::RenderWindow()
{
  vtkRenderWindow* window = this->Interactor ? this->Interactor->GetRenderWindow() : nullptr;
  if (!window || this->Rendering)
  {
    return;
  }
  this->Rendering = true;
  this->InvokeEvent(vtkCommand::StartEvent);
  window->Render();
  this->InvokeEvent(vtkCommand::EndEvent);
  this->Rendering = false;
  // Armed again here, not only on the frame's event: a tick consumed while rendering
  // (processed by an observer of the events above) must not leave refinement without a timer.
  if (this->Mapper && !this->Mapper->GetRefinementComplete())
  {
    this->StartTimer();
  }
}

void vtkSAVRRefinementDriver::SetTimerInterval(int interval)
{
  interval = std::min(std::max(interval, 1), 10000);
  if (interval == this->TimerInterval)
  {
    return;
  }
  this->TimerInterval = interval;
  // A running timer keeps the interval it was created with: replace it.
  if (this->TimerId)
  {
    this->StopTimer();
    this->StartTimer();
  }
  this->Modified();
}

void vtkSAVRRefinementDriver::OnTimer(vtkObject*, unsigned long, void* timerId)
{
  // The interactor's TimerEvent is every timer's: other drivers' (N drivers would render N
  // times a tick each) and the application's. Only where the interactor could make no timer is
  // each of its TimerEvents a tick.
  if (!this->HostTicks)
  {
    if (!this->TimerId || !timerId || *static_cast<int*>(timerId) != this->TimerId)
    {
      return;
    }
    this->TimerId = 0; // it has fired
  }
  if (!this->Mapper || !this->Interactor || this->Mapper->GetInteractive() || this->Rendering)
  {
    return; // EndInteractionEvent starts it again; so does the end of a render under way
  }
  if (!this->Mapper->GetRefinementComplete() && this->Interactor->GetRenderWindow())
  {
    ++this->NumberOfRefinementRenders;
    this->RenderWindow();
  }
}

void vtkSAVRRefinementDriver::OnRefinementFrame(vtkObject*, unsigned long, void* frameInfo)
{
  // Whoever rendered (this timer, the interactor style, the application): an idle window needs
  // no timer, and a render that started refinement over needs it again.
  if (static_cast<vtkSAVRVolumeMapper::FrameInfo*>(frameInfo)->Complete)
  {
    this->StopTimer();
  }
  else
  {
    this->StartTimer();
  }
}

void vtkSAVRRefinementDriver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TimerInterval: " << this->TimerInterval << "\n";
  os << indent << "NumberOfRefinementRenders: " << this->NumberOfRefinementRenders << "\n";
}

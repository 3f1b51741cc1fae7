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
}

void vtkSAVRRefinementDriver::SetMapper(vtkSAVRVolumeMapper* mapper)
{
  this->Mapper = mapper;
  this->Modified();
}

vtkSAVRVolumeMapper* vtkSAVRRefinementDriver::GetMapper() const
{
  return this->Mapper;
}

void vtkSAVRRefinementDriver::Detach()
{
  if (this->Interactor)
  {
    if (this->TimerId)
    {
      this->Interactor->DestroyTimer(this->TimerId);
    }
    this->Interactor->RemoveObserver(this->InteractorObserver);
  }
  if (this->Style)
  {
    for (unsigned long tag : this->StyleObservers)
    {
      this->Style->RemoveObserver(tag);
    }
  }
  this->TimerId = 0;
  this->Interactor = nullptr;
  this->Style = nullptr;
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
  this->TimerId = interactor->CreateRepeatingTimer(this->TimerInterval);
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
  if (this->Interactor && !this->TimerId)
  {
    this->TimerId = this->Interactor->CreateRepeatingTimer(this->TimerInterval);
  }
  if (this->Interactor && this->Interactor->GetRenderWindow() && this->Mapper &&
      !this->Mapper->GetRefinementComplete())
  {
    this->Interactor->GetRenderWindow()->Render();
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
  if (this->Interactor && this->TimerId)
  {
    this->Interactor->DestroyTimer(this->TimerId);
    this->TimerId = this->Interactor->CreateRepeatingTimer(this->TimerInterval);
  }
  this->Modified();
}

void vtkSAVRRefinementDriver::OnTimer(vtkObject*, unsigned long, void* timerId)
{
  // The interactor's TimerEvent is every timer's: other drivers' (N drivers would render N
  // times a tick each) and the application's. An interactor that could not make the driver's
  // timer (a generic interactor whose host makes no timers, as in pvbatch) has its host deliver
  // TimerEvents that name no timer of ours: then each one is a tick.
  if (this->TimerId && (!timerId || *static_cast<int*>(timerId) != this->TimerId))
  {
    return;
  }
  if (!this->Mapper || !this->Interactor || this->Mapper->GetInteractive())
  {
    return;
  }
  if (!this->Mapper->GetRefinementComplete() && this->Interactor->GetRenderWindow())
  {
    ++this->NumberOfRefinementRenders;
    this->Interactor->GetRenderWindow()->Render();
  }
}

void vtkSAVRRefinementDriver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TimerInterval: " << this->TimerInterval << "\n";
  os << indent << "NumberOfRefinementRenders: " << this->NumberOfRefinementRenders << "\n";
}

#include "vtkSMSAVRSettingsProxy.h"

#include "vtkCommand.h"
#include "vtkObjectFactory.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSMSession.h"

vtkStandardNewMacro(vtkSMSAVRSettingsProxy);

vtkSMSAVRSettingsProxy::vtkSMSAVRSettingsProxy() = default;

vtkSMSAVRSettingsProxy::~vtkSMSAVRSettingsProxy()
{
  if (this->Observed)
  {
    this->Observed->RemoveObserver(this->Observer);
  }
  if (this->Driver)
  {
    for (unsigned long tag : this->DriverObservers)
    {
      this->Driver->RemoveObserver(tag);
    }
  }
  this->EndProgress();
}

void vtkSMSAVRSettingsProxy::CreateVTKObjects()
{
  if (this->ObjectsCreated)
  {
    return;
  }
  this->Superclass::CreateVTKObjects();
  // The object in this process, when there is one: in a client connected to a server it is the
  // client's copy, which never renders and so never reports a frame.
  auto* settings = vtkSAVRRepresentationSettings::SafeDownCast(this->GetClientSideObject());
  if (settings && !this->Observed)
  {
    this->Observed = settings;
    this->Observer = settings->AddObserver(vtkSAVRRepresentationSettings::StateChangedEvent, this,
      &vtkSMSAVRSettingsProxy::OnStateChanged);
  }
  // The driver's renders pass progress on only where they render the data: in a client of a
  // server the client's driver has nothing to refine, and a scope there would cost a round trip
  // to the server.
  vtkSMSession* session = this->GetSession();
  if (settings && !this->Driver && session &&
      (session->GetProcessRoles() & vtkPVSession::RENDER_SERVER))
  {
    this->Driver = settings->GetRefinementDriver();
    this->DriverObservers[0] = this->Driver->AddObserver(
      vtkCommand::StartEvent, this, &vtkSMSAVRSettingsProxy::BeginProgress);
    this->DriverObservers[1] =
      this->Driver->AddObserver(vtkCommand::EndEvent, this, &vtkSMSAVRSettingsProxy::EndProgress);
  }
}

void vtkSMSAVRSettingsProxy::OnStateChanged()
{
  this->UpdatePropertyInformation();
}

void vtkSMSAVRSettingsProxy::BeginProgress()
{
  // Within a scope ParaView has opened (a render it started), or while it closes one, progress
  // is already passed on or must not be reopened.
  vtkSMSession* session = this->GetSession();
  if (!this->InProgress && session && !session->GetPendingProgress())
  {
    session->PrepareProgress();
    this->InProgress = true;
  }
}

void vtkSMSAVRSettingsProxy::EndProgress()
{
  vtkSMSession* session = this->GetSession();
  if (this->InProgress && session)
  {
    session->CleanupPendingProgress();
  }
  this->InProgress = false;
}

void vtkSMSAVRSettingsProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Observing: " << (this->Observed ? "yes" : "no") << "\n";
  os << indent << "ReportingDriverProgress: " << (this->Driver ? "yes" : "no") << "\n";
}

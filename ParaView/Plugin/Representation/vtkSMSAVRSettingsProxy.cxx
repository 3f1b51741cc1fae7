#include "vtkSMSAVRSettingsProxy.h"

#include "vtkObjectFactory.h"
#include "vtkSAVRRepresentationSettings.h"

vtkStandardNewMacro(vtkSMSAVRSettingsProxy);

vtkSMSAVRSettingsProxy::vtkSMSAVRSettingsProxy() = default;

vtkSMSAVRSettingsProxy::~vtkSMSAVRSettingsProxy()
{
  if (this->Observed)
  {
    this->Observed->RemoveObserver(this->Observer);
  }
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
}

void vtkSMSAVRSettingsProxy::OnStateChanged()
{
  this->UpdatePropertyInformation();
}

void vtkSMSAVRSettingsProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Observing: " << (this->Observed ? "yes" : "no") << "\n";
}

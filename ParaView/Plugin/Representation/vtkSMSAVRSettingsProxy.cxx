#include "vtkSMSAVRSettingsProxy.h"

#include "vtkCommand.h"
#include "vtkObjectFactory.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSMEnumerationDomain.h"
#include "vtkSMProperty.h"
#include "vtkSMSAVRRefinementScheduler.h"

#include <cstring>

vtkStandardNewMacro(vtkSMSAVRSettingsProxy);

namespace
{
/// ParaView's image volume representation offers only the blend modes of its own volume types
/// (Composite, Isosurface, Slice); the mapper draws every vtkVolumeMapper blend mode. The
/// shared BlendMode property of the representation holding the settings offers them all.
void OfferEveryBlendMode(vtkSMProxy* representation)
{
  // Image data only: there the stock volume mapper draws every mode too.
  if (!representation || !representation->GetXMLName() ||
      std::strcmp(representation->GetXMLName(), "UniformGridRepresentation") != 0)
  {
    return;
  }
  vtkSMProperty* blendMode = representation->GetProperty("BlendMode");
  auto* modes = blendMode ? blendMode->FindDomain<vtkSMEnumerationDomain>() : nullptr;
  if (!modes)
  {
    return;
  }
  const struct
  {
    const char* Text;
    int Value;
  } every[] = { { "Maximum Intensity", 1 }, { "Minimum Intensity", 2 }, { "Average Intensity", 3 },
    { "Additive", 4 } };
  for (const auto& mode : every)
  {
    if (!modes->GetEntryTextForValue(mode.Value))
    {
      modes->AddEntry(mode.Text, mode.Value);
    }
  }
}
} // namespace

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
  OfferEveryBlendMode(this->GetTrueParentProxy());
  // Shading is a setting of the first screen for "SAVR Volume", as it is for ParaView's own
  // "Volume" (which marks it so for that type alone: the property names one type).
  vtkSMProxy* representation = this->GetTrueParentProxy();
  if (vtkSMProperty* shade = representation ? representation->GetProperty("Shade") : nullptr)
  {
    shade->SetPanelVisibility("default");
  }
  this->Scheduler = vtkSMSAVRRefinementScheduler::Watch(this->GetSession());
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

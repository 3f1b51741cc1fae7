#include "vtkSMSAVRRefinementScheduler.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxyIterator.h"
#include "vtkSMRenderViewProxy.h"
#include "vtkSMSAVRSettingsProxy.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSMSAVRRefinementScheduler);

namespace
{
// The live scheduler of each session (owned by the session's SAVR settings proxies; each
// scheduler removes itself when it goes).
std::map<vtkSMSession*, vtkSMSAVRRefinementScheduler*>& Schedulers()
{
  static std::map<vtkSMSession*, vtkSMSAVRRefinementScheduler*> schedulers;
  return schedulers;
}

// vtkSMProxy::GetSubProxy() is protected in ParaView 5.11; a derived class may name it, and the
// pointer it names calls it on any proxy.
struct SubProxies : vtkSMProxy
{
  static vtkSMProxy* Get(vtkSMProxy* proxy, const char* name)
  {
    vtkSMProxy* (vtkSMProxy::*get)(const char*) = &SubProxies::GetSubProxy;
    return proxy ? (proxy->*get)(name) : nullptr;
  }
};

/// The SAVR settings proxy of `representation`: its own (a SAVR representation proxy) or that of
/// its "SAVRVolumeRepresentation" sub-proxy (the name under which the plugin's XML adds the SAVR
/// type to ParaView's composite representations).
void CollectSettings(vtkSMProxy* representation, std::vector<vtkSMProxy*>& settings)
{
  vtkSMProxy* savr = SubProxies::Get(representation, "SAVRVolumeRepresentation");
  vtkSMProxy* found = SubProxies::Get(savr ? savr : representation, "SAVRSettings");
  if (found && found->IsA("vtkSMSAVRSettingsProxy"))
  {
    settings.push_back(found);
  }
}

/// The representations shown in `view` (its Representations property).
std::vector<vtkSMProxy*> RepresentationsOf(vtkSMProxy* view)
{
  std::vector<vtkSMProxy*> representations;
  if (view && view->GetProperty("Representations"))
  {
    vtkSMPropertyHelper helper(view, "Representations");
    for (unsigned int i = 0; i < helper.GetNumberOfElements(); ++i)
    {
      if (vtkSMProxy* representation = helper.GetAsProxy(i))
      {
        representations.push_back(representation);
      }
    }
  }
  return representations;
}

std::vector<vtkSMProxy*> SettingsOf(vtkSMProxy* view)
{
  std::vector<vtkSMProxy*> settings;
  for (vtkSMProxy* representation : RepresentationsOf(view))
  {
    CollectSettings(representation, settings);
  }
  return settings;
}

/// The representation type `representation` shows, "" when it has none.
std::string TypeOf(vtkSMProxy* representation)
{
  if (!representation->GetProperty("Representation"))
  {
    return std::string();
  }
  const char* type = vtkSMPropertyHelper(representation, "Representation").GetAsString();
  return type ? type : "";
}

bool IsSAVRType(const std::string& type)
{
  return type.rfind("SAVR", 0) == 0;
}

/// Colors a representation that shows a solid color by its first point array (else its first
/// array), with the transfer function rescaled to the data: what ParaView does when its own
/// volume types are chosen.
void ChooseArray(vtkSMPVRepresentationProxy* representation)
{
  if (representation->GetUsingScalarColoring())
  {
    return;
  }
  vtkSMProperty* colorArray = representation->GetProperty("ColorArrayName");
  auto* arrays = colorArray ? colorArray->FindDomain<vtkSMArrayListDomain>() : nullptr;
  if (!arrays || arrays->GetNumberOfStrings() == 0)
  {
    return;
  }
  unsigned int chosen = 0;
  for (unsigned int i = 0; i < arrays->GetNumberOfStrings(); ++i)
  {
    if (arrays->GetFieldAssociation(i) == vtkDataObject::POINT)
    {
      chosen = i;
      break;
    }
  }
  if (representation->SetScalarColoring(
        arrays->GetString(chosen), arrays->GetFieldAssociation(chosen)))
  {
    representation->RescaleTransferFunctionToDataRange(true);
  }
}
} // namespace

struct vtkSMSAVRRefinementScheduler::Internals
{
  struct ViewState
  {
    vtkWeakPointer<vtkSMRenderViewProxy> View;
    vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
    unsigned long ViewObservers[2] = { 0, 0 };
    unsigned long InteractorObservers[3] = { 0, 0, 0 };
    bool Armed = false;       // a tick is awaited
    int TimerId = 0;          // the armed one-shot timer, 0 when none is
    bool HostTicks = false;   // the interactor makes no timers: each TimerEvent is a tick
    bool Interacting = false; // between the interactor's Start- and EndInteractionEvent

    void Detach()
    {
      if (this->Interactor)
      {
        if (this->TimerId)
        {
          this->Interactor->DestroyTimer(this->TimerId);
        }
        for (unsigned long tag : this->InteractorObservers)
        {
          this->Interactor->RemoveObserver(tag);
        }
      }
      this->Interactor = nullptr;
      this->Armed = false;
      this->TimerId = 0;
      this->HostTicks = false;
      this->Interacting = false;
    }
  };
  std::vector<ViewState> Views;
  // Each representation seen in a view, observed for its type (the observer's tag).
  std::map<vtkSMProxy*, std::pair<vtkWeakPointer<vtkSMProxy>, unsigned long>> Seen;
  unsigned long RegisterObserver = 0;
  vtkWeakPointer<vtkObject> ProxyManager;

  ViewState* Find(vtkObject* viewOrInteractor)
  {
    for (ViewState& state : this->Views)
    {
      if (state.View == viewOrInteractor || state.Interactor == viewOrInteractor)
      {
        return &state;
      }
    }
    return nullptr;
  }
};

vtkSMSAVRRefinementScheduler::vtkSMSAVRRefinementScheduler()
  : Internal(new Internals)
{
}

vtkSMSAVRRefinementScheduler::~vtkSMSAVRRefinementScheduler()
{
  auto& schedulers = Schedulers();
  for (auto it = schedulers.begin(); it != schedulers.end(); ++it)
  {
    if (it->second == this)
    {
      schedulers.erase(it);
      break;
    }
  }
  for (Internals::ViewState& state : this->Internal->Views)
  {
    state.Detach();
    if (state.View)
    {
      for (unsigned long tag : state.ViewObservers)
      {
        state.View->RemoveObserver(tag);
      }
    }
  }
  for (auto& seen : this->Internal->Seen)
  {
    if (seen.second.first)
    {
      seen.second.first->RemoveObserver(seen.second.second);
    }
  }
  if (this->Internal->ProxyManager)
  {
    this->Internal->ProxyManager->RemoveObserver(this->Internal->RegisterObserver);
  }
}

vtkSmartPointer<vtkSMSAVRRefinementScheduler> vtkSMSAVRRefinementScheduler::Watch(
  vtkSMSession* session)
{
  if (!session)
  {
    return nullptr;
  }
  auto& schedulers = Schedulers();
  auto found = schedulers.find(session);
  vtkSmartPointer<vtkSMSAVRRefinementScheduler> scheduler;
  // (A scheduler of a session gone, whose address a new session reuses, is not this one's.)
  if (found != schedulers.end() && found->second->Session == session)
  {
    scheduler = found->second;
  }
  else
  {
    scheduler = vtkSmartPointer<vtkSMSAVRRefinementScheduler>::New();
    scheduler->SetSession(session);
    schedulers[session] = scheduler;
  }
  scheduler->WatchViews();
  return scheduler;
}

void vtkSMSAVRRefinementScheduler::SetSession(vtkSMSession* session)
{
  this->Session = session;
  vtkSMSessionProxyManager* proxyManager = session->GetSessionProxyManager();
  if (proxyManager)
  {
    this->Internal->ProxyManager = proxyManager;
    this->Internal->RegisterObserver = proxyManager->AddObserver(
      vtkCommand::RegisterEvent, this, &vtkSMSAVRRefinementScheduler::WatchViews);
  }
}

void vtkSMSAVRRefinementScheduler::WatchViews()
{
  if (!this->Session)
  {
    return;
  }
  vtkNew<vtkSMProxyIterator> views;
  views->SetSession(this->Session);
  views->SetModeToOneGroup();
  for (views->Begin("views"); !views->IsAtEnd(); views->Next())
  {
    auto* view = vtkSMRenderViewProxy::SafeDownCast(views->GetProxy());
    if (!view || this->Internal->Find(view))
    {
      continue;
    }
    Internals::ViewState state;
    state.View = view;
    state.ViewObservers[0] =
      view->AddObserver(vtkCommand::StartEvent, this, &vtkSMSAVRRefinementScheduler::OnViewStart);
    state.ViewObservers[1] =
      view->AddObserver(vtkCommand::EndEvent, this, &vtkSMSAVRRefinementScheduler::OnViewEnd);
    this->Internal->Views.push_back(state);
  }
}

void vtkSMSAVRRefinementScheduler::AttachInteractor(void* viewState)
{
  auto& state = *static_cast<Internals::ViewState*>(viewState);
  // The view may get its interactor after it was first seen (pvpython's Interact()).
  vtkRenderWindowInteractor* interactor = state.View ? state.View->GetInteractor() : nullptr;
  if (interactor == state.Interactor)
  {
    return;
  }
  state.Detach();
  if (!interactor)
  {
    return;
  }
  state.Interactor = interactor;
  state.InteractorObservers[0] = interactor->AddObserver(
    vtkCommand::StartInteractionEvent, this, &vtkSMSAVRRefinementScheduler::OnStartInteraction);
  state.InteractorObservers[1] = interactor->AddObserver(
    vtkCommand::EndInteractionEvent, this, &vtkSMSAVRRefinementScheduler::OnEndInteraction);
  state.InteractorObservers[2] =
    interactor->AddObserver(vtkCommand::TimerEvent, this, &vtkSMSAVRRefinementScheduler::OnTimer);
}

void vtkSMSAVRRefinementScheduler::Arm(void* viewState, int interval)
{
  auto& state = *static_cast<Internals::ViewState*>(viewState);
  if (!state.Interactor || state.Armed)
  {
    return;
  }
  state.Armed = true;
  if (!state.HostTicks)
  {
    state.TimerId = state.Interactor->CreateOneShotTimer(interval);
    // An interactor whose host makes no timers (a generic one, as pvpython's Interact() makes)
    // gives none: its host's TimerEvents, which name no timer, are then the ticks.
    state.HostTicks = state.TimerId == 0;
  }
}

void vtkSMSAVRRefinementScheduler::OnViewStart(vtkObject* view, unsigned long, void* interactive)
{
  const int isInteractive = interactive ? *static_cast<int*>(interactive) : 0;
  auto* viewProxy = static_cast<vtkSMProxy*>(view);
  for (vtkSMProxy* representation : RepresentationsOf(viewProxy))
  {
    // From the first render that shows it, a representation switched to a SAVR type gets an
    // array to draw at once (as ParaView's own volume types do, within the switch); one seen
    // for the first time with a SAVR type (a script's) gets it now.
    auto& seen = this->Internal->Seen[representation];
    if (!seen.first)
    {
      seen.first = representation;
      seen.second = representation->AddObserver(
        vtkCommand::PropertyModifiedEvent, this, &vtkSMSAVRRefinementScheduler::OnTypeChanged);
      auto* colored = vtkSMPVRepresentationProxy::SafeDownCast(representation);
      if (colored && IsSAVRType(TypeOf(representation)))
      {
        ChooseArray(colored);
      }
    }
  }
  // Forget representations that are gone.
  for (auto it = this->Internal->Seen.begin(); it != this->Internal->Seen.end();)
  {
    it = it->second.first ? std::next(it) : this->Internal->Seen.erase(it);
  }
  for (vtkSMProxy* settings : SettingsOf(viewProxy))
  {
    vtkSMProperty* property = settings->GetProperty("Interactive");
    if (property && vtkSMPropertyHelper(property).GetAsInt() != isInteractive)
    {
      vtkSMPropertyHelper(property).Set(isInteractive);
      settings->UpdateVTKObjects();
    }
  }
}

void vtkSMSAVRRefinementScheduler::OnTypeChanged(
  vtkObject* representation, unsigned long, void* propertyName)
{
  const char* name = static_cast<const char*>(propertyName);
  auto* colored = vtkSMPVRepresentationProxy::SafeDownCast(representation);
  if (colored && name && std::strcmp(name, "Representation") == 0 && IsSAVRType(TypeOf(colored)))
  {
    ChooseArray(colored);
  }
}

void vtkSMSAVRRefinementScheduler::OnViewEnd(vtkObject* view, unsigned long, void* interactive)
{
  Internals::ViewState* state = this->Internal->Find(view);
  if (!state)
  {
    return;
  }
  this->AttachInteractor(state);
  if (!state->Interactor || state->Interacting || (interactive && *static_cast<int*>(interactive)))
  {
    return;
  }
  bool pending = false;
  for (vtkSMProxy* settings : SettingsOf(state->View))
  {
    settings->UpdatePropertyInformation();
    if (settings->GetProperty("RefinementPending") &&
        vtkSMPropertyHelper(settings, "RefinementPending").GetAsInt() != 0)
    {
      pending = true;
    }
  }
  if (pending)
  {
    this->Arm(state, this->TimerInterval);
  }
}

void vtkSMSAVRRefinementScheduler::OnStartInteraction(vtkObject* interactor, unsigned long, void*)
{
  if (Internals::ViewState* state = this->Internal->Find(interactor))
  {
    state->Interacting = true;
  }
}

void vtkSMSAVRRefinementScheduler::OnEndInteraction(vtkObject* interactor, unsigned long, void*)
{
  if (Internals::ViewState* state = this->Internal->Find(interactor))
  {
    state->Interacting = false;
    // The still render that ends a drag starts accumulation; if ParaView makes one itself,
    // this tick finds nothing pending or adds the next frame.
    this->Arm(state, this->TimerInterval);
  }
}

void vtkSMSAVRRefinementScheduler::OnTimer(vtkObject* interactor, unsigned long, void* timerId)
{
  Internals::ViewState* state = this->Internal->Find(interactor);
  if (!state || !state->Armed)
  {
    return;
  }
  // The interactor's TimerEvent is every timer's: only this view's armed one is a tick (or,
  // where the host makes no timers, any).
  if (!state->HostTicks)
  {
    if (!timerId || *static_cast<int*>(timerId) != state->TimerId)
    {
      return;
    }
    state->TimerId = 0;
  }
  state->Armed = false;
  if (!state->View || state->Interacting)
  {
    return; // EndInteractionEvent arms it again
  }
  vtkSMSession* session = state->View->GetSession();
  if (session && session->GetPendingProgress())
  {
    // ParaView is rendering or updating (this tick came from its event processing): later.
    this->Arm(state, std::max(this->TimerInterval, 10));
    return;
  }
  ++this->NumberOfRefinementRenders;
  // The view's EndEvent arms the next tick while refinement is still pending.
  vtkSmartPointer<vtkSMRenderViewProxy> view = state->View.GetPointer();
  view->StillRender();
}

void vtkSMSAVRRefinementScheduler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TimerInterval: " << this->TimerInterval << "\n";
  os << indent << "NumberOfRefinementRenders: " << this->NumberOfRefinementRenders << "\n";
  os << indent << "Views: " << this->Internal->Views.size() << "\n";
}

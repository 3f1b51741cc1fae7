/**
 * @class   vtkSMSAVRSettingsProxy
 * @brief   The proxy of the SAVR settings: keeps the mapper's state current in the panel.
 *
 * The "SAVRSettings" proxy of the plugin's XML (the SAVRSettingsProxy element) is of this class.
 * Where its vtkSAVRRepresentationSettings lives in this process and renders (the GUI's built-in
 * session, pvpython, pvbatch), it updates its information properties (frames accumulated,
 * frame limit, refinement complete, error estimate, frame time, memory in use) after every frame
 * of the mapper, the refinement driver's included, so the Properties panel shows the state as
 * refinement goes on. Elsewhere (a client connected to a server, whose copy of the settings
 * never renders) it is a plain vtkSMProxy: call UpdatePropertyInformation() to read the state.
 *
 * Where it renders, it also opens the session's progress scope (PrepareProgress, then
 * CleanupPendingProgress) around each render the refinement driver makes itself, unless a scope
 * is open already: ParaView passes the representation's progress on (to the GUI's progress bar)
 * only within such a scope, which it opens only around the renders it starts.
 */
#ifndef vtkSMSAVRSettingsProxy_h
#define vtkSMSAVRSettingsProxy_h

#include "vtkSAVRParaViewModule.h" // For export macro
#include "vtkSMProxy.h"
#include "vtkWeakPointer.h" // For vtkWeakPointer

class vtkObject;

class VTKSAVRPARAVIEW_EXPORT vtkSMSAVRSettingsProxy : public vtkSMProxy
{
public:
  static vtkSMSAVRSettingsProxy* New();
  vtkTypeMacro(vtkSMSAVRSettingsProxy, vtkSMProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSMSAVRSettingsProxy();
  ~vtkSMSAVRSettingsProxy() override;

  void CreateVTKObjects() override;

private:
  vtkSMSAVRSettingsProxy(const vtkSMSAVRSettingsProxy&) = delete;
  void operator=(const vtkSMSAVRSettingsProxy&) = delete;

  void OnStateChanged();
  void BeginProgress();
  void EndProgress();

  vtkWeakPointer<vtkObject> Observed; // the settings observed in this process, if any
  unsigned long Observer = 0;
  vtkWeakPointer<vtkObject> Driver; // the refinement driver in this process, where it renders
  unsigned long DriverObservers[2] = { 0, 0 };
  bool InProgress = false; // a progress scope of ours is open
};

#endif

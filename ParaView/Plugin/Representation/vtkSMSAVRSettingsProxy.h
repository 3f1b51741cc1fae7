/**
 * @class   vtkSMSAVRSettingsProxy
 * @brief   The proxy of the SAVR settings: keeps the mapper's state current in the panel and
 *          has the views that show it refined.
 *
 * The "SAVRSettings" proxy of the plugin's XML (the SAVRSettingsProxy element) is of this class.
 * Where its vtkSAVRRepresentationSettings lives in this process and renders (the GUI's built-in
 * session, pvpython, pvbatch), it updates its information properties (frames accumulated,
 * frame limit, refinement complete, error estimate, frame time, memory in use) after every frame
 * of the mapper, so the Properties panel shows the state as refinement goes on. Elsewhere (a
 * client connected to a server, whose copy of the settings never renders) call
 * UpdatePropertyInformation() to read the state.
 *
 * In every session it also hands its session to vtkSMSAVRRefinementScheduler, which renders the
 * session's views again, through their proxies, while a SAVR representation in them has
 * refinement pending.
 */
#ifndef vtkSMSAVRSettingsProxy_h
#define vtkSMSAVRSettingsProxy_h

#include "vtkSAVRParaViewModule.h" // For export macro
#include "vtkSMProxy.h"
#include "vtkSmartPointer.h" // For vtkSmartPointer
#include "vtkWeakPointer.h"  // For vtkWeakPointer

class vtkObject;
class vtkSMSAVRRefinementScheduler;

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

  vtkWeakPointer<vtkObject> Observed; // the settings observed in this process, if any
  unsigned long Observer = 0;
  vtkSmartPointer<vtkSMSAVRRefinementScheduler> Scheduler; // its session's, shared
};

#endif

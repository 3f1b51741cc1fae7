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

  vtkWeakPointer<vtkObject> Observed; // the settings observed in this process, if any
  unsigned long Observer = 0;
};

#endif

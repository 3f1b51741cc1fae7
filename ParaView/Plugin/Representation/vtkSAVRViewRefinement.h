// Private to the plugin's representations: refinement in a view that has an interactor.
#ifndef vtkSAVRViewRefinement_h
#define vtkSAVRViewRefinement_h

#include "vtkPVRenderView.h"
#include "vtkSAVRRefinementDriver.h"

/**
 * Attaches `driver` to the interactor of `view` (a vtkPVRenderView), or detaches it when the view
 * has none. Where ParaView renders a view in this process with an interactor (the GUI's built-in
 * session, or pvpython/pvbatch after Interact()), the driver re-renders the window on the
 * interactor's repeating timer while refinement is incomplete, and makes the mapper render single
 * passes while the user drags: the image refines on its own once interaction stops. Without an
 * interactor (pvbatch scripts, render servers) every Render() call is one frame, as before.
 */
inline void vtkSAVRAttachRefinementDriver(vtkSAVRRefinementDriver* driver, vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  vtkRenderWindowInteractor* interactor = renderView ? renderView->GetInteractor() : nullptr;
  if (interactor != driver->GetInteractor())
  {
    driver->SetInteractor(interactor);
  }
}

#endif

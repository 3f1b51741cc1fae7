/**
 * @class   vtkSMSAVRRefinementScheduler
 * @brief   Renders a session's views again, through their proxies, while SAVR refinement is
 *          pending in them; tells SAVR representations when ParaView's renders are interactive.
 *
 * SAVR refines one frame per still render. ParaView renders only when something asks, so on
 * the client (the process whose view proxies the application drives: the GUI, pvpython) this
 * object asks: after each still render of a render view it reads the RefinementPending state of
 * the SAVR representations in that view (from the server in client-server mode) and, while one
 * has refinement pending, arms a one-shot timer on the view's interactor whose tick calls the
 * view proxy's StillRender(), as ParaView's own streaming and progressive passes do. So every
 * refinement frame is a render ParaView makes itself: annotations, depth peeling, compositing
 * and the remote image delivery all happen as for any other render, and the application's event
 * loop runs between frames. A tick waits while ParaView has a render or an update under way
 * (pending progress) and while the user drags.
 *
 * It also passes on whether each render is interactive: ParaView's InteractiveRender() (a drag)
 * sets Interactive on the SAVR settings of the view's representations (single passes that store
 * nothing), its StillRender() clears it (accumulation starts again).
 *
 * And, as ParaView does for its own "Volume" type, a representation switched to a SAVR type
 * while it shows a solid color is colored by its first point array (else its first array) with
 * the transfer function rescaled to the data, within the switch (for representations shown in
 * a view that has rendered since they were added; one first seen with a SAVR type is colored
 * at that render).
 *
 * Where the view has no interactor (pvbatch, pvpython before Interact()), nothing is scheduled:
 * every Render() is one frame. An interactor whose host makes no timers (a generic one) has each
 * of its TimerEvents taken as a tick. vtkSMSAVRSettingsProxy calls Watch() for its session and
 * holds what it returns.
 */
#ifndef vtkSMSAVRRefinementScheduler_h
#define vtkSMSAVRRefinementScheduler_h

#include "vtkObject.h"
#include "vtkSAVRParaViewModule.h" // For export macro
#include "vtkSmartPointer.h"       // For vtkSmartPointer
#include "vtkWeakPointer.h"        // For vtkWeakPointer

#include <memory> // For std::unique_ptr

class vtkSMSession;

class VTKSAVRPARAVIEW_EXPORT vtkSMSAVRRefinementScheduler : public vtkObject
{
public:
  static vtkSMSAVRRefinementScheduler* New();
  vtkTypeMacro(vtkSMSAVRRefinementScheduler, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The scheduler of `session`, made on first use and shared by those who hold it (each SAVR
  /// settings proxy of the session): it lives as long as one of them does.
  static vtkSmartPointer<vtkSMSAVRRefinementScheduler> Watch(vtkSMSession* session);

  ///@{
  /// Milliseconds from a still render that left refinement pending to the next (default 5).
  vtkSetClampMacro(TimerInterval, int, 0, 10000);
  vtkGetMacro(TimerInterval, int);
  ///@}

  /// Still renders the scheduler has asked for so far, over all views.
  vtkGetMacro(NumberOfRefinementRenders, int);

protected:
  vtkSMSAVRRefinementScheduler();
  ~vtkSMSAVRRefinementScheduler() override;

private:
  vtkSMSAVRRefinementScheduler(const vtkSMSAVRRefinementScheduler&) = delete;
  void operator=(const vtkSMSAVRRefinementScheduler&) = delete;

  struct Internals;
  std::unique_ptr<Internals> Internal;
  vtkWeakPointer<vtkSMSession> Session;
  int TimerInterval = 5;
  int NumberOfRefinementRenders = 0;

  void SetSession(vtkSMSession* session);
  void WatchViews();
  void AttachInteractor(void* viewState);
  void Arm(void* viewState, int interval);
  void OnViewStart(vtkObject* view, unsigned long event, void* interactive);
  void OnViewEnd(vtkObject* view, unsigned long event, void* interactive);
  void OnTypeChanged(vtkObject* representation, unsigned long event, void* propertyName);
  void OnStartInteraction(vtkObject* interactor, unsigned long event, void* data);
  void OnEndInteraction(vtkObject* interactor, unsigned long event, void* data);
  void OnTimer(vtkObject* interactor, unsigned long event, void* timerId);
};

#endif

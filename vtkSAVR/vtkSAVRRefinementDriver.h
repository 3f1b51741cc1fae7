/**
 * @class   vtkSAVRRefinementDriver
 * @brief   Keeps a vtkSAVRVolumeMapper refining in an interactive window.
 *
 * VTK renders only when something asks it to. Attached to a vtkRenderWindowInteractor, the
 * driver renders again on a repeating timer while the mapper's refinement is incomplete (the
 * timer stops when refinement completes, so that an idle window does not wake, and starts again
 * when a render leaves refinement incomplete, as a camera change does), tells
 * the mapper to render single passes while the user drags (the interactor style's
 * StartInteractionEvent) and to accumulate again when the drag ends (EndInteractionEvent).
 *
 * Each render the driver makes itself is bracketed by its own vtkCommand::StartEvent and
 * EndEvent, so that an application which passes progress on only within a scope it opens (as
 * ParaView does around the renders it starts) can open one for the driver's renders too. A tick
 * that arrives while the driver renders (an observer of those events that processes the
 * application's events) renders nothing.
 *
 * @code
 * vtkNew<vtkSAVRRefinementDriver> driver;
 * driver->SetMapper(mapper);
 * driver->SetInteractor(interactor); // after the interactor style is set
 * interactor->Start();
 * @endcode
 */
#ifndef vtkSAVRRefinementDriver_h
#define vtkSAVRRefinementDriver_h

#include "vtkObject.h"
#include "vtkSAVRModule.h"  // For export macro
#include "vtkWeakPointer.h" // For vtkWeakPointer

class vtkInteractorObserver;
class vtkRenderWindowInteractor;
class vtkSAVRVolumeMapper;

class VTKSAVR_EXPORT vtkSAVRRefinementDriver : public vtkObject
{
public:
  static vtkSAVRRefinementDriver* New();
  vtkTypeMacro(vtkSAVRRefinementDriver, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The mapper whose refinement to drive (not reference counted, observed for its frames).
  void SetMapper(vtkSAVRVolumeMapper* mapper);
  vtkSAVRVolumeMapper* GetMapper() const;

  /**
   * Attaches to the interactor (initializing it if needed) and its current interactor style, and
   * starts the timer. Call again after replacing the interactor style. Null detaches.
   */
  void SetInteractor(vtkRenderWindowInteractor* interactor);
  vtkRenderWindowInteractor* GetInteractor() const;

  ///@{
  /// Milliseconds between refinement renders (default 10, 1 to 10000); takes effect at once.
  void SetTimerInterval(int interval);
  vtkGetMacro(TimerInterval, int);
  ///@}

  /// Renders made by the timer so far.
  vtkGetMacro(NumberOfRefinementRenders, int);

protected:
  vtkSAVRRefinementDriver();
  ~vtkSAVRRefinementDriver() override;

private:
  vtkSAVRRefinementDriver(const vtkSAVRRefinementDriver&) = delete;
  void operator=(const vtkSAVRRefinementDriver&) = delete;

  void Detach();
  void StartTimer();
  void StopTimer();
  void OnRefinementFrame(vtkObject* caller, unsigned long event, void* frameInfo);
  void OnTimer(vtkObject* caller, unsigned long event, void* timerId);
  void OnStartInteraction();
  void OnEndInteraction();
  void RenderWindow();

  vtkWeakPointer<vtkSAVRVolumeMapper> Mapper;
  vtkWeakPointer<vtkRenderWindowInteractor> Interactor;
  vtkWeakPointer<vtkInteractorObserver> Style;
  unsigned long InteractorObserver = 0;
  unsigned long MapperObserver = 0;
  unsigned long StyleObservers[2] = { 0, 0 };
  int TimerId = 0;        // the armed one-shot timer, 0 when none is
  bool HostTicks = false; // the interactor makes no timers: each TimerEvent is a tick
  int TimerInterval = 10;
  int NumberOfRefinementRenders = 0;
  bool Rendering = false; // within RenderWindow()
};

#endif

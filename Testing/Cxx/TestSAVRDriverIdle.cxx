// The refinement driver's timer stops once refinement completes (an idle window does not tick),
// and starts again when a camera change starts refinement over. Each render of the driver's own
// is bracketed by its StartEvent and EndEvent (where ParaView opens a progress scope).

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"
#include "vtkSAVRRefinementDriver.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkRenderWindowInteractor.h"

#include <string>

namespace
{
struct IdleState
{
  vtkRenderWindowInteractor* Interactor = nullptr;
  vtkRenderer* Renderer = nullptr;
  vtkSAVRRefinementDriver* Driver = nullptr;
  int Completions = 0;
  int WaitTimer = 0;     // the test's one-shot timer after each completion
  int WatchdogTimer = 0; // ends the loop should refinement never complete
  bool TimedOut = false;
  int TicksAfterCompletion[2] = { 0, 0 };
  int RendersBeforeMove = 0;
  int RendersAfterMove = 0;
  int DriverStarts = 0;
  int DriverEnds = 0;
  int FramesInDriverRenders = 0;
};

// Completion arms a 300 ms wait (not from inside the render: the camera moves outside it).
void OnFrame(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* state = static_cast<IdleState*>(clientData);
  const auto* info = static_cast<vtkSAVRVolumeMapper::FrameInfo*>(callData);
  if (state->DriverStarts > state->DriverEnds)
  {
    ++state->FramesInDriverRenders;
  }
  if (info->Complete && !state->WaitTimer && state->Completions < 2)
  {
    ++state->Completions;
    state->WaitTimer = state->Interactor->CreateOneShotTimer(300);
  }
}

void OnDriverRender(vtkObject*, unsigned long event, void* clientData, void*)
{
  auto* state = static_cast<IdleState*>(clientData);
  ++(event == vtkCommand::StartEvent ? state->DriverStarts : state->DriverEnds);
}

void OnTimer(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* state = static_cast<IdleState*>(clientData);
  const int id = *static_cast<int*>(callData);
  if (id == state->WatchdogTimer)
  {
    state->TimedOut = true;
    state->Interactor->TerminateApp();
    return;
  }
  if (id != state->WaitTimer)
  {
    // Another timer's tick: the driver's, while a wait after completion runs, counts.
    if (state->WaitTimer)
    {
      ++state->TicksAfterCompletion[state->Completions - 1];
    }
    return;
  }
  state->WaitTimer = 0;
  if (state->Completions == 2)
  {
    state->Interactor->TerminateApp();
    return;
  }
  // As an application would: move the camera and render once; the driver takes it from there.
  state->RendersBeforeMove = state->Driver->GetNumberOfRefinementRenders();
  state->Renderer->GetActiveCamera()->Azimuth(10.0);
  state->Renderer->ResetCameraClippingRange();
  state->Interactor->Render();
}
} // namespace

int TestSAVRDriverIdle(int, char*[])
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(10);
  savr_scenes::Scene scene(data, 120, 120);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(6);

  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(scene.Window);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  scene.Window->Render();

  vtkNew<vtkSAVRRefinementDriver> driver;
  driver->SetMapper(scene.Mapper);
  driver->SetInteractor(interactor);

  IdleState state;
  state.Interactor = interactor;
  state.Renderer = scene.Renderer;
  state.Driver = driver;
  vtkNew<vtkCallbackCommand> onFrame;
  onFrame->SetCallback(OnFrame);
  onFrame->SetClientData(&state);
  scene.Mapper->AddObserver(vtkSAVRVolumeMapper::RefinementFrameEvent, onFrame);
  vtkNew<vtkCallbackCommand> onTimer;
  onTimer->SetCallback(OnTimer);
  onTimer->SetClientData(&state);
  // Before the driver's observer: the tick whose render completes refinement is seen before it.
  interactor->AddObserver(vtkCommand::TimerEvent, onTimer, 1.0f);
  state.WatchdogTimer = interactor->CreateOneShotTimer(60000);
  vtkNew<vtkCallbackCommand> onDriverRender;
  onDriverRender->SetCallback(OnDriverRender);
  onDriverRender->SetClientData(&state);
  driver->AddObserver(vtkCommand::StartEvent, onDriverRender);
  driver->AddObserver(vtkCommand::EndEvent, onDriverRender);

  interactor->Start();
  state.RendersAfterMove = driver->GetNumberOfRefinementRenders() - state.RendersBeforeMove;

  savr_scenes::Expectations expect;
  const std::string counts =
    " (ticks after each completion: " + std::to_string(state.TicksAfterCompletion[0]) + ", " +
    std::to_string(state.TicksAfterCompletion[1]) +
    "; refinement renders after the move: " + std::to_string(state.RendersAfterMove) + ")";
  std::cout << counts << "\n";
  expect(!state.TimedOut, "the loop ended before the watchdog");
  expect(state.Completions == 2, "refinement completed, and again after the camera moved");
  expect(state.TicksAfterCompletion[0] == 0, "no tick in the 300 ms after completion" + counts);
  expect(state.TicksAfterCompletion[1] == 0,
    "no tick in the 300 ms after the second completion" + counts);
  // The move renders frame 1; the driver's timer renders frames 2..6.
  expect(state.RendersAfterMove >= 5, "the timer resumed refinement after the move" + counts);
  expect(scene.Mapper->GetRefinementComplete(), "refinement is complete at the end");
  const int renders = driver->GetNumberOfRefinementRenders();
  expect(state.DriverStarts == renders && state.DriverEnds == renders,
    "a StartEvent and an EndEvent for each of the driver's " + std::to_string(renders) +
      " renders (" + std::to_string(state.DriverStarts) + ", " + std::to_string(state.DriverEnds) +
      ")");
  expect(state.FramesInDriverRenders == renders,
    "each of the driver's renders is one frame between them (" +
      std::to_string(state.FramesInDriverRenders) + ")");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

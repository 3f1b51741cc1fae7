// CompleteEachRender: one Render refines to completion and draws the same image as a Render per
// frame, with an event per frame; after a camera change one Render completes again; while
// Interactive it still renders single passes.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"

#include <string>

int TestSAVRCompleteEachRender(int, char*[])
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(10);
  savr_scenes::Expectations expect;

  savr_scenes::Scene perFrame(data, 160, 160);
  savr_scenes::WaveletProperty(perFrame.Property);
  const int renders = perFrame.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> refined = savr_scenes::Capture(perFrame.Window);
  perFrame.Renderer->GetActiveCamera()->Azimuth(20.0);
  perFrame.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> turned = savr_scenes::Capture(perFrame.Window);

  savr_scenes::Scene atOnce(data, 160, 160);
  savr_scenes::WaveletProperty(atOnce.Property);
  atOnce.Mapper->SetCompleteEachRender(true);
  int events = 0;
  vtkNew<vtkCallbackCommand> count;
  count->SetClientData(&events);
  count->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*) { ++*static_cast<int*>(clientData); });
  atOnce.Mapper->AddObserver(vtkSAVRVolumeMapper::RefinementFrameEvent, count);

  atOnce.Window->Render();
  const std::string seen = " (" + std::to_string(atOnce.Mapper->GetNumberOfFramesAccumulated()) +
                           " frames, " + std::to_string(events) +
                           " events; a render per frame took " + std::to_string(renders) +
                           " renders)";
  expect(renders > 1, "refinement takes several renders one frame at a time" + seen);
  expect(atOnce.Mapper->GetRefinementComplete() &&
           atOnce.Mapper->GetNumberOfFramesAccumulated() == atOnce.Mapper->GetFrameLimit(),
    "one Render refines to completion" + seen);
  expect(events == atOnce.Mapper->GetFrameLimit(), "one event per frame" + seen);
  expect(savr_scenes::Compare(savr_scenes::Capture(atOnce.Window), refined).Max == 0,
    "the image equals the one refined a Render per frame");

  atOnce.Renderer->GetActiveCamera()->Azimuth(20.0);
  atOnce.Window->Render();
  expect(atOnce.Mapper->GetRefinementComplete() &&
           savr_scenes::Compare(savr_scenes::Capture(atOnce.Window), turned).Max == 0,
    "after a camera change one Render completes again, with the same image");

  atOnce.Mapper->SetInteractive(true);
  atOnce.Renderer->GetActiveCamera()->Azimuth(20.0);
  atOnce.Window->Render();
  expect(!atOnce.Mapper->GetRefinementComplete(), "while interactive, a Render is a single pass");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

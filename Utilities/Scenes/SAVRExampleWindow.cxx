#include "SAVRExampleWindow.h"

#include "vtkSAVRRefinementDriver.h"
#include "vtkSAVRVolumeMapper.h"

#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSmartPointer.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

namespace savr_scenes
{

WindowOptions::WindowOptions(Arguments& arguments, const std::string& output)
  : Output(output)
{
  arguments.Flag("--headless", &this->Headless,
    "Render offscreen until refinement completes, print each frame, write --output.");
  arguments.Option(
    "--output", &this->Output, arguments.Keep("The PNG --headless writes (" + output + ")."));
  arguments.Option("--size", &this->Size, "Window height in pixels (512).");
}

int RenderHeadless(vtkRenderWindow* window, const std::vector<vtkSAVRVolumeMapper*>& mappers,
  const std::string& output)
{
  window->SetOffScreenRendering(1);
  vtkSAVRVolumeMapper* first = mappers.front();
  std::printf("frame  accumulated  ms      memory_MiB  error_estimate\n");
  int render = 0;
  do
  {
    window->Render();
    ++render;
    std::printf("%5d  %11d  %7.1f  %10.2f  %14.2e\n", render, first->GetNumberOfFramesAccumulated(),
      1e3 * first->GetLastFrameTime(), first->GetMemoryInUse() / 1048576.0,
      first->GetErrorEstimate());
  } while (!std::all_of(mappers.begin(), mappers.end(),
             [](vtkSAVRVolumeMapper* m) { return m->GetRefinementComplete(); }) &&
           render < 100000);
  std::printf("refinement complete: %d frames at base step %g (effective step %g)\n",
    first->GetNumberOfFramesAccumulated(), first->GetEffectiveSampleDistance(),
    first->GetEffectiveSampleDistance() / first->GetNumberOfFramesAccumulated());
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(output.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  std::printf("wrote %s\n", output.c_str());
  return EXIT_SUCCESS;
}

int Interact(
  vtkRenderWindow* window, const std::vector<vtkSAVRVolumeMapper*>& mappers, vtkCommand* keys)
{
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  if (keys)
  {
    interactor->AddObserver(vtkCommand::KeyPressEvent, keys);
  }
  window->Render();
  std::vector<vtkSmartPointer<vtkSAVRRefinementDriver>> drivers;
  for (vtkSAVRVolumeMapper* mapper : mappers)
  {
    // An interactive window stays responsive while a slow frame (a million particles, say)
    // refines: no render holds the event loop for much longer than this.
    mapper->SetMaximumRenderTime(0.2);
    drivers.push_back(vtkSmartPointer<vtkSAVRRefinementDriver>::New());
    drivers.back()->SetMapper(mapper);
    drivers.back()->SetInteractor(interactor);
  }
  interactor->Start();
  return EXIT_SUCCESS;
}

int Show(vtkRenderWindow* window, const std::vector<vtkSAVRVolumeMapper*>& mappers,
  const WindowOptions& options, vtkCommand* keys)
{
  return options.Headless ? RenderHeadless(window, mappers, options.Output)
                          : Interact(window, mappers, keys);
}

} // namespace savr_scenes

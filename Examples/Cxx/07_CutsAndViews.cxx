// Example 7: cuts and views of the MRI head. Cropping keeps a fence of the middle thirds (VTK's
// cropping regions; key x), a clipping plane through the centre keeps the front half (key k);
// the camera may use a parallel projection or stand inside the volume. A second volume beside
// the first, and a second viewport that sees the data from behind, each get a mapper of their
// own: a mapper keeps the samples of one view.
//
//   savr_views [--crop] [--clip] [--parallel] [--inside] [--volumes 1|2] [--viewports 1|2]
//              [--headless] [--output savr_views.png] [--size 512]

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkPlane.h"
#include "vtkRenderWindowInteractor.h"

#include <cstdlib>
#include <vector>

namespace
{
struct Cuts
{
  std::vector<vtkSAVRVolumeMapper*> Mappers;
  vtkPlane* Plane;
};

// Key x toggles cropping, k the clipping plane, on every mapper.
void OnKey(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
  const char key = interactor->GetKeyCode();
  for (vtkSAVRVolumeMapper* mapper : static_cast<Cuts*>(clientData)->Mappers)
  {
    if (key == 'x')
    {
      mapper->SetCropping(!mapper->GetCropping());
    }
    else if (key == 'k')
    {
      mapper->GetNumberOfClippingPlanes() > 0
        ? mapper->RemoveAllClippingPlanes()
        : mapper->AddClippingPlane(static_cast<Cuts*>(clientData)->Plane);
    }
  }
  interactor->Render();
}
} // namespace

int main(int argc, char* argv[])
{
  bool crop = false;
  bool clip = false;
  bool parallel = false;
  bool inside = false;
  int volumes = 1;
  int viewports = 1;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_views: the MRI head cropped, clipped, seen from inside, in two volumes and two "
    "viewports\n(keys: x cropping, k clipping plane).");
  savr_scenes::WindowOptions window(arguments, "savr_views.png");
  arguments.Flag("--crop", &crop, "Crop to a fence of the middle thirds.");
  arguments.Flag("--clip", &clip, "Clip with a plane through the centre.");
  arguments.Flag("--parallel", &parallel, "Parallel projection.");
  arguments.Flag("--inside", &inside, "Put the camera inside the volume.");
  arguments.Option("--volumes", &volumes, "1, or 2 for a second volume beside the first.");
  arguments.Option("--viewports", &viewports, "1, or 2 for a second viewport from behind.");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkImageData> head = savr_scenes::Head();
  if (head->GetNumberOfPoints() == 0)
  {
    return EXIT_FAILURE;
  }
  double bounds[6];
  double thirds[6];
  double centre[3];
  head->GetBounds(bounds);
  for (int a = 0; a < 3; ++a)
  {
    thirds[2 * a] = bounds[2 * a] + (bounds[2 * a + 1] - bounds[2 * a]) / 3.0;
    thirds[2 * a + 1] = bounds[2 * a] + 2.0 * (bounds[2 * a + 1] - bounds[2 * a]) / 3.0;
    centre[a] = (bounds[2 * a] + bounds[2 * a + 1]) / 2.0;
  }
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(centre);
  plane->SetNormal(0.0, -1.0, 0.0);
  vtkNew<vtkVolumeProperty> property;
  savr_scenes::HeadProperty(property);

  // A volume with a mapper of its own, cut as the flags say.
  Cuts cuts{ {}, plane };
  std::vector<vtkSmartPointer<vtkSAVRVolumeMapper>> mappers;
  const auto newVolume = [&]()
  {
    mappers.push_back(vtkSmartPointer<vtkSAVRVolumeMapper>::New());
    vtkSAVRVolumeMapper* mapper = mappers.back();
    mapper->SetInputData(head);
    mapper->SetCroppingRegionPlanes(thirds);
    mapper->SetCroppingRegionFlagsToFence();
    mapper->SetCropping(crop);
    if (clip)
    {
      mapper->AddClippingPlane(plane);
    }
    cuts.Mappers.push_back(mapper);
    auto volume = vtkSmartPointer<vtkVolume>::New();
    volume->SetMapper(mapper);
    volume->SetProperty(property);
    return volume;
  };

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(newVolume());
  if (volumes > 1)
  {
    vtkSmartPointer<vtkVolume> second = newVolume();
    second->SetPosition(1.15 * (bounds[1] - bounds[0]), 0.0, 0.0);
    renderer->AddVolume(second);
  }
  renderer->SetBackground(0.1, 0.1, 0.15);
  savr_scenes::FaceTheHead(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(parallel);
  if (inside)
  {
    // From a little behind the centre, looking the same way.
    const double* f = camera->GetFocalPoint();
    const double* p = camera->GetPosition();
    const double view[3] = { p[0] - f[0], p[1] - f[1], p[2] - f[2] };
    camera->SetPosition(
      centre[0] + 0.1 * view[0], centre[1] + 0.1 * view[1], centre[2] + 0.1 * view[2]);
    camera->SetFocalPoint(centre[0] - view[0], centre[1] - view[1], centre[2] - view[2]);
    renderer->ResetCameraClippingRange();
  }
  vtkNew<vtkRenderWindow> renderWindow;
  renderWindow->SetSize(viewports > 1 ? 2 * window.Size : window.Size, window.Size);
  renderWindow->AddRenderer(renderer);
  vtkNew<vtkRenderer> back;
  if (viewports > 1)
  {
    // The right half sees the data from the opposite side.
    renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
    back->SetViewport(0.5, 0.0, 1.0, 1.0);
    back->SetBackground(0.12, 0.1, 0.1);
    back->AddVolume(newVolume());
    back->GetActiveCamera()->DeepCopy(camera);
    back->GetActiveCamera()->Azimuth(180.0);
    back->ResetCameraClippingRange();
    renderWindow->AddRenderer(back);
  }
  renderWindow->SetWindowName("vtkSAVR: cuts and views");
  vtkNew<vtkCallbackCommand> onKey;
  onKey->SetCallback(OnKey);
  onKey->SetClientData(&cuts);
  return savr_scenes::Show(renderWindow, cuts.Mappers, window, onKey);
}

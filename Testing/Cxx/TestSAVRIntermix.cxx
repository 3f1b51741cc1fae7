// An opaque sphere inside the wavelet: rays stop at the sphere, the volume in front of it still
// shows, and the sphere hides the volume behind it.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkActor.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

int TestSAVRIntermix(int argc, char* argv[])
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet();
  savr_scenes::Scene scene(data, 300, 300);
  savr_scenes::WaveletProperty(scene.Property);
  // A thin medium, so that the sphere shows through the half of the volume in front of it.
  scene.Property->SetScalarOpacityUnitDistance(20.0);

  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0, 0, 0);
  sphere->SetRadius(8.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  actor->GetProperty()->SetColor(0.1, 0.9, 0.2);
  scene.Renderer->AddActor(actor);
  scene.Renderer->ResetCameraClippingRange();
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> both = savr_scenes::Capture(scene.Window);

  int failures = 0;
  // The same view with the sphere alone, and with the volume alone.
  scene.Volume->VisibilityOff();
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> sphereOnly = savr_scenes::Capture(scene.Window);
  scene.Volume->VisibilityOn();
  actor->VisibilityOff();
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> volumeOnly = savr_scenes::Capture(scene.Window);
  actor->VisibilityOn();

  const int w = 300;
  const int centre = 3 * (150 * w + 150);
  const unsigned char* pb = savr_scenes::Bytes(both);
  const unsigned char* ps = savr_scenes::Bytes(sphereOnly);
  const unsigned char* pv = savr_scenes::Bytes(volumeOnly);
  std::cout << "centre: both " << int(pb[centre]) << "," << int(pb[centre + 1]) << ","
            << int(pb[centre + 2]) << " sphere " << int(ps[centre]) << "," << int(ps[centre + 1])
            << "," << int(ps[centre + 2]) << " volume " << int(pv[centre]) << ","
            << int(pv[centre + 1]) << "," << int(pv[centre + 2]) << "\n";
  // At the centre the sphere is seen through half the volume: not the bare sphere, and not the
  // full volume either (which would mean the sphere was ignored).
  int diffSphere = 0;
  int diffVolume = 0;
  for (int c = 0; c < 3; ++c)
  {
    diffSphere += std::abs(pb[centre + c] - ps[centre + c]);
    diffVolume += std::abs(pb[centre + c] - pv[centre + c]);
  }
  if (diffSphere < 6)
  {
    std::cerr << "the volume in front of the sphere does not show\n";
    ++failures;
  }
  if (diffVolume < 6)
  {
    std::cerr << "the sphere does not show through the volume\n";
    ++failures;
  }
  // The sphere's green must dominate at the centre: it is opaque and the volume in front is thin.
  if (!(pb[centre + 1] > pb[centre] && pb[centre + 1] > pb[centre + 2]))
  {
    std::cerr << "the sphere does not dominate the centre pixel\n";
    ++failures;
  }
  if (savr_scenes::CoveredFraction(both, scene.Renderer->GetBackground()) < 0.1)
  {
    std::cerr << "the image is (nearly) blank\n";
    ++failures;
  }
  scene.RenderUntilComplete();
  if (!savr_scenes::MatchesBaseline(scene.Window, argc, argv))
  {
    ++failures;
  }

  // The sphere drawn by a renderer in the layer below, whose depth the volume's renderer keeps:
  // the volume's renderer holds no geometry itself, yet its rays must still stop at the sphere,
  // giving the image of both in one renderer.
  scene.Renderer->RemoveActor(actor);
  vtkNew<vtkRenderer> below;
  below->SetBackground(scene.Renderer->GetBackground());
  below->SetActiveCamera(scene.Renderer->GetActiveCamera());
  below->AddActor(actor);
  scene.Window->SetNumberOfLayers(2);
  scene.Window->AddRenderer(below);
  scene.Renderer->SetLayer(1);
  scene.Renderer->PreserveDepthBufferOn();
  scene.RenderUntilComplete();
  const savr_scenes::Difference layered =
    savr_scenes::Compare(savr_scenes::Capture(scene.Window), both);
  std::cout << "sphere in the layer below: max " << layered.Max << " mean " << layered.Mean
            << " levels from both in one renderer\n";
  if (layered.Max > 3 || layered.Mean > 0.05)
  {
    std::cerr << "the volume does not stop at the depth kept from the layer below\n";
    ++failures;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

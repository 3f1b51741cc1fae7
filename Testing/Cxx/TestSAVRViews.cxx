// Views other than one perspective viewport: two viewports in one window each render like a
// window of their own; parallel projection and a camera inside the volume match VTK's
// fixed-point mapper at a fine step.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkImageClip.h"

namespace
{
// The same pixels of a window region.
vtkSmartPointer<vtkImageData> Region(vtkImageData* image, int x0, int x1, int y0, int y1)
{
  vtkNew<vtkImageClip> clip;
  clip->SetInputData(image);
  clip->SetOutputWholeExtent(x0, x1, y0, y1, 0, 0);
  clip->ClipDataOn();
  clip->Update();
  auto region = vtkSmartPointer<vtkImageData>::New();
  region->DeepCopy(clip->GetOutput());
  return region;
}
} // namespace

int TestSAVRViews(int argc, char* argv[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet();

  // Two viewports, two cameras.
  savr_scenes::Scene split(data, 400, 200);
  savr_scenes::WaveletProperty(split.Property);
  split.Renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  right->SetBackground(split.Renderer->GetBackground());
  vtkNew<vtkSAVRVolumeMapper> rightMapper;
  rightMapper->SetInputData(data);
  vtkNew<vtkVolume> rightVolume;
  rightVolume->SetMapper(rightMapper);
  rightVolume->SetProperty(split.Property);
  right->AddVolume(rightVolume);
  right->ResetCamera();
  right->GetActiveCamera()->Elevation(60.0);
  right->GetActiveCamera()->OrthogonalizeViewUp();
  right->ResetCameraClippingRange();
  split.Window->AddRenderer(right);
  do
  {
    split.Window->Render();
  } while (!(split.Mapper->GetRefinementComplete() && rightMapper->GetRefinementComplete()));
  vtkSmartPointer<vtkImageData> both = savr_scenes::Capture(split.Window);

  for (int side = 0; side < 2; ++side)
  {
    savr_scenes::Scene alone(data, 200, 200);
    savr_scenes::WaveletProperty(alone.Property);
    alone.Renderer->SetActiveCamera(
      side == 0 ? split.Renderer->GetActiveCamera() : right->GetActiveCamera());
    alone.RenderUntilComplete();
    vtkSmartPointer<vtkImageData> expected = savr_scenes::Capture(alone.Window);
    vtkSmartPointer<vtkImageData> got = Region(both, 200 * side, 200 * side + 199, 0, 199);
    got->SetOrigin(0, 0, 0);
    got->SetExtent(0, 199, 0, 199, 0, 0);
    const auto d = savr_scenes::Compare(expected, got);
    std::cout << "viewport " << side << " vs its own window: max " << d.Max << " mean " << d.Mean
              << "\n";
    expect(d.Max <= 1.0, "a viewport renders like a window of its own");
    expect(
      savr_scenes::CoveredFraction(got, right->GetBackground()) > 0.1, "the viewport is not blank");
  }

  // Parallel projection and a camera inside the volume, against the fixed-point mapper.
  for (int inside = 0; inside < 2; ++inside)
  {
    savr_scenes::Scene scene(data, 200, 200);
    savr_scenes::WaveletProperty(scene.Property);
    vtkCamera* camera = scene.Renderer->GetActiveCamera();
    if (inside)
    {
      camera->SetPosition(3, 2, 6);
      camera->SetFocalPoint(-5, -3, -20);
      camera->SetViewAngle(60);
      camera->SetClippingRange(0.1, 200);
      scene.Renderer->SetActiveCamera(camera);
    }
    else
    {
      camera->ParallelProjectionOn();
      scene.Renderer->ResetCamera();
    }
    scene.Mapper->SetMaximumNumberOfFrames(16);
    scene.RenderUntilComplete();
    vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene.Window);
    const auto d =
      savr_scenes::Compare(image, savr_scenes::FixedPointImage(data, camera, 200, 200));
    const char* what = inside ? "camera inside the volume" : "parallel projection";
    std::cout << what << " vs fixed point: max " << d.Max << " mean " << d.Mean << "\n";
    // Fixed point quantizes to 15 bits and 8-bit tables and stops rays at 1/128 transmittance:
    // a few levels on average.
    expect(d.Mean < 3.0, std::string(what) + " matches the fixed-point mapper");
    expect(savr_scenes::CoveredFraction(image, scene.Renderer->GetBackground()) > 0.1,
      std::string(what) + ": the image is not blank");
  }

  split.Window->Render();
  if (!savr_scenes::MatchesBaseline(split.Window, argc, argv))
  {
    ++expect.Failures;
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

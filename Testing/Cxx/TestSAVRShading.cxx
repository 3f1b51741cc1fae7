// Shading: the renderer's lights and the volume property's Ambient, Diffuse, Specular and
// SpecularPower, against VTK's fixed-point mapper; normals are stored only when shading is on,
// and editing the coefficients re-blends without resampling.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

namespace
{
void Shaded(vtkVolumeProperty* property, double ambient, double diffuse)
{
  property->ShadeOn();
  property->SetAmbient(ambient);
  property->SetDiffuse(diffuse);
  property->SetSpecular(0.3);
  property->SetSpecularPower(12.0);
}
} // namespace

int TestSAVRShading(int argc, char* argv[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet();

  // Unshaded: no normals are stored (the wavelet's float samples take 2 bytes each).
  savr_scenes::Scene flat(data, 200, 200);
  savr_scenes::WaveletProperty(flat.Property);
  flat.Mapper->SetMaximumNumberOfFrames(8);
  flat.RenderUntilComplete();
  const double flatBytes = savr_scenes::BytesPerStoredSample(flat.Mapper);
  std::cout << "unshaded: " << flatBytes << " bytes per stored sample\n";
  expect(flatBytes == 2.0, "an unshaded scene stores no normals");

  savr_scenes::Scene scene(data, 200, 200);
  savr_scenes::WaveletProperty(scene.Property);
  Shaded(scene.Property, 0.2, 0.7);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  scene.Renderer->SetActiveCamera(flat.Renderer->GetActiveCamera());
  scene.RenderUntilComplete();
  const double shadedBytes = savr_scenes::BytesPerStoredSample(scene.Mapper);
  std::cout << "shaded: " << shadedBytes << " bytes per stored sample\n";
  expect(shadedBytes == 4.0, "a shaded scene stores a 2-byte normal per sample");
  vtkSmartPointer<vtkImageData> shaded = savr_scenes::Capture(scene.Window);
  expect(savr_scenes::Compare(shaded, savr_scenes::Capture(flat.Window)).Mean > 2.0,
    "shading changes the image");
  expect(savr_scenes::CoveredFraction(shaded, scene.Renderer->GetBackground()) > 0.1,
    "the shaded image is not blank");

  // Against the fixed-point mapper at a fine step, shading the same way.
  vtkSmartPointer<vtkImageData> peer =
    savr_scenes::FixedPointImage(data, scene.Renderer->GetActiveCamera(), 200, 200, nullptr,
      [](vtkVolumeProperty* property) { Shaded(property, 0.2, 0.7); });
  const auto d = savr_scenes::Compare(shaded, peer);
  std::cout << "shaded vs fixed point: max " << d.Max << " mean " << d.Mean << "\n";
  // The fixed-point mapper quantizes normals to 13 bits and colours to 15, and estimates
  // gradients on the voxels: measured 1.8 levels on average (ambient alone: 0.03; diffuse
  // alone: 1.6).
  expect(d.Mean < 3.0, "shading matches the fixed-point mapper");

  // Editing the coefficients re-blends the stored samples, and equals a fresh render.
  const vtkTypeUInt64 memory = scene.Mapper->GetMemoryInUse();
  const vtkTypeUInt64 taken = scene.Mapper->GetNumberOfSamplesTaken();
  scene.Property->SetAmbient(0.4);
  scene.Property->SetDiffuse(0.5);
  scene.Window->Render();
  expect(scene.Mapper->GetNumberOfFramesAccumulated() == 8 &&
           scene.Mapper->GetMemoryInUse() == memory && scene.Mapper->GetRefinementComplete() &&
           scene.Mapper->GetNumberOfSamplesTaken() == taken,
    "a coefficient edit re-blends without sampling");
  savr_scenes::Scene fresh(data, 200, 200);
  savr_scenes::WaveletProperty(fresh.Property);
  Shaded(fresh.Property, 0.4, 0.5);
  fresh.Mapper->SetMaximumNumberOfFrames(8);
  fresh.Renderer->SetActiveCamera(scene.Renderer->GetActiveCamera());
  fresh.RenderUntilComplete();
  expect(
    savr_scenes::Compare(savr_scenes::Capture(scene.Window), savr_scenes::Capture(fresh.Window))
        .Max == 0.0,
    "the re-blend equals a fresh render with the new coefficients");
  expect(savr_scenes::Compare(savr_scenes::Capture(scene.Window), shaded).Mean > 1.0,
    "the coefficients change the image");

  scene.Property->SetAmbient(0.2);
  scene.Property->SetDiffuse(0.7);
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> pointShaded = savr_scenes::Capture(scene.Window);

  // Pre-integration is lit too: close to the point-sampled shaded image, far from unshaded.
  scene.Mapper->PreIntegrationOn();
  scene.Window->Render();
  const auto lit = savr_scenes::Compare(savr_scenes::Capture(scene.Window), pointShaded);
  std::cout << "pre-integrated shaded vs point-sampled shaded: mean " << lit.Mean << "\n";
  expect(lit.Mean < 1.5, "pre-integration is shaded like point sampling");
  scene.Mapper->PreIntegrationOff();

  // Interacting passes shade only what they see; they match whatever the thread count, and a
  // budget too small for one frame still shades.
  for (int threads : { 0, 1 })
  {
    savr_scenes::Scene moving(data, 200, 200);
    savr_scenes::WaveletProperty(moving.Property);
    Shaded(moving.Property, 0.2, 0.7);
    moving.Mapper->SetNumberOfThreads(threads);
    moving.Mapper->InteractiveOn();
    moving.Renderer->SetActiveCamera(scene.Renderer->GetActiveCamera());
    moving.Window->Render();
    static vtkSmartPointer<vtkImageData> first;
    vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(moving.Window);
    expect(savr_scenes::Compare(image, pointShaded).Mean < 3.0,
      "an interacting shaded pass is close to the refined image");
    if (threads == 0)
    {
      first = image;
    }
    else
    {
      expect(savr_scenes::Compare(image, first).Max == 0.0,
        "interacting shaded passes do not depend on the thread count");
    }
    moving.Mapper->InteractiveOff();
    // Room for the images, not for one frame's samples.
    moving.Mapper->SetMemoryBudget(moving.Mapper->GetImageMemoryInUse() + 1024);
    moving.Window->Render();
    expect(moving.Mapper->GetRefinementComplete() &&
             savr_scenes::Compare(savr_scenes::Capture(moving.Window), pointShaded).Mean < 3.0,
      "shading without stored samples");
  }

  scene.Window->Render();
  if (!savr_scenes::MatchesBaseline(scene.Window, argc, argv))
  {
    ++expect.Failures;
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

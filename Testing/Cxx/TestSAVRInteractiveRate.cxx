// AutoAdjustSampleDistances: while Interactive, a single pass that takes longer than the time
// VTK allocates the volume (from the window's DesiredUpdateRate) doubles the next pass's step,
// up to 8 base steps, then its pixels per ray, up to 8x8; with time to spare it refines the
// pixels, then the step; switched off, or with the default rate (no drag: thousands of seconds),
// the step stays the base step and every pixel has its ray. Still frames are not affected: the
// refined image after the drag is the one a fresh mapper refines.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"

#include <string>

namespace
{
/// `renders` interactive renders at the window's `rate`, the camera turning a little each time;
/// the step of the next pass in base steps.
double Drag(savr_scenes::Scene& scene, double rate, int renders)
{
  scene.Mapper->SetInteractive(true);
  scene.Window->SetDesiredUpdateRate(rate);
  for (int i = 0; i < renders; ++i)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(2.0);
    scene.Window->Render();
  }
  return scene.Mapper->GetInteractiveSampleDistance() / scene.Mapper->GetEffectiveSampleDistance();
}
} // namespace

int TestSAVRInteractiveRate(int, char*[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(15);

  savr_scenes::Scene scene(data, 160, 160);
  savr_scenes::WaveletProperty(scene.Property);
  scene.RenderUntilComplete();
  // A microsecond per frame: no pass keeps within it.
  const double coarse = Drag(scene, 1e6, 3);
  expect(coarse == 8.0 && scene.Mapper->GetInteractivePixelStride() == 1,
    "passes over their time coarsen the step to 8 base steps first (" + std::to_string(coarse) +
      ")");
  Drag(scene, 1e6, 4);
  expect(scene.Mapper->GetInteractivePixelStride() == 8,
    "then one ray for 2x2, 4x4, at most 8x8 pixels (" +
      std::to_string(scene.Mapper->GetInteractivePixelStride()) + ")");
  expect(savr_scenes::CoveredFraction(
           savr_scenes::Capture(scene.Window), scene.Renderer->GetBackground()) > 0.1,
    "a pass with one ray per 8x8 pixels is drawn");
  // Ten thousand seconds per frame (VTK's rate without a drag): the pixels, then the step come
  // back.
  const double pixelsBack = Drag(scene, 1e-4, 3);
  expect(pixelsBack == 8.0 && scene.Mapper->GetInteractivePixelStride() == 1,
    "passes well within their time give every pixel its ray again first");
  const double back = Drag(scene, 1e-4, 3);
  expect(back == 1.0, "then refine the step again (" + std::to_string(back) + ")");

  // The drag ends: still frames at the base step, the same image as a fresh mapper's.
  Drag(scene, 1e6, 6);
  scene.Mapper->SetInteractive(false);
  scene.Window->SetDesiredUpdateRate(1e-4);
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> refined = savr_scenes::Capture(scene.Window);
  savr_scenes::Scene fresh(data, 160, 160);
  savr_scenes::WaveletProperty(fresh.Property);
  fresh.Renderer->GetActiveCamera()->DeepCopy(scene.Renderer->GetActiveCamera());
  fresh.RenderUntilComplete();
  expect(savr_scenes::Compare(savr_scenes::Capture(fresh.Window), refined).Max == 0,
    "the refined image after the drag is the one a fresh mapper refines");

  savr_scenes::Scene fixed(data, 160, 160);
  savr_scenes::WaveletProperty(fixed.Property);
  fixed.Mapper->AutoAdjustSampleDistancesOff();
  fixed.RenderUntilComplete();
  const double kept = Drag(fixed, 1e6, 8);
  expect(kept == 1.0 && fixed.Mapper->GetInteractivePixelStride() == 1,
    "with AutoAdjustSampleDistances off the step stays the base step (" + std::to_string(kept) +
      "), every pixel its ray");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

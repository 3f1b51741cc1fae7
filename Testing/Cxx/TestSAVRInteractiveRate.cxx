// AutoAdjustSampleDistances: while Interactive, a single pass that takes longer than the time
// VTK allocates the volume (from the window's DesiredUpdateRate) coarsens the next pass by as
// many halvings of its cost as it was over: the step first, up to 8 base steps, then its pixels
// per ray, up to 8x8; with time to spare it refines a level a pass, the pixels, then the step;
// switched off, or with the default rate (no drag: thousands of seconds), the step stays the base
// step and every pixel has its ray. Still frames are not affected: the refined image after the drag
// is the one a fresh mapper refines.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"

#include <algorithm>
#include <string>
#include <vector>

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
  // A pass a few times over its time (a third of what one took): the step alone coarsens (the
  // pixels would at more than 8 times).
  scene.Mapper->AutoAdjustSampleDistancesOff();
  scene.Mapper->SetInteractive(true);
  std::vector<double> took;
  for (int i = 0; i < 5; ++i)
  {
    scene.Renderer->GetActiveCamera()->Azimuth(2.0);
    scene.Window->Render();
    took.push_back(scene.Mapper->GetLastFrameTime());
  }
  std::sort(took.begin(), took.end());
  scene.Mapper->AutoAdjustSampleDistancesOn();
  const double little = Drag(scene, 3.0 / took[2], 1);
  expect(little > 1.0 && scene.Mapper->GetInteractivePixelStride() == 1,
    "a pass a few times over its time coarsens the step first (" + std::to_string(little) + ")");
  // A microsecond per frame: so far over that one pass coarsens the step to 8 base steps and
  // the pixels to one ray per 8x8.
  const double coarse = Drag(scene, 1e6, 1);
  expect(coarse == 8.0 && scene.Mapper->GetInteractivePixelStride() == 8,
    "a pass far over its time coarsens the step to 8 base steps and the pixels to 8x8 (" +
      std::to_string(coarse) + ", " + std::to_string(scene.Mapper->GetInteractivePixelStride()) +
      ")");
  Drag(scene, 1e6, 1);
  expect(savr_scenes::CoveredFraction(
           savr_scenes::Capture(scene.Window), scene.Renderer->GetBackground()) > 0.1,
    "a pass with one ray per 8x8 pixels is drawn");
  // Ten thousand seconds per frame (VTK's rate without a drag): a level a pass, the pixels,
  // then the step come back.
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

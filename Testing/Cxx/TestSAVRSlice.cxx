// Slice blending (vtkVolumeMapper::SLICE_BLEND): the volume property's slice plane drawn with
// the transfer function's colour and opacity at each ray's crossing, as vtkGPUVolumeRayCastMapper
// draws it. Checked: the first Render is the complete image (nothing to refine, error estimate
// 0), an interacting render draws the same, the image matches vtkGPUVolumeRayCastMapper's on the
// same view (Mesa) and its baseline, moving the plane draws the plane where it now is, and a
// slice function that is not a plane ends with an error, an empty image and refinement complete.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkSphere.h"

#include <cstdio>
#include <string>

namespace
{
savr_scenes::Expectations Expect;

constexpr int kSize = 200;

// The wavelet's colours; opacity from 0.3 to 1 over its range, so that the slice is seen whole.
void SliceProperty(vtkVolumeProperty* property, vtkPlane* plane)
{
  savr_scenes::WaveletProperty(property);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(37.0, 0.3);
  opacity->AddPoint(277.0, 1.0);
  property->SetScalarOpacity(opacity);
  property->SetSliceFunction(plane);
}

vtkSmartPointer<vtkImageData> GPUImage(
  vtkImageData* data, vtkPlane* plane, vtkCamera* camera, bool shade = false)
{
  bool supported = false;
  vtkSmartPointer<vtkImageData> image = savr_scenes::GPUImage(
    data, camera, kSize, kSize,
    [&](vtkGPUVolumeRayCastMapper* mapper, vtkVolumeProperty* property, vtkRenderer*)
    {
      mapper->SetBlendModeToSlice();
      SliceProperty(property, plane);
      property->SetShade(shade);
    },
    &supported);
  Expect(supported, "the GPU mapper renders here");
  return image;
}

std::string LastError;

void KeepError(vtkObject*, unsigned long, void*, void* callData)
{
  LastError = callData ? static_cast<const char*>(callData) : "";
}
} // namespace

int TestSAVRSlice(int argc, char* argv[])
{
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet();
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(2.0, -1.0, 3.0);
  plane->SetNormal(1.0, 0.6, 0.8);

  savr_scenes::Scene scene(wavelet, kSize, kSize);
  SliceProperty(scene.Property, plane);
  scene.Mapper->SetBlendModeToSlice();
  scene.Renderer->GetActiveCamera()->Azimuth(30.0);
  scene.Renderer->GetActiveCamera()->Elevation(20.0);
  scene.Renderer->ResetCameraClippingRange();
  scene.Window->Render();
  Expect(scene.Mapper->GetRefinementComplete() != 0, "the first Render is the complete slice");
  Expect(scene.Mapper->GetErrorEstimate() == 0.0, "its error estimate is 0");
  vtkSmartPointer<vtkImageData> slice = savr_scenes::Capture(scene.Window);
  const double background[3] = { 0.1, 0.1, 0.15 };
  const double covered = savr_scenes::CoveredFraction(slice, background);
  std::printf("slice covers %.3f of the window\n", covered);
  Expect(covered > 0.2, "the slice is drawn");

  // Against the GPU mapper on the same view.
  vtkSmartPointer<vtkImageData> gpu =
    GPUImage(wavelet, plane, scene.Renderer->GetActiveCamera());
  const savr_scenes::Difference fromGPU = savr_scenes::Compare(slice, gpu);
  std::printf("against vtkGPUVolumeRayCastMapper: max %.0f levels, mean %.3f\n", fromGPU.Max,
    fromGPU.Mean);
  Expect(fromGPU.Mean <= 2.0, "the slice matches the GPU mapper's (mean at most 2 levels)");
  const bool baseline = savr_scenes::MatchesBaseline(scene.Window, argc, argv);
  Expect(baseline, "the slice matches its baseline");

  // While interacting: the same exact image.
  scene.Mapper->SetInteractive(true);
  scene.Window->Render();
  const savr_scenes::Difference interacting =
    savr_scenes::Compare(savr_scenes::Capture(scene.Window), slice);
  Expect(interacting.Max == 0.0, "an interacting render draws the same slice");
  scene.Mapper->SetInteractive(false);

  // The plane moved: drawn where it is now, again in one Render.
  plane->SetOrigin(-4.0, 2.0, -3.0);
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> moved = savr_scenes::Capture(scene.Window);
  Expect(scene.Mapper->GetRefinementComplete() != 0, "the moved plane is complete at once");
  Expect(savr_scenes::Compare(moved, slice).Mean > 1.0, "moving the plane changes the image");
  const savr_scenes::Difference movedFromGPU = savr_scenes::Compare(
    moved, GPUImage(wavelet, plane, scene.Renderer->GetActiveCamera()));
  std::printf("moved plane against the GPU mapper: max %.0f levels, mean %.3f\n",
    movedFromGPU.Max, movedFromGPU.Mean);
  Expect(movedFromGPU.Mean <= 2.0, "the moved slice matches the GPU mapper's");

  // Lit by the gradient at the crossing, as the GPU mapper lights it.
  scene.Property->SetShade(1);
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> lit = savr_scenes::Capture(scene.Window);
  Expect(scene.Mapper->GetRefinementComplete() != 0, "the lit slice is complete at once");
  Expect(savr_scenes::Compare(lit, moved).Mean > 1.0, "shading changes the slice");
  vtkSmartPointer<vtkImageData> litGPU =
    GPUImage(wavelet, plane, scene.Renderer->GetActiveCamera(), true);
  const savr_scenes::Difference litFromGPU = savr_scenes::Compare(lit, litGPU);
  const savr_scenes::Difference unlitFromGPU = savr_scenes::Compare(moved, litGPU);
  std::printf("lit slice against the GPU mapper's: max %.0f levels, mean %.3f (unlit: mean %.3f)\n",
    litFromGPU.Max, litFromGPU.Mean, unlitFromGPU.Mean);
  // The two mappers light differently (as in composite blending), so the lit images differ
  // more than the unlit ones; lighting must still bring the slice well towards the GPU's.
  Expect(litFromGPU.Mean <= 8.0 && litFromGPU.Mean < 0.5 * unlitFromGPU.Mean,
    "the lit slice is close to the GPU mapper's lit slice (mean at most 8 levels, under half "
    "the unlit slice's difference)");
  scene.Property->SetShade(0);

  // Not a plane: an error naming the problem, nothing drawn, refinement complete.
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(KeepError);
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, onError);
  vtkNew<vtkSphere> sphere;
  scene.Property->SetSliceFunction(sphere);
  scene.Window->Render();
  Expect(LastError.find("slice blending needs a vtkPlane") != std::string::npos &&
      LastError.find("vtkSphere") != std::string::npos,
    "a sphere as the slice function is refused by name (" + LastError + ")");
  Expect(scene.Mapper->GetRefinementComplete() != 0, "refinement is complete after the error");
  Expect(savr_scenes::CoveredFraction(savr_scenes::Capture(scene.Window), background) == 0.0,
    "nothing is drawn after the error");
  return Expect.Failures == 0 ? 0 : 1;
}

// A translucent surface beside and behind the volume, with depth peeling on (ParaView's default):
// with peeling for volumes off, VTK draws the peeled surface and then the volume over it; with it
// on, VTK's dual depth peeling calls every volume's Render once before peeling, once per peel and
// once more at the end, drawing into two colour attachments at once. The mapper draws its image
// once per frame, into the peeling's front layer (so that it composites over the translucent
// surface, as with peeling for volumes off), and nothing at the later calls.
//
// Checked, with the sphere (opacity 0.4) behind the volume: the image with peeling for volumes
// on matches the image with it off (and its baseline), each window Render refines one frame,
// and the image matches vtkGPUVolumeRayCastMapper's with peeling for volumes on (Mesa), which
// composites in depth order: with the sphere behind, the volume over it. With the sphere through
// the volume, one frame per render and the GPU mapper's image within a mean of 3 levels, though
// not in depth order where the sphere is in front (the volume is drawn over it).

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkMath.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <vector>

namespace
{
savr_scenes::Expectations Expect;

constexpr int kSize = 200;

// A translucent sphere behind the volume's centre and to one side, as the camera sees it.
void AddSphere(vtkRenderer* renderer, const double center[3])
{
  static vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(center[0], center[1], center[2]);
  sphere->SetRadius(16.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(48);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.9, 0.9, 0.9);
  actor->GetProperty()->SetOpacity(0.4);
  renderer->AddActor(actor);
}

void Peeling(vtkRenderer* renderer, bool forVolumes)
{
  renderer->SetUseDepthPeeling(1);
  renderer->SetMaximumNumberOfPeels(4);
  renderer->SetOcclusionRatio(0.0);
  renderer->SetUseDepthPeelingForVolumes(forVolumes);
}

struct Result
{
  vtkSmartPointer<vtkImageData> Image;
  int Renders = 0;
  int MostFramesPerRender = 0;
};

Result SAVRImage(vtkImageData* data, const double center[3], bool forVolumes, vtkCamera* camera)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes; // windows stay open
  scenes.emplace_back(new savr_scenes::Scene(data, kSize, kSize));
  savr_scenes::Scene& scene = *scenes.back();
  scene.Window->SetAlphaBitPlanes(1);
  savr_scenes::WaveletProperty(scene.Property);
  AddSphere(scene.Renderer, center);
  Peeling(scene.Renderer, forVolumes);
  scene.Renderer->GetActiveCamera()->DeepCopy(camera);
  scene.Renderer->ResetCameraClippingRange();
  Result result;
  int frames = 0;
  while (!scene.Mapper->GetRefinementComplete() && result.Renders < 64)
  {
    scene.Window->Render();
    ++result.Renders;
    const int now = scene.Mapper->GetNumberOfFramesAccumulated();
    result.MostFramesPerRender = std::max(result.MostFramesPerRender, now - frames);
    frames = now;
  }
  result.Image = savr_scenes::Capture(scene.Window);
  return result;
}

vtkSmartPointer<vtkImageData> GPUImage(
  vtkImageData* data, const double center[3], vtkCamera* camera)
{
  bool supported = false;
  vtkSmartPointer<vtkImageData> image = savr_scenes::GPUImage(
    data, camera, kSize, kSize,
    [&](vtkGPUVolumeRayCastMapper* mapper, vtkVolumeProperty* property, vtkRenderer* renderer)
    {
      renderer->GetRenderWindow()->SetAlphaBitPlanes(1);
      mapper->SetAutoAdjustSampleDistances(0);
      mapper->SetSampleDistance(0.25);
      savr_scenes::WaveletProperty(property);
      AddSphere(renderer, center);
      Peeling(renderer, true);
    },
    &supported);
  Expect(supported, "the GPU mapper renders here");
  return image;
}
} // namespace

int TestSAVRTranslucent(int argc, char* argv[])
{
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet();
  // The camera the scenes use, and a sphere behind the volume and to the right, as it sees it.
  savr_scenes::Scene framing(wavelet, kSize, kSize);
  vtkCamera* camera = framing.Renderer->GetActiveCamera();
  double direction[3];
  camera->GetDirectionOfProjection(direction);
  double right[3];
  vtkMath::Cross(direction, camera->GetViewUp(), right);
  const double* focus = camera->GetFocalPoint();
  double center[3];
  for (int a = 0; a < 3; ++a)
  {
    center[a] = focus[a] + 40.0 * direction[a] + 30.0 * right[a];
  }

  const Result off = SAVRImage(wavelet, center, false, camera);
  const Result on = SAVRImage(wavelet, center, true, camera);
  std::printf("peeling for volumes off: %d renders, at most %d frames per render\n", off.Renders,
    off.MostFramesPerRender);
  std::printf("peeling for volumes on: %d renders, at most %d frames per render\n", on.Renders,
    on.MostFramesPerRender);
  const savr_scenes::Difference onOff = savr_scenes::Compare(on.Image, off.Image);
  std::printf("on against off: max %.0f levels, mean %.3f\n", onOff.Max, onOff.Mean);
  Expect(on.MostFramesPerRender == 1, "with peeling for volumes on, a Render refines one frame");
  Expect(onOff.Mean <= 0.5 && onOff.Max <= 8.0,
    "peeling for volumes on draws what it draws off (mean at most 0.5 levels, max 8)");
  const double background[3] = { 0.1, 0.1, 0.15 };
  Expect(savr_scenes::CoveredFraction(on.Image, background) > 0.3, "volume and sphere are drawn");

  const savr_scenes::Difference fromGPU =
    savr_scenes::Compare(on.Image, GPUImage(wavelet, center, camera));
  std::printf("against vtkGPUVolumeRayCastMapper, peeling for volumes on: max %.0f levels, mean "
              "%.3f\n",
    fromGPU.Max, fromGPU.Mean);
  Expect(fromGPU.Mean <= 3.0, "the GPU mapper's image, peeling for volumes on (mean at most 3)");

  // A sphere through the volume: VTK's other volume mappers, and this one, draw the volume over
  // it; the GPU mapper composites the two in depth order, so where the sphere is in front they
  // differ (max 62 levels measured), but over the image by a mean of 1.65 levels.
  double through[3];
  for (int a = 0; a < 3; ++a)
  {
    through[a] = focus[a] + 12.0 * right[a];
  }
  const Result cut = SAVRImage(wavelet, through, true, camera);
  const savr_scenes::Difference cutFromGPU =
    savr_scenes::Compare(cut.Image, GPUImage(wavelet, through, camera));
  std::printf("a sphere through the volume, against the GPU mapper: max %.0f levels, mean %.3f\n",
    cutFromGPU.Max, cutFromGPU.Mean);
  Expect(cut.MostFramesPerRender == 1 && cutFromGPU.Mean <= 3.0,
    "a sphere through the volume: one frame per render, the GPU mapper's image within a mean of "
    "3 levels");

  // The baseline: the window as it is, with peeling for volumes on.
  savr_scenes::Scene last(wavelet, kSize, kSize);
  last.Window->SetAlphaBitPlanes(1);
  savr_scenes::WaveletProperty(last.Property);
  AddSphere(last.Renderer, center);
  Peeling(last.Renderer, true);
  last.Renderer->GetActiveCamera()->DeepCopy(camera);
  last.Renderer->ResetCameraClippingRange();
  last.RenderUntilComplete(64);
  Expect(savr_scenes::MatchesBaseline(last.Window, argc, argv), "the baseline");
  return Expect.Failures == 0 ? 0 : 1;
}

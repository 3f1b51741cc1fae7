// A translucent surface in the same view as the volume, with depth peeling on (ParaView's
// default): with peeling for volumes off, VTK draws the peeled surface and then the volume over
// it; with it on, VTK's dual depth peeling calls every volume's Render once before peeling, once
// per peel and once more at the end, each time for the parts of the rays between translucent
// layers, drawing into two colour attachments at once. The mapper samples one frame per window
// Render, at the first call, and at each call blends its stored samples over that call's parts,
// so that volume and surface composite in depth order.
//
// Checked, with the sphere (opacity 0.4) behind the volume: the image with peeling for volumes
// on matches the image with it off (and its baseline), each window Render refines one frame, and
// the image matches vtkGPUVolumeRayCastMapper's with peeling for volumes on (Mesa). With the
// argument "order": the sphere through the volume and in front of it, at most 4 peels and none,
// against the GPU mapper (a mean of 3 levels at most; drawn over the sphere, the volume differed
// from it by a mean of 7.8 levels in front), the same image on one thread and two, and the
// baseline of the sphere through the volume.

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
#include <string>
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

void Peeling(vtkRenderer* renderer, bool forVolumes, int peels = 4)
{
  renderer->SetUseDepthPeeling(1);
  renderer->SetMaximumNumberOfPeels(peels);
  renderer->SetOcclusionRatio(0.0);
  renderer->SetUseDepthPeelingForVolumes(forVolumes);
}

struct Result
{
  vtkSmartPointer<vtkImageData> Image;
  int Renders = 0;
  int MostFramesPerRender = 0;
};

Result SAVRImage(vtkImageData* data, const double center[3], bool forVolumes, vtkCamera* camera,
  int peels = 4, int threads = 0)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes; // windows stay open
  scenes.emplace_back(new savr_scenes::Scene(data, kSize, kSize));
  savr_scenes::Scene& scene = *scenes.back();
  scene.Window->SetAlphaBitPlanes(1);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetNumberOfThreads(threads);
  AddSphere(scene.Renderer, center);
  Peeling(scene.Renderer, forVolumes, peels);
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
  vtkImageData* data, const double center[3], vtkCamera* camera, int peels = 4)
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
      Peeling(renderer, true, peels);
    },
    &supported);
  Expect(supported, "the GPU mapper renders here");
  return image;
}
// The window as it is, peeling for volumes on, against the baseline.
bool MatchesBaseline(
  vtkImageData* data, const double center[3], vtkCamera* camera, int argc, char* argv[])
{
  savr_scenes::Scene last(data, kSize, kSize);
  last.Window->SetAlphaBitPlanes(1);
  savr_scenes::WaveletProperty(last.Property);
  AddSphere(last.Renderer, center);
  Peeling(last.Renderer, true);
  last.Renderer->GetActiveCamera()->DeepCopy(camera);
  last.Renderer->ResetCameraClippingRange();
  last.RenderUntilComplete(64);
  return savr_scenes::MatchesBaseline(last.Window, argc, argv);
}

// The sphere through the volume and in front of it, peeling for volumes on with at most 4 peels
// and with none (the pass then blends what lies between the nearest and farthest translucent
// layers in one go): composited in depth order, as the GPU mapper does.
int DepthOrder(vtkImageData* wavelet, vtkCamera* camera, int argc, char* argv[])
{
  const double* focus = camera->GetFocalPoint();
  double direction[3];
  camera->GetDirectionOfProjection(direction);
  double right[3];
  vtkMath::Cross(direction, camera->GetViewUp(), right);
  struct Placement
  {
    const char* Name;
    double Ahead;
    double Aside;
  };
  const Placement placements[] = { { "through", 0.0, 12.0 }, { "in front", -24.0, 6.0 } };
  for (const Placement& placement : placements)
  {
    double center[3];
    for (int a = 0; a < 3; ++a)
    {
      center[a] = focus[a] + placement.Ahead * direction[a] + placement.Aside * right[a];
    }
    for (const int peels : { 4, 0 })
    {
      const Result savr = SAVRImage(wavelet, center, true, camera, peels);
      const savr_scenes::Difference fromGPU =
        savr_scenes::Compare(savr.Image, GPUImage(wavelet, center, camera, peels));
      std::printf("sphere %s, at most %d peels: against the GPU mapper max %.0f levels, mean "
                  "%.3f; at most %d frames per render\n",
        placement.Name, peels, fromGPU.Max, fromGPU.Mean, savr.MostFramesPerRender);
      Expect(fromGPU.Mean <= 3.0, std::string("sphere ") + placement.Name + ", " +
                                    std::to_string(peels) +
                                    " peels: the GPU mapper's image within a mean of 3 levels");
      Expect(savr.MostFramesPerRender == 1, std::string("sphere ") + placement.Name + ", " +
                                              std::to_string(peels) +
                                              " peels: a Render refines one frame");
    }
  }

  // The image does not depend on the number of threads.
  double through[3];
  for (int a = 0; a < 3; ++a)
  {
    through[a] = focus[a] + 12.0 * right[a];
  }
  const Result one = SAVRImage(wavelet, through, true, camera, 4, 1);
  const Result two = SAVRImage(wavelet, through, true, camera, 4, 2);
  const savr_scenes::Difference threads = savr_scenes::Compare(one.Image, two.Image);
  Expect(threads.Max == 0.0, "one thread and two draw the same image");

  Expect(MatchesBaseline(wavelet, through, camera, argc, argv), "the baseline");
  return Expect.Failures == 0 ? 0 : 1;
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
  if (argc > 1 && std::string(argv[1]) == "order")
  {
    return DepthOrder(wavelet, camera, argc, argv);
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

  // A sphere through the volume: in depth order, as the GPU mapper draws it (VTK's other volume
  // mappers draw the volume over it, max 62 levels and a mean of 1.65 from the GPU mapper's).
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

  Expect(MatchesBaseline(wavelet, center, camera, argc, argv), "the baseline");
  return Expect.Failures == 0 ? 0 : 1;
}

// Conformance with VTK's own mappers: lights (VTK's TestGPURayCastVolumeLightKit and the
// one-light cases of its lighting tests, rebuilt on the MRI head). The shaded head is rendered
// by vtkGPUVolumeRayCastMapper, vtkFixedPointVolumeRayCastMapper and vtkSAVRVolumeMapper
// (refined) in the same window size with the same camera and lights. Where VTK's two mappers
// agree, SAVR must agree with them as well: its mean channel difference from the GPU mapper is
// at most twice the fixed-point mapper's plus 2 levels. Each case also checks on which side the
// light falls: the upper half of the image (the top of the head, lit by a light from above) must
// be brighter than the lower half for all three mappers alike.
//
// Cases: the renderer's lights from a vtkLightKit (ParaView's default lighting) with one-sided
// lighting; one scene light from above, one-sided; the same light, two-sided (VTK's mappers
// differ there: the GPU mapper lights both sides of a surface, the fixed-point mapper turns the
// normal to the viewer first; SAVR follows the fixed-point mapper, and the bound follows from
// how far the two disagree).

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkLight.h"
#include "vtkLightKit.h"
#include "vtkVolumeProperty.h"

#include <cstdio>
#include <functional>
#include <string>

namespace
{
constexpr int kSize = 200;
constexpr double kStep = 0.25; // a quarter voxel, for all three

using Lighting = std::function<void(vtkRenderer*)>;

void Shaded(vtkVolumeProperty* property)
{
  savr_scenes::HeadProperty(property);
  property->ShadeOn();
  property->SetAmbient(0.2);
  property->SetDiffuse(0.8);
  property->SetSpecular(0.2);
  property->SetSpecularPower(10.0);
}

/// Mean brightness of the upper half of the image minus the lower half's, in levels.
double UpperMinusLower(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  const unsigned char* bytes = savr_scenes::Bytes(image);
  double upper = 0.0;
  double lower = 0.0;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const unsigned char* p = bytes + 3 * (static_cast<std::size_t>(y) * dims[0] + x);
      const double value = (p[0] + p[1] + p[2]) / 3.0;
      (y >= dims[1] / 2 ? upper : lower) += value;
    }
  }
  const double half = static_cast<double>(dims[0]) * (dims[1] / 2);
  return (upper - lower) / half;
}

struct Images
{
  vtkSmartPointer<vtkImageData> GPU, FixedPoint, SAVR;
};

Images Render(vtkImageData* head, const Lighting& lighting)
{
  Images images;
  // SAVR, refined; its camera is the one every mapper uses.
  savr_scenes::Scene scene(head, kSize, kSize);
  Shaded(scene.Property);
  scene.Mapper->SetSampleDistance(4 * kStep);
  scene.Mapper->SetMaximumNumberOfFrames(4);
  savr_scenes::FaceTheHead(scene.Renderer);
  lighting(scene.Renderer);
  scene.RenderUntilComplete();
  images.SAVR = savr_scenes::Capture(scene.Window);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();

  // The fixed-point mapper in a scene of its own, lit the same way.
  {
    savr_scenes::Scene peer(head, kSize, kSize);
    Shaded(peer.Property);
    vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
    fixedPoint->SetInputData(head);
    fixedPoint->AutoAdjustSampleDistancesOff();
    fixedPoint->SetSampleDistance(kStep);
    fixedPoint->SetImageSampleDistance(1.0);
    peer.Volume->SetMapper(fixedPoint);
    peer.Renderer->SetActiveCamera(camera);
    lighting(peer.Renderer);
    peer.Window->Render();
    images.FixedPoint = savr_scenes::Capture(peer.Window);
  }
  images.GPU = savr_scenes::GPUImage(head, camera, kSize, kSize,
    [&lighting](vtkGPUVolumeRayCastMapper* mapper, vtkVolumeProperty* property, vtkRenderer* ren)
    {
      mapper->AutoAdjustSampleDistancesOff();
      mapper->SetSampleDistance(kStep);
      Shaded(property);
      lighting(ren);
    });
  return images;
}

void Check(savr_scenes::Expectations& expect, const std::string& label, const Images& images)
{
  const double savr = savr_scenes::Compare(images.SAVR, images.GPU).Mean;
  const double fixedPoint = savr_scenes::Compare(images.FixedPoint, images.GPU).Mean;
  const double bound = 2.0 * fixedPoint + 2.0;
  std::printf("%s: SAVR vs GPU mean %.2f levels, fixed point vs GPU %.2f (bound %.2f); upper "
              "minus lower half: GPU %.1f, fixed point %.1f, SAVR %.1f\n",
    label.c_str(), savr, fixedPoint, bound, UpperMinusLower(images.GPU),
    UpperMinusLower(images.FixedPoint), UpperMinusLower(images.SAVR));
  expect(savr <= bound, label + ": SAVR within the bound of the GPU mapper (mean " +
                          std::to_string(savr) + ", bound " + std::to_string(bound) + ")");
  const bool peersAgree =
    (UpperMinusLower(images.GPU) > 0) == (UpperMinusLower(images.FixedPoint) > 0);
  if (peersAgree)
  {
    expect((UpperMinusLower(images.SAVR) > 0) == (UpperMinusLower(images.GPU) > 0),
      label + ": SAVR lights the same half of the head as VTK's mappers");
  }
}
} // namespace

int TestSAVRConformanceLights(int, char*[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> head = savr_scenes::Head();
  if (!head)
  {
    expect(false, "the MRI head is read (" + savr_scenes::HeadFile() + ")");
    return EXIT_FAILURE;
  }

  // ParaView's default lighting: a light kit, one-sided.
  Check(expect, "light kit, one-sided",
    Render(head,
      [](vtkRenderer* renderer)
      {
        renderer->RemoveAllLights();
        vtkNew<vtkLightKit> kit;
        kit->AddLightsToRenderer(renderer);
        renderer->TwoSidedLightingOff();
      }));

  // One scene light above the head (+z is superior), one-sided and two-sided.
  for (const bool twoSided : { false, true })
  {
    Check(expect, twoSided ? "light from above, two-sided" : "light from above, one-sided",
      Render(head,
        [twoSided](vtkRenderer* renderer)
        {
          renderer->RemoveAllLights();
          vtkNew<vtkLight> light;
          light->SetLightTypeToSceneLight();
          light->SetPositional(false);
          light->SetPosition(0.0, 0.0, 1.0);
          light->SetFocalPoint(0.0, 0.0, 0.0);
          renderer->AddLight(light);
          renderer->SetTwoSidedLighting(twoSided);
        }));
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

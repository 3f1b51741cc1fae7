// Clipping planes (one and several) and the five cropping modes, each against VTK's fixed-point
// mapper rendering the same scene at a fine step.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkVolumeMapper.h"

namespace
{
// Renders the wavelet with `configure` applied to both mappers; returns the mean difference.
template <typename Configure>
double CompareWithFixedPoint(const std::string& what, vtkImageData* data, Configure configure,
  savr_scenes::Expectations& expect, vtkSmartPointer<vtkImageData>* keep = nullptr)
{
  savr_scenes::Scene scene(data, 200, 200);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  configure(static_cast<vtkVolumeMapper*>(scene.Mapper));
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene.Window);

  const auto d = savr_scenes::Compare(image,
    savr_scenes::FixedPointImage(data, scene.Renderer->GetActiveCamera(), 200, 200, configure));
  const double covered = savr_scenes::CoveredFraction(image, scene.Renderer->GetBackground());
  std::cout << what << " vs fixed point: max " << d.Max << " mean " << d.Mean << ", covered "
            << covered << "\n";
  // Fixed point quantizes to 15 bits and stops rays at 1/128 transmittance; a cut's edge
  // falls on one side or the other of a pixel: measured 0.2 to 0.9 levels on average.
  expect(d.Mean < 1.5, what + " matches the fixed-point mapper");
  expect(covered > 0.05, what + ": the image is not blank");
  if (keep)
  {
    *keep = image;
  }
  return d.Mean;
}
} // namespace

int TestSAVRCropClip(int argc, char* argv[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet();

  vtkNew<vtkPlane> half;
  half->SetOrigin(2, 0, 0);
  half->SetNormal(1, 0.3, 0);
  vtkNew<vtkPlane> slab;
  slab->SetOrigin(0, 6, 0);
  slab->SetNormal(0, -1, 0.2);
  CompareWithFixedPoint(
    "one clipping plane", data, [&](vtkVolumeMapper* m) { m->AddClippingPlane(half); }, expect);
  CompareWithFixedPoint(
    "two clipping planes", data,
    [&](vtkVolumeMapper* m)
    {
      m->AddClippingPlane(half);
      m->AddClippingPlane(slab);
    },
    expect);

  // The unclipped image differs, or the comparisons above would prove little.
  vtkSmartPointer<vtkImageData> clipped;
  CompareWithFixedPoint(
    "clipped again", data, [&](vtkVolumeMapper* m) { m->AddClippingPlane(half); }, expect,
    &clipped);
  vtkSmartPointer<vtkImageData> whole;
  CompareWithFixedPoint(
    "no clipping", data, [](vtkVolumeMapper*) {}, expect, &whole);
  expect(savr_scenes::Compare(clipped, whole).Mean > 5.0, "clipping changes the image");

  // The fixed-point mapper measures cropping planes from the first voxel as if the extent
  // started at 0: give it such an image of the same points.
  auto zeroExtent = vtkSmartPointer<vtkImageData>::New();
  zeroExtent->SetExtent(0, 40, 0, 40, 0, 40);
  zeroExtent->SetOrigin(-20, -20, -20);
  zeroExtent->GetPointData()->SetScalars(data->GetPointData()->GetScalars());
  data = zeroExtent;

  const struct
  {
    const char* Name;
    int Flags;
  } modes[] = { { "sub-volume", VTK_CROP_SUBVOLUME }, { "fence", VTK_CROP_FENCE },
    { "inverted fence", VTK_CROP_INVERTED_FENCE }, { "cross", VTK_CROP_CROSS },
    { "inverted cross", VTK_CROP_INVERTED_CROSS } };
  vtkSmartPointer<vtkImageData> fence;
  for (const auto& mode : modes)
  {
    vtkSmartPointer<vtkImageData> image;
    CompareWithFixedPoint(
      std::string("cropping, ") + mode.Name, data,
      [&](vtkVolumeMapper* m)
      {
        m->CroppingOn();
        m->SetCroppingRegionPlanes(-12, 8, -10, 10, -6, 14);
        m->SetCroppingRegionFlags(mode.Flags);
      },
      expect, &image);
    expect(
      savr_scenes::Compare(image, whole).Mean > 2.0, std::string(mode.Name) + " changes the image");
    if (mode.Flags == VTK_CROP_FENCE)
    {
      fence = image;
    }
  }

  // The baseline: the fence, rendered again.
  savr_scenes::Scene scene(data, 200, 200);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  scene.Mapper->CroppingOn();
  scene.Mapper->SetCroppingRegionPlanes(-12, 8, -10, 10, -6, 14);
  scene.Mapper->SetCroppingRegionFlagsToFence();
  scene.RenderUntilComplete();
  expect(savr_scenes::Compare(fence, savr_scenes::Capture(scene.Window)).Max == 0.0,
    "the same cropping renders the same image");
  if (!savr_scenes::MatchesBaseline(scene.Window, argc, argv))
  {
    ++expect.Failures;
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

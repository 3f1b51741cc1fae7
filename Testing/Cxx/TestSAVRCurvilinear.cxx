// Curvilinear (vtkStructuredGrid) and rectilinear grids, sampled natively through their
// hexahedra and voxels, against the same field as image data: the grids on the image's points;
// a curvilinear grid whose points are the image's rotated, against the image in a volume rotated
// the same way; and a structured grid with half its cells blanked, against the image cropped to
// the other half.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkDoubleArray.h"
#include "vtkImageDataToPointSet.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRectilinearGrid.h"
#include "vtkStructuredGrid.h"
#include "vtkTransform.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace
{
savr_scenes::Scene* Render(vtkDataObject* data, vtkCamera* camera,
  const std::function<void(savr_scenes::Scene&)>& configure = nullptr)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes;
  scenes.emplace_back(new savr_scenes::Scene(data, 160, 160));
  savr_scenes::Scene& scene = *scenes.back();
  // The sampling is compared with the same values on an image: the image mappers' reading of
  // opacity for the grids too (MeshOpacityAsAttenuation has its own conformance test).
  scene.Mapper->MeshOpacityAsAttenuationOff();
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetSampleDistance(0.5);
  scene.Mapper->SetMaximumNumberOfFrames(4);
  scene.Renderer->SetActiveCamera(camera);
  if (configure)
  {
    configure(scene);
  }
  scene.RenderUntilComplete();
  return &scene;
}

vtkSmartPointer<vtkStructuredGrid> StructuredCopy(vtkImageData* image)
{
  vtkNew<vtkImageDataToPointSet> convert;
  convert->SetInputData(image);
  convert->Update();
  return convert->GetOutput();
}

vtkSmartPointer<vtkRectilinearGrid> RectilinearCopy(vtkImageData* image)
{
  int dims[3];
  image->GetDimensions(dims);
  auto grid = vtkSmartPointer<vtkRectilinearGrid>::New();
  grid->SetDimensions(dims);
  vtkNew<vtkDoubleArray> coordinates[3];
  for (int a = 0; a < 3; ++a)
  {
    for (int i = 0; i < dims[a]; ++i)
    {
      coordinates[a]->InsertNextValue(
        image->GetOrigin()[a] + (image->GetExtent()[2 * a] + i) * image->GetSpacing()[a]);
    }
  }
  grid->SetXCoordinates(coordinates[0]);
  grid->SetYCoordinates(coordinates[1]);
  grid->SetZCoordinates(coordinates[2]);
  grid->GetPointData()->SetScalars(image->GetPointData()->GetScalars());
  return grid;
}
} // namespace

int TestSAVRCurvilinear(int argc, char* argv[])
{
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet(10);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(45, 30, 60);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  camera->SetClippingRange(1, 300);
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> reference = savr_scenes::Capture(Render(wavelet, camera)->Window);

  auto check = [&](const char* name, savr_scenes::Scene* scene, vtkImageData* expected,
                 double maxLevels, double meanLevels)
  {
    vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene->Window);
    const auto d = savr_scenes::Compare(image, expected);
    std::cout << name << " vs image data: max " << d.Max << " mean " << d.Mean << " levels\n";
    expect(d.Max <= maxLevels && d.Mean <= meanLevels, std::string(name) + " render as the image");
    expect(savr_scenes::CoveredFraction(image, scene->Renderer->GetBackground()) > 0.2,
      std::string(name) + " is not blank");
    expect(
      scene->Mapper->GetRefinementComplete() && scene->Mapper->GetNumberOfFramesAccumulated() == 4,
      std::string(name) + " refines to completion");
  };

  // 1. On the image's own points: axis-aligned hexahedra and voxels interpolate trilinearly, as
  // the image does: float round-off only.
  check("structured grid", Render(StructuredCopy(wavelet), camera), reference, 1.0, 0.01);
  check("rectilinear grid", Render(RectilinearCopy(wavelet), camera), reference, 1.0, 0.01);

  // 2. Curvilinear: the points rotated by 30 degrees about two axes (no cell is axis-aligned),
  // against the image placed by a volume rotated the same way.
  vtkSmartPointer<vtkStructuredGrid> rotated = StructuredCopy(wavelet);
  vtkNew<vtkTransform> rotation;
  rotation->RotateZ(30.0);
  rotation->RotateX(30.0);
  vtkNew<vtkPoints> turned;
  rotation->TransformPoints(rotated->GetPoints(), turned);
  rotated->SetPoints(turned);
  vtkSmartPointer<vtkImageData> rotatedReference = savr_scenes::Capture(Render(wavelet, camera,
    [](savr_scenes::Scene& s) { s.Volume->SetOrientation(30, 0, 30); })->Window);
  savr_scenes::Scene* curvilinear = Render(rotated, camera);
  check("rotated curvilinear grid", curvilinear, rotatedReference, 3.0, 0.1);
  // The rotation shows: the check above could tell a grid that ignored it.
  const auto turnedAway = savr_scenes::Compare(rotatedReference, reference);
  std::cout << "rotated vs unrotated image data: max " << turnedAway.Max << " mean "
            << turnedAway.Mean << " levels\n";
  expect(turnedAway.Mean > 1.0, "the rotation changes the image");

  // 3. Blanked cells are transparent: the cells left of x = 0 blanked, against the image cropped
  // to x >= 0.
  vtkSmartPointer<vtkStructuredGrid> blanked = StructuredCopy(wavelet);
  int dims[3];
  blanked->GetDimensions(dims);
  for (int k = 0; k < dims[2] - 1; ++k)
  {
    for (int j = 0; j < dims[1] - 1; ++j)
    {
      for (int i = 0; i < (dims[0] - 1) / 2; ++i)
      {
        blanked->BlankCell(i + (dims[0] - 1) * (j + (dims[1] - 1) * k));
      }
    }
  }
  vtkSmartPointer<vtkImageData> croppedReference = savr_scenes::Capture(Render(wavelet, camera,
    [](savr_scenes::Scene& s)
    {
      s.Mapper->SetCropping(1);
      s.Mapper->SetCroppingRegionPlanes(0, 10, -10, 10, -10, 10);
      s.Mapper->SetCroppingRegionFlagsToSubVolume();
    })->Window);
  savr_scenes::Scene* half = Render(blanked, camera);
  check("half-blanked structured grid", half, croppedReference, 3.0, 0.1);
  expect(half->Mapper->GetRefinementComplete(), "blanked cells are not an error");

  if (!savr_scenes::MatchesBaseline(curvilinear->Window, argc, argv))
  {
    expect(false, "the rotated curvilinear grid matches its baseline");
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// Which data a mapper renders: a named point or cell array instead of the active scalars, and
// two volumes in one renderer, each drawn as it is drawn alone.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"

namespace
{
vtkSmartPointer<vtkImageData> RenderedAlone(
  vtkImageData* data, vtkCamera* camera, void (*configure)(vtkSAVRVolumeMapper*), int size = 160)
{
  savr_scenes::Scene scene(data, size, size);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Renderer->SetActiveCamera(camera);
  if (configure)
  {
    configure(scene.Mapper);
  }
  scene.RenderUntilComplete();
  return savr_scenes::Capture(scene.Window);
}
} // namespace

int TestSAVRSelection(int argc, char* argv[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet(16);
  vtkDataArray* values = wavelet->GetPointData()->GetScalars();

  // An image whose active scalars are a constant, with the wavelet as a second, named array.
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(wavelet);
  vtkNew<vtkFloatArray> constant;
  constant->SetName("constant");
  constant->SetNumberOfTuples(values->GetNumberOfTuples());
  constant->Fill(40.0);
  image->GetPointData()->SetScalars(constant);
  vtkNew<vtkFloatArray> named;
  named->DeepCopy(values);
  named->SetName("wave");
  image->GetPointData()->AddArray(named);

  vtkNew<vtkCamera> camera;
  camera->SetPosition(40, 30, 60);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetClippingRange(1, 200);

  vtkSmartPointer<vtkImageData> expected = RenderedAlone(wavelet, camera, nullptr);
  vtkSmartPointer<vtkImageData> active = RenderedAlone(image, camera, nullptr);
  vtkSmartPointer<vtkImageData> byName = RenderedAlone(image, camera,
    [](vtkSAVRVolumeMapper* m)
    {
      m->SetScalarModeToUsePointFieldData();
      m->SelectScalarArray("wave");
    });
  vtkSmartPointer<vtkImageData> byIndex = RenderedAlone(image, camera,
    [](vtkSAVRVolumeMapper* m)
    {
      m->SetScalarModeToUsePointFieldData();
      m->SelectScalarArray(1);
    });
  expect(savr_scenes::Compare(expected, byName).Max == 0.0, "a point array selected by name");
  expect(savr_scenes::Compare(expected, byIndex).Max == 0.0, "a point array selected by index");
  expect(savr_scenes::Compare(expected, active).Mean > 2.0, "the active scalars are another array");
  expect(savr_scenes::CoveredFraction(
           expected, savr_scenes::Scene(wavelet, 8, 8).Renderer->GetBackground()) > 0.1,
    "the image is not blank");

  // A named cell array: the same values on cells of a grid one point larger.
  auto cells = vtkSmartPointer<vtkImageData>::New();
  cells->SetOrigin(-16.5, -16.5, -16.5);
  cells->SetDimensions(34, 34, 34);
  vtkNew<vtkFloatArray> cellConstant;
  cellConstant->SetName("constant");
  cellConstant->SetNumberOfTuples(values->GetNumberOfTuples());
  cellConstant->Fill(40.0);
  cells->GetCellData()->SetScalars(cellConstant);
  cells->GetCellData()->AddArray(named);
  vtkSmartPointer<vtkImageData> cellByName = RenderedAlone(cells, camera,
    [](vtkSAVRVolumeMapper* m)
    {
      m->SetScalarModeToUseCellFieldData();
      m->SelectScalarArray("wave");
    });
  auto activeCells = vtkSmartPointer<vtkImageData>::New();
  activeCells->CopyStructure(cells);
  activeCells->GetCellData()->SetScalars(named);
  vtkSmartPointer<vtkImageData> cellActive = RenderedAlone(activeCells, camera, nullptr);
  expect(savr_scenes::Compare(cellActive, cellByName).Max == 0.0,
    "a cell array selected by name renders as the same array made active");
  expect(savr_scenes::Compare(cellActive, expected).Mean < 5.0 &&
           savr_scenes::Compare(cellActive, expected).Mean > 0.0,
    "cell data is close to the point data it was made from (the cells reach half a cell further)");

  // Two volumes side by side in one renderer.
  vtkNew<vtkCamera> wide;
  wide->SetPosition(0, 0, 150);
  wide->SetFocalPoint(0, 0, 0);
  wide->SetViewUp(0, 1, 0);
  wide->SetClippingRange(1, 400);
  savr_scenes::Scene both(wavelet, 240, 160);
  savr_scenes::WaveletProperty(both.Property);
  both.Renderer->SetActiveCamera(wide);
  both.Volume->SetPosition(-22, 0, 0);
  vtkNew<vtkSAVRVolumeMapper> secondMapper;
  secondMapper->SetInputData(wavelet);
  vtkNew<vtkVolume> second;
  second->SetMapper(secondMapper);
  second->SetProperty(both.Property);
  second->SetPosition(22, 0, 0);
  both.Renderer->AddVolume(second);
  do
  {
    both.Window->Render();
  } while (!(both.Mapper->GetRefinementComplete() && secondMapper->GetRefinementComplete()));
  vtkSmartPointer<vtkImageData> pair = savr_scenes::Capture(both.Window);
  for (int side = 0; side < 2; ++side)
  {
    savr_scenes::Scene alone(wavelet, 240, 160);
    savr_scenes::WaveletProperty(alone.Property);
    alone.Renderer->SetActiveCamera(wide);
    alone.Volume->SetPosition(side == 0 ? -22 : 22, 0, 0);
    alone.RenderUntilComplete();
    vtkSmartPointer<vtkImageData> single = savr_scenes::Capture(alone.Window);
    // Compare the half of the window where this volume is.
    const unsigned char* a = savr_scenes::Bytes(single);
    const unsigned char* b = savr_scenes::Bytes(pair);
    int worst = 0;
    for (int y = 0; y < 160; ++y)
    {
      for (int x = side * 120; x < side * 120 + 120; ++x)
      {
        for (int c = 0; c < 3; ++c)
        {
          worst = std::max(worst, std::abs(a[3 * (y * 240 + x) + c] - b[3 * (y * 240 + x) + c]));
        }
      }
    }
    std::cout << "volume " << side << " in a pair vs alone: max " << worst << "\n";
    expect(worst <= 1, "each of two volumes renders as it does alone");
  }
  expect(
    savr_scenes::CoveredFraction(pair, both.Renderer->GetBackground()) > 0.1, "the pair is drawn");

  both.Window->Render();
  if (!savr_scenes::MatchesBaseline(both.Window, argc, argv))
  {
    ++expect.Failures;
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

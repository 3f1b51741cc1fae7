// vtkOverlappingAMR input: VTK's Gaussian pulse hierarchy rendered natively, against the same
// analytic pulse on a uniform grid at the finest level's resolution (the independent
// expectation) and at the coarsest (which the refinement must beat); bounds, progression,
// scalar selection by name, and a baseline.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkOverlappingAMR.h"

namespace
{
savr_scenes::Expectations Expect;

double Pulse(const double p[3])
{
  double r = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double d = (p[a] - savr_scenes::PulseOrigin[a]) / savr_scenes::PulseWidth;
    r += d * d;
  }
  return std::exp(-r);
}

// The pulse at the cell centres of a grid of cells `h` wide over `bounds`.
vtkSmartPointer<vtkImageData> PulseImage(const double bounds[6], double h)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  int cells[3];
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = static_cast<int>(std::lround((bounds[2 * a + 1] - bounds[2 * a]) / h));
  }
  image->SetDimensions(cells[0] + 1, cells[1] + 1, cells[2] + 1);
  image->SetOrigin(bounds[0], bounds[2], bounds[4]);
  image->SetSpacing(h, h, h);
  vtkNew<vtkDoubleArray> values;
  values->SetName("Gaussian-Pulse");
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i)
      {
        const double p[3] = { bounds[0] + (i + 0.5) * h, bounds[2] + (j + 0.5) * h,
          bounds[4] + (k + 0.5) * h };
        values->InsertNextValue(Pulse(p));
      }
  image->GetCellData()->SetScalars(values);
  return image;
}

savr_scenes::Scene* Render(vtkDataObject* data, vtkCamera* camera, bool refine)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes;
  scenes.emplace_back(new savr_scenes::Scene(data, 200, 200));
  savr_scenes::Scene& scene = *scenes.back();
  savr_scenes::PulseProperty(scene.Property);
  scene.Mapper->SetScalarModeToUseCellFieldData();
  scene.Mapper->SelectScalarArray("Gaussian-Pulse");
  scene.Mapper->SetSampleDistance(0.25);
  scene.Mapper->SetMaximumNumberOfFrames(16); // a final step of 1/64 of a level-1 cell
  scene.Renderer->SetActiveCamera(camera);
  if (refine)
  {
    scene.RenderUntilComplete();
  }
  else
  {
    scene.Window->Render();
  }
  return &scene;
}
} // namespace

int TestSAVRAMR(int argc, char* argv[])
{
  vtkSmartPointer<vtkOverlappingAMR> amr = savr_scenes::GaussianPulse();
  double bounds[6];
  amr->GetBounds(bounds);
  Expect(amr->GetNumberOfLevels() == 2, "the pulse source makes two levels");

  vtkNew<vtkCamera> camera;
  camera->SetFocalPoint(
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]));
  camera->SetPosition(4.0, -5.0, 5.5);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(30);
  camera->SetClippingRange(0.5, 30);

  savr_scenes::Scene* first = Render(amr, camera, false);
  vtkSmartPointer<vtkImageData> firstImage = savr_scenes::Capture(first->Window);
  savr_scenes::Scene* refined = Render(amr, camera, true);
  vtkSmartPointer<vtkImageData> amrImage = savr_scenes::Capture(refined->Window);
  const double* volumeBounds = refined->Volume->GetBounds();
  bool sameBounds = true;
  for (int i = 0; i < 6; ++i)
  {
    sameBounds = sameBounds && std::abs(volumeBounds[i] - bounds[i]) < 1e-12;
  }
  Expect(sameBounds, "the volume's bounds are the hierarchy's");
  Expect(refined->Mapper->GetNumberOfFramesAccumulated() == 16, "refinement accumulates 16 frames");
  Expect(savr_scenes::CoveredFraction(amrImage, refined->Renderer->GetBackground()) > 0.1,
    "the AMR image is not blank");
  Expect(
    savr_scenes::Compare(firstImage, amrImage).Mean > 0.05, "refinement changes the first frame");

  // The analytic pulse at the finest level's resolution everywhere, and at the coarsest.
  vtkSmartPointer<vtkImageData> fine = PulseImage(bounds, 0.25);
  vtkSmartPointer<vtkImageData> coarse = PulseImage(bounds, 0.5);
  vtkSmartPointer<vtkImageData> fineImage =
    savr_scenes::Capture(Render(fine, camera, true)->Window);
  vtkSmartPointer<vtkImageData> coarseImage =
    savr_scenes::Capture(Render(coarse, camera, true)->Window);
  const auto toFine = savr_scenes::Compare(amrImage, fineImage);
  const auto coarseToFine = savr_scenes::Compare(coarseImage, fineImage);
  std::cout << "AMR vs fine grid: max " << toFine.Max << " mean " << toFine.Mean
            << "; coarse grid vs fine grid: max " << coarseToFine.Max << " mean "
            << coarseToFine.Mean << " levels\n";
  // The hierarchy holds the fine values where the pulse's refined patches are and coarse values
  // elsewhere: it must be much closer to the fine grid than the coarse grid is, and close in
  // absolute terms (the remaining error is the coarse level's interpolation outside the
  // patches).
  Expect(toFine.Mean < 0.5 * coarseToFine.Mean,
    "the AMR image is closer to the fine grid than the coarse grid is");
  Expect(toFine.Mean < 1.5, "the AMR image matches the fine grid to 1.5 levels on average");

  // Images do not depend on the thread count.
  savr_scenes::Scene* oneThread = Render(amr, camera, false);
  oneThread->Mapper->SetNumberOfThreads(1);
  oneThread->RenderUntilComplete();
  Expect(savr_scenes::Compare(savr_scenes::Capture(oneThread->Window), amrImage).Max == 0.0,
    "1 thread and all threads give the same bytes");

  refined->Window->Render(); // refinement is complete: the same image again
  if (!savr_scenes::MatchesBaseline(refined->Window, argc, argv))
  {
    ++Expect.Failures;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

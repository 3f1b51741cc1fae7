// Isosurface blend mode on a distance field, whose isosurfaces are spheres of known radii:
// coverage and composited colours follow from geometry alone; then shaded, against a baseline.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkFloatArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"

int TestSAVRIsosurface(int argc, char* argv[])
{
  savr_scenes::Expectations expect;
  // Distance from the centre of a 41^3 grid of unit spacing.
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->SetExtent(-20, 20, -20, 20, -20, 20);
  vtkNew<vtkFloatArray> distance;
  distance->SetName("distance");
  distance->SetNumberOfTuples(field->GetNumberOfPoints());
  for (vtkIdType i = 0; i < field->GetNumberOfPoints(); ++i)
  {
    double p[3];
    field->GetPoint(i, p);
    distance->SetValue(i, static_cast<float>(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2])));
  }
  field->GetPointData()->SetScalars(distance);

  const double background[3] = { 0.1, 0.1, 0.15 };
  savr_scenes::Scene scene(field, 200, 200);
  scene.Renderer->SetBackground(background[0], background[1], background[2]);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 1.0, 1.0, 1.0);
  color->AddRGBPoint(40.0, 1.0, 1.0, 1.0);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.5);
  opacity->AddPoint(40.0, 0.5);
  scene.Property->SetColor(color);
  scene.Property->SetScalarOpacity(opacity);
  scene.Property->SetInterpolationTypeToLinear();
  scene.Property->GetIsoSurfaceValues()->SetValue(0, 8.0);
  scene.Property->GetIsoSurfaceValues()->SetValue(1, 14.0);
  scene.Mapper->SetBlendModeToIsoSurface();
  scene.Mapper->SetMaximumNumberOfFrames(8);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 0, 100);
  camera->SetViewUp(0, 1, 0);
  camera->ParallelProjectionOn();
  camera->SetParallelScale(20.0); // 200 pixels span 40 units: 5 pixels per unit
  camera->SetClippingRange(50, 150);
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene.Window);

  // A ray through both spheres crosses four surfaces of opacity 0.5; through the outer shell
  // only, two; outside, none. White surfaces over the background.
  const unsigned char* p = savr_scenes::Bytes(image);
  auto expected = [&](int crossings, int c)
  {
    const double t = std::pow(0.5, crossings);
    return 255.0 * ((1.0 - t) + t * background[c]);
  };
  const struct
  {
    const char* Name;
    int X, Y, Crossings;
  } probes[] = { { "centre", 100, 100, 4 }, { "inside the outer shell only", 100 + 55, 100, 2 },
    { "outside", 100 + 85, 100, 0 } };
  for (const auto& probe : probes)
  {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, static_cast<int>(std::abs(p[3 * (probe.Y * 200 + probe.X) + c] -
                                                        expected(probe.Crossings, c))));
    }
    std::cout << probe.Name << ": " << int(p[3 * (probe.Y * 200 + probe.X)]) << " expected "
              << expected(probe.Crossings, 0) << "\n";
    expect(worst <= 2, std::string("composited isosurfaces: ") + probe.Name);
  }
  // The outer sphere covers a disc of radius 14 units = 70 pixels.
  const double covered = savr_scenes::CoveredFraction(image, background);
  const double disc = M_PI * 70.0 * 70.0 / (200.0 * 200.0);
  std::cout << "covered " << covered << ", disc " << disc << "\n";
  // Within a ring of 1.5 pixels around the exact silhouette (the field is interpolated linearly
  // between grid points and samples, and a pixel counts when its centre's ray hits).
  const double ring = 2.0 * M_PI * 70.0 * 1.5 / (200.0 * 200.0);
  expect(std::abs(covered - disc) < ring, "the outer sphere's silhouette");

  // Shaded: lit with the interpolated normals; compared with the baseline.
  scene.Property->ShadeOn();
  scene.Property->SetAmbient(0.2);
  scene.Property->SetDiffuse(0.8);
  scene.Property->SetSpecular(0.3);
  camera->ParallelProjectionOff();
  camera->SetPosition(40, 30, 70);
  camera->SetClippingRange(10, 200);
  scene.RenderUntilComplete();
  expect(savr_scenes::CoveredFraction(savr_scenes::Capture(scene.Window), background) > 0.2,
    "the shaded isosurfaces are drawn");
  if (!savr_scenes::MatchesBaseline(scene.Window, argc, argv))
  {
    ++expect.Failures;
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

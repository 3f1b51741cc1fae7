// The image adaptor places data in world space from the image's origin, spacing, direction
// matrix and extent, and the volume's matrix; point and cell scalars of every numeric type.
// Equivalent placements must give the same image; the baseline holds the rotated one.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkImageCast.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkPointData.h"
#include "vtkTransform.h"

namespace
{
savr_scenes::Expectations Expect;

vtkSmartPointer<vtkImageData> RenderedWith(vtkImageData* data, vtkMatrix4x4* volumeMatrix,
  vtkCamera* camera, savr_scenes::Scene** keep = nullptr)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes;
  scenes.emplace_back(new savr_scenes::Scene(data, 160, 160));
  savr_scenes::Scene& scene = *scenes.back();
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetSampleDistance(0.5);
  scene.Mapper->SetMaximumNumberOfFrames(2);
  if (volumeMatrix)
  {
    scene.Volume->SetUserMatrix(volumeMatrix);
  }
  scene.Renderer->SetActiveCamera(camera);
  scene.RenderUntilComplete();
  if (keep)
  {
    *keep = &scene;
  }
  return savr_scenes::Capture(scene.Window);
}
} // namespace

int TestSAVRPlacement(int argc, char* argv[])
{
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet(12);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(60, 35, 80);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetClippingRange(1, 300);
  camera->SetViewAngle(40);

  // A rotation about z by 90 degrees and a translation, once as the image's direction matrix and
  // origin, once as the volume's matrix.
  vtkNew<vtkTransform> transform;
  transform->Translate(3, -2, 1);
  transform->RotateZ(90);
  vtkSmartPointer<vtkImageData> viaVolume = RenderedWith(wavelet, transform->GetMatrix(), camera);

  auto directed = vtkSmartPointer<vtkImageData>::New();
  directed->ShallowCopy(wavelet);
  double direction[9] = { 0, -1, 0, 1, 0, 0, 0, 0, 1 };
  directed->SetDirectionMatrix(direction);
  // world = origin + D * index, with the extent's own indices (-12..12): origin = t.
  directed->SetOrigin(3, -2, 1);
  savr_scenes::Scene* rotatedScene = nullptr;
  vtkSmartPointer<vtkImageData> viaDirection =
    RenderedWith(directed, nullptr, camera, &rotatedScene);
  auto d = savr_scenes::Compare(viaVolume, viaDirection);
  std::cout << "direction matrix vs volume matrix: max " << d.Max << " mean " << d.Mean << "\n";
  Expect(d.Max <= 1.0, "a direction matrix places data like the same volume matrix");
  Expect(savr_scenes::CoveredFraction(viaDirection, rotatedScene->Renderer->GetBackground()) > 0.1,
    "the rotated image is not blank");

  // Spacing 2 and a shifted extent vs a volume matrix scaling by 2.
  vtkSmartPointer<vtkImageData> plain = RenderedWith(wavelet, nullptr, camera);
  Expect(
    savr_scenes::Compare(plain, viaVolume).Mean > 1.0, "the placements differ from no placement");
  vtkNew<vtkTransform> scale;
  scale->Scale(2, 2, 2);
  vtkSmartPointer<vtkImageData> scaledByVolume = RenderedWith(wavelet, scale->GetMatrix(), camera);
  auto spaced = vtkSmartPointer<vtkImageData>::New();
  spaced->ShallowCopy(wavelet);
  spaced->SetSpacing(2, 2, 2);
  vtkSmartPointer<vtkImageData> scaledBySpacing = RenderedWith(spaced, nullptr, camera);
  d = savr_scenes::Compare(scaledByVolume, scaledBySpacing);
  std::cout << "spacing vs volume scale: max " << d.Max << " mean " << d.Mean << "\n";
  Expect(d.Max <= 1.0, "spacing places data like the same volume scale");

  // Every numeric scalar type of the same values renders the same image (the values fit all).
  const int types[] = { VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_UNSIGNED_SHORT, VTK_INT, VTK_UNSIGNED_INT,
    VTK_LONG_LONG, VTK_UNSIGNED_LONG_LONG, VTK_FLOAT, VTK_DOUBLE };
  vtkNew<vtkImageCast> toBytes;
  toBytes->SetInputData(wavelet);
  toBytes->SetOutputScalarType(VTK_UNSIGNED_CHAR);
  toBytes->ClampOverflowOn();
  toBytes->Update();
  vtkSmartPointer<vtkImageData> reference;
  for (int type : types)
  {
    vtkNew<vtkImageCast> cast;
    cast->SetInputConnection(toBytes->GetOutputPort());
    cast->SetOutputScalarType(type);
    cast->Update();
    vtkSmartPointer<vtkImageData> image = RenderedWith(cast->GetOutput(), nullptr, camera);
    if (!reference)
    {
      reference = image;
      continue;
    }
    d = savr_scenes::Compare(reference, image);
    std::cout << vtkImageScalarTypeNameMacro(type) << " vs unsigned char: max " << d.Max << "\n";
    // Integral types store exactly. Float and double are normalized to 16 bits and their
    // interpolated samples are not rounded to a whole level, as the integral types' are: two
    // levels at most.
    Expect(d.Max <= (type == VTK_FLOAT || type == VTK_DOUBLE ? 2.0 : 0.0),
      std::string("scalar type ") + vtkImageScalarTypeNameMacro(type));
  }

  // Cell scalars: the wavelet's point values moved to cells render close to the point version.
  auto cells = vtkSmartPointer<vtkImageData>::New();
  cells->SetOrigin(-12.5, -12.5, -12.5);
  cells->SetDimensions(26, 26, 26);
  cells->GetCellData()->SetScalars(wavelet->GetPointData()->GetScalars());
  vtkSmartPointer<vtkImageData> fromCells = RenderedWith(cells, nullptr, camera);
  d = savr_scenes::Compare(plain, fromCells);
  std::cout << "cell scalars vs point scalars: max " << d.Max << " mean " << d.Mean << "\n";
  // Same values at the same centres; only the half-cell rim at the boundary differs.
  Expect(d.Mean < 2.0, "cell scalars render like the same point scalars");

  rotatedScene->Window->Render();
  if (!savr_scenes::MatchesBaseline(rotatedScene->Window, argc, argv))
  {
    ++Expect.Failures;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

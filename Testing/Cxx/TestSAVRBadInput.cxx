// Bad input gets a clear error and a blank image; partial problems (NaN voxels) render the rest.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkAMRGaussianPulseSource.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkObject.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnstructuredGrid.h"

#include <functional>
#include <limits>

namespace
{
struct ErrorCatcher
{
  int Count = 0;
  std::string Last;
};

void CatchError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* catcher = static_cast<ErrorCatcher*>(clientData);
  ++catcher->Count;
  catcher->Last = callData ? static_cast<const char*>(callData) : "";
}

vtkSmartPointer<vtkImageData> Image(int nx, int ny, int nz, double spacing = 1.0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->SetSpacing(spacing, spacing, spacing);
  return image;
}

vtkSmartPointer<vtkFloatArray> Ramp(vtkIdType n, int components = 1)
{
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName("ramp");
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n * components; ++i)
  {
    array->SetValue(i, static_cast<float>(37 + (i % 240)));
  }
  return array;
}

// Renders `image` in `window` (one window for all cases: creating and destroying X windows in
// quick succession makes Xvfb refuse connections now and then) with a fresh mapper, and reports
// whether an error was raised and how much of the window is covered.
bool RenderCase(vtkRenderWindow* window, vtkRenderer* renderer, const std::string& name,
  vtkDataObject* image, const char* expectedError, bool expectImage, bool independent = true,
  const std::function<void(vtkSAVRVolumeMapper*)>& configure = nullptr)
{
  vtkNew<vtkSAVRVolumeMapper> mapper;
  mapper->SetInputDataObject(image);
  if (configure)
  {
    configure(mapper);
  }
  vtkNew<vtkVolumeProperty> property;
  savr_scenes::WaveletProperty(property);
  property->SetIndependentComponents(independent);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  renderer->RemoveAllViewProps();
  renderer->AddVolume(volume);
  if (renderer->GetActiveCamera()->GetViewUp()[2] != 1.0)
  {
    renderer->ResetCamera(-10, 10, -10, 10, -10, 10);
  }
  ErrorCatcher catcher;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(CatchError);
  callback->SetClientData(&catcher);
  mapper->AddObserver(vtkCommand::ErrorEvent, callback);
  window->Render();
  window->Render(); // a second frame must not crash or repeat the message
  const double covered =
    savr_scenes::CoveredFraction(savr_scenes::Capture(window), renderer->GetBackground());
  const std::string message = catcher.Last.substr(catcher.Last.find('\n') + 1);
  const bool errorAsExpected =
    expectedError ? catcher.Count == 1 && message.find(expectedError) != std::string::npos
                  : catcher.Count == 0;
  // A failed input has nothing left to refine, so loops that wait for completion end (an input
  // drawn in part refines as usual).
  const bool completes = !expectedError || expectImage || mapper->GetRefinementComplete();
  const bool ok = errorAsExpected && (covered > 0.01) == expectImage && completes;
  std::cout << (ok ? "ok     " : "FAILED ") << name << ": errors " << catcher.Count << " covered "
            << covered << (message.empty() ? "" : " message: ") << message << "\n";
  renderer->RemoveAllViewProps();
  return ok;
}
// Images: empty, too small, flat, without or with unusable scalars, too large for their array;
// NaN voxels; a camera that cannot be inverted; and, last, a valid image.
int ImageCases(vtkRenderWindow* window, vtkRenderer* renderer)
{
  int failures = 0;
  auto RenderCase = [&](
                      const std::string& name, vtkDataObject* image, const char* error, bool drawn)
  { return ::RenderCase(window, renderer, name, image, error, drawn); };
  auto empty = vtkSmartPointer<vtkImageData>::New();
  failures += !RenderCase("empty image", empty, "empty", false);

  auto single = Image(1, 1, 1);
  single->GetPointData()->SetScalars(Ramp(1));
  failures += !RenderCase("one voxel", single, "at least 2 points", false);

  auto flat = Image(10, 10, 10, 0.0);
  flat->GetPointData()->SetScalars(Ramp(1000));
  failures += !RenderCase("zero spacing", flat, "spacing is zero", false);

  auto noScalars = Image(10, 10, 10);
  failures += !RenderCase("no scalars", noScalars, "no scalars", false);

  auto fiveComponents = Image(10, 10, 10);
  fiveComponents->GetPointData()->SetScalars(Ramp(1000, 5));
  failures += !RenderCase("five components", fiveComponents, "5 components", false);

  // Three components are independent only (dependent ones are luminance-alpha or RGBA).
  auto threeComponents = Image(10, 10, 10);
  threeComponents->GetPointData()->SetScalars(Ramp(1000, 3));
  failures += !::RenderCase(window, renderer, "three dependent components", threeComponents,
    "dependent components must be two", false, false);

  auto strings = Image(10, 10, 10);
  vtkNew<vtkStringArray> text;
  text->SetNumberOfValues(1000);
  text->SetName("text");
  strings->GetPointData()->AddArray(text);
  failures += !RenderCase("string array only", strings, "no scalars", false);

  auto huge = Image(100000, 100000, 100000);
  huge->GetPointData()->SetScalars(Ramp(1000));
  failures +=
    !RenderCase("dimensions larger than the array", huge, "shorter than the image", false);

  // NaN and Inf voxels are transparent; the rest of the volume renders, with no error.
  auto holes = Image(21, 21, 21);
  auto values = Ramp(21 * 21 * 21);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); i += 7)
  {
    values->SetValue(
      i, i % 2 ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity());
  }
  holes->GetPointData()->SetScalars(values);
  holes->SetOrigin(-10, -10, -10);
  failures += !RenderCase("NaN and Inf voxels", holes, nullptr, true);

  // A camera whose view-up is parallel to its direction: its projection cannot be inverted.
  {
    auto fine = Image(21, 21, 21);
    fine->SetOrigin(-10, -10, -10);
    fine->GetPointData()->SetScalars(Ramp(21 * 21 * 21));
    vtkNew<vtkCamera> degenerate;
    degenerate->SetPosition(0, 0, 50);
    degenerate->SetFocalPoint(0, 0, 0);
    degenerate->SetViewUp(0, 0, 1);
    renderer->SetActiveCamera(degenerate);
    failures +=
      !RenderCase("view-up parallel to the view direction", fine, "cannot be inverted", false);
    vtkNew<vtkCamera> sane;
    renderer->SetActiveCamera(sane);
  }

  // A sane image renders (the checks above would pass on a mapper that draws nothing).
  auto fine = Image(21, 21, 21);
  fine->SetOrigin(-10, -10, -10);
  fine->GetPointData()->SetScalars(Ramp(21 * 21 * 21));
  failures += !RenderCase("a valid image", fine, nullptr, true);

  return failures;
}

// Unstructured grids and AMR without what a render needs.
int MeshAndAMRCases(vtkRenderWindow* window, vtkRenderer* renderer)
{
  int failures = 0;
  auto RenderCase = [&](
                      const std::string& name, vtkDataObject* image, const char* error, bool drawn)
  { return ::RenderCase(window, renderer, name, image, error, drawn); };
  // Unstructured grids: no cells; only unsupported cells; missing scalars; and unsupported cells
  // among tetrahedra, which are left out with one message while the rest renders.
  {
    auto noCells = vtkSmartPointer<vtkUnstructuredGrid>::New();
    failures += !RenderCase("unstructured grid without cells", noCells, "no cells", false);

    vtkNew<vtkPoints> points;
    for (int i = 0; i < 8; ++i)
    {
      points->InsertNextPoint(i & 1 ? 10 : -10, i & 2 ? 10 : -10, i & 4 ? 10 : -10);
    }
    auto triangles = vtkSmartPointer<vtkUnstructuredGrid>::New();
    triangles->SetPoints(points);
    const vtkIdType triangle[3] = { 0, 1, 2 };
    triangles->InsertNextCell(VTK_TRIANGLE, 3, triangle);
    triangles->GetPointData()->SetScalars(Ramp(8));
    failures +=
      !RenderCase("unstructured grid of triangles", triangles, "no supported cells", false);

    auto mixed = vtkSmartPointer<vtkUnstructuredGrid>::New();
    mixed->SetPoints(points);
    const vtkIdType hexahedron[8] = { 0, 1, 3, 2, 4, 5, 7, 6 };
    mixed->InsertNextCell(VTK_HEXAHEDRON, 8, hexahedron);
    mixed->InsertNextCell(VTK_TRIANGLE, 3, triangle);
    auto values = Ramp(8);
    for (vtkIdType i = 0; i < 8; ++i)
    {
      values->SetValue(i, 200.0f + 10.0f * static_cast<float>(i % 3));
    }
    mixed->GetPointData()->SetScalars(values);
    failures += !RenderCase("a triangle among hexahedra", mixed, "1 cells are left out", true);

    auto unnamed = vtkSmartPointer<vtkUnstructuredGrid>::New();
    unnamed->SetPoints(points);
    unnamed->InsertNextCell(VTK_HEXAHEDRON, 8, hexahedron);
    failures += !RenderCase("unstructured grid without scalars", unnamed, "no scalars", false);
  }

  // AMR: no levels; blocks without the array.
  {
    auto none = vtkSmartPointer<vtkOverlappingAMR>::New();
    failures += !RenderCase("AMR without levels", none, "no levels", false);

    vtkNew<vtkAMRGaussianPulseSource> pulse;
    pulse->Update();
    auto pulseAMR = vtkSmartPointer<vtkOverlappingAMR>::New();
    pulseAMR->ShallowCopy(pulse->GetOutput());
    // Point scalars are asked for; the pulse has cell arrays only.
    failures += !RenderCase("AMR without point scalars", pulseAMR, "has no scalars", false);
  }

  return failures;
}

int ParticleCases(vtkRenderWindow* window, vtkRenderer* renderer)
{
  int failures = 0;
  // Particles (vtkPolyData): none; a radius array of the wrong length; a zero radius; a radius
  // array that is missing; non-finite positions among good ones (left out, the rest drawn); a
  // hundred thousand coincident points (merged: one particle, drawn at once).
  const auto cloud = [](vtkIdType n, double spread)
  {
    auto points = vtkSmartPointer<vtkPoints>::New();
    for (vtkIdType i = 0; i < n; ++i)
    {
      const double t = spread * i;
      points->InsertNextPoint(8.0 * std::sin(1.7 * t), 8.0 * std::cos(2.3 * t), 8.0 * std::sin(t));
    }
    auto particles = vtkSmartPointer<vtkPolyData>::New();
    particles->SetPoints(points);
    particles->GetPointData()->SetScalars(Ramp(n));
    return particles;
  };
  const auto particleCase = [&](const std::string& name, vtkPolyData* particles, const char* error,
                              bool drawn, double radius, const char* radii)
  {
    return ::RenderCase(window, renderer, name, particles, error, drawn, true,
      [radius, radii](vtkSAVRVolumeMapper* mapper)
      {
        mapper->SetParticleRadius(radius);
        mapper->SetParticleRadiusArrayName(radii);
      });
  };
  {
    failures += !particleCase("no particles", cloud(0, 1.0), "no points", false, 1.0, nullptr);
    auto shortRadii = cloud(500, 0.37);
    auto radii = vtkSmartPointer<vtkDoubleArray>::New();
    radii->SetName("radius");
    radii->SetNumberOfTuples(499);
    radii->Fill(1.5);
    shortRadii->GetPointData()->AddArray(radii);
    failures += !particleCase("a radius array of the wrong length", shortRadii,
      "not one value per point", false, 0.0, "radius");
    auto zeroRadius = cloud(500, 0.37);
    auto someZero = vtkSmartPointer<vtkDoubleArray>::New();
    someZero->SetName("radius");
    someZero->SetNumberOfTuples(500);
    someZero->Fill(1.5);
    someZero->SetValue(42, 0.0);
    zeroRadius->GetPointData()->AddArray(someZero);
    failures += !particleCase(
      "a zero radius", zeroRadius, "the radius of particle 42 is 0", false, 0.0, "radius");
    failures += !particleCase(
      "a missing radius array", cloud(500, 0.37), "no point array 'size'", false, 0.0, "size");
    auto withNaN = cloud(500, 0.37);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    withNaN->GetPoints()->SetPoint(7, nan, 0.0, 0.0);
    withNaN->GetPoints()->SetPoint(9, 0.0, std::numeric_limits<double>::infinity(), 0.0);
    failures += !particleCase(
      "two non-finite positions", withNaN, "2 particles are left out", true, 2.0, nullptr);
    auto coincident = cloud(100000, 0.0);
    failures +=
      !particleCase("100000 coincident particles", coincident, nullptr, true, 4.0, nullptr);
  }

  return failures;
}

} // namespace

int TestSAVRBadInput(int, char*[])
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(120, 120);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);
  const int failures = ImageCases(window, renderer) + MeshAndAMRCases(window, renderer) +
                       ParticleCases(window, renderer);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

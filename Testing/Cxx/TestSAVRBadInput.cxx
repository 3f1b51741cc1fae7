// Bad input gets a clear error and a blank image; partial problems (NaN voxels) render the rest.

#include "SAVRTestScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"

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

// Renders `image` and reports whether an error was raised and how much of the window is covered.
bool RenderCase(const std::string& name, vtkImageData* image, bool expectError, bool expectImage)
{
  savr_scenes::Scene scene(image, 120, 120);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Renderer->ResetCamera(-10, 10, -10, 10, -10, 10);
  ErrorCatcher catcher;
  vtkNew<vtkCallbackCommand> callback;
  callback->SetCallback(CatchError);
  callback->SetClientData(&catcher);
  scene.Mapper->AddObserver(vtkCommand::ErrorEvent, callback);
  scene.Window->Render();
  scene.Window->Render(); // a second frame must not crash or repeat the message
  const double covered = savr_scenes::CoveredFraction(savr_scenes::Capture(scene.Window), scene.Renderer->GetBackground());
  const bool ok = (catcher.Count > 0) == expectError && catcher.Count <= 1 && (covered > 0.01) == expectImage;
  std::cout << (ok ? "ok     " : "FAILED ") << name << ": errors " << catcher.Count << " covered " << covered
            << (catcher.Last.empty() ? "" : " message: ") << catcher.Last << "\n";
  return ok;
}
} // namespace

int TestSAVRBadInput(int, char*[])
{
  int failures = 0;

  auto empty = vtkSmartPointer<vtkImageData>::New();
  failures += !RenderCase("empty image", empty, true, false);

  auto single = Image(1, 1, 1);
  single->GetPointData()->SetScalars(Ramp(1));
  failures += !RenderCase("one voxel", single, true, false);

  auto flat = Image(10, 10, 10, 0.0);
  flat->GetPointData()->SetScalars(Ramp(1000));
  failures += !RenderCase("zero spacing", flat, true, false);

  auto noScalars = Image(10, 10, 10);
  failures += !RenderCase("no scalars", noScalars, true, false);

  auto threeComponents = Image(10, 10, 10);
  threeComponents->GetPointData()->SetScalars(Ramp(1000, 3));
  failures += !RenderCase("three components", threeComponents, true, false);

  auto strings = Image(10, 10, 10);
  vtkNew<vtkStringArray> text;
  text->SetNumberOfValues(1000);
  text->SetName("text");
  strings->GetPointData()->AddArray(text);
  failures += !RenderCase("string array only", strings, true, false);

  auto huge = Image(100000, 100000, 100000);
  huge->GetPointData()->SetScalars(Ramp(1000));
  failures += !RenderCase("dimensions larger than the array", huge, true, false);

  // NaN and Inf voxels are transparent; the rest of the volume renders, with no error.
  auto holes = Image(21, 21, 21);
  auto values = Ramp(21 * 21 * 21);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); i += 7)
  {
    values->SetValue(i, i % 2 ? std::numeric_limits<float>::quiet_NaN() : std::numeric_limits<float>::infinity());
  }
  holes->GetPointData()->SetScalars(values);
  holes->SetOrigin(-10, -10, -10);
  failures += !RenderCase("NaN and Inf voxels", holes, false, true);

  // A sane image renders (the checks above would pass on a mapper that draws nothing).
  auto fine = Image(21, 21, 21);
  fine->SetOrigin(-10, -10, -10);
  fine->GetPointData()->SetScalars(Ramp(21 * 21 * 21));
  failures += !RenderCase("a valid image", fine, false, true);

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

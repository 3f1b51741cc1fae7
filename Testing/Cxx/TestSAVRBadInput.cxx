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

// Renders `image` in `window` (one window for all cases: creating and destroying X windows in
// quick succession makes Xvfb refuse connections now and then) with a fresh mapper, and reports
// whether an error was raised and how much of the window is covered.
bool RenderCase(vtkRenderWindow* window, vtkRenderer* renderer, const std::string& name,
  vtkImageData* image, const char* expectedError, bool expectImage)
{
  vtkNew<vtkSAVRVolumeMapper> mapper;
  mapper->SetInputData(image);
  vtkNew<vtkVolumeProperty> property;
  savr_scenes::WaveletProperty(property);
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
  // A failed input has nothing left to refine, so loops that wait for completion end.
  const bool completes = !expectedError || mapper->GetRefinementComplete();
  const bool ok = errorAsExpected && (covered > 0.01) == expectImage && completes;
  std::cout << (ok ? "ok     " : "FAILED ") << name << ": errors " << catcher.Count << " covered "
            << covered << (message.empty() ? "" : " message: ") << message << "\n";
  renderer->RemoveAllViewProps();
  return ok;
}
} // namespace

int TestSAVRBadInput(int, char*[])
{
  int failures = 0;
  vtkNew<vtkRenderWindow> window;
  window->SetSize(120, 120);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);
  auto RenderCase = [&](const std::string& name, vtkImageData* image, const char* error, bool drawn)
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

  auto threeComponents = Image(10, 10, 10);
  threeComponents->GetPointData()->SetScalars(Ramp(1000, 3));
  failures += !RenderCase("three components", threeComponents, "3 components", false);

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

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

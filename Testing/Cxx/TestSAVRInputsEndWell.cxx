// Every input ends well: no exception leaves Render, the README's loop
// `while (!mapper->GetRefinementComplete()) window->Render();` ends, and data at the edges of
// double's range renders right or is refused with one message naming the problem.
//
// One argument picks the group: "crash", "endless", "extremes", "messages" or "driver".

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellType.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSAVRImageSampler.h"
#include "vtkSAVRRefinementDriver.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <limits>
#include <memory>

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct ErrorCatcher
{
  int Count = 0;
  std::string Last;
};

void CatchError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* catcher = static_cast<ErrorCatcher*>(clientData);
  ++catcher->Count;
  const std::string text = callData ? static_cast<const char*>(callData) : "";
  catcher->Last = text.substr(text.find('\n') + 1);
}

vtkSmartPointer<vtkImageData> Image(int n, double spacing = 1.0)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetSpacing(spacing, spacing, spacing);
  image->SetOrigin(-0.5 * (n - 1) * spacing, -0.5 * (n - 1) * spacing, -0.5 * (n - 1) * spacing);
  return image;
}

// Values from `low` to `high` along x (so that a transfer function over them shows a gradient).
template <typename ArrayT>
vtkSmartPointer<ArrayT> Ramp(vtkIdType n, int nx, double low, double high)
{
  auto array = vtkSmartPointer<ArrayT>::New();
  array->SetName("ramp");
  array->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double t = nx > 1 ? static_cast<double>(i % nx) / (nx - 1) : 0.0;
    // low + t * (high - low) overflows when the two are near opposite ends of double's range.
    array->SetValue(i, static_cast<typename ArrayT::ValueType>((1.0 - t) * low + t * high));
  }
  return array;
}

vtkSmartPointer<vtkImageData> RampImage(int n, double low = 37.0, double high = 276.0)
{
  auto image = Image(n);
  image->GetPointData()->SetScalars(Ramp<vtkDoubleArray>(vtkIdType(n) * n * n, n, low, high));
  return image;
}

// A cube of 8 points and one hexahedron, `size` across, with the values of RampImage's corners.
vtkSmartPointer<vtkUnstructuredGrid> Hexahedron(double size, double low = 37.0, double high = 276.0)
{
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 8; ++i)
  {
    points->InsertNextPoint(
      i & 1 ? size / 2 : -size / 2, i & 2 ? size / 2 : -size / 2, i & 4 ? size / 2 : -size / 2);
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  const vtkIdType hexahedron[8] = { 0, 1, 3, 2, 4, 5, 7, 6 };
  grid->InsertNextCell(VTK_HEXAHEDRON, 8, hexahedron);
  grid->GetPointData()->SetScalars(Ramp<vtkDoubleArray>(8, 2, low, high));
  return grid;
}

// The wavelet's transfer functions spread over [low, high] (in place of [37, 276]).
void SpreadProperty(vtkVolumeProperty* property, double low, double high)
{
  // As (1 - f) low + f high: high - low overflows when the two are near double's ends.
  auto at = [&](double v)
  {
    const double f = (v - 37.0) / (276.0 - 37.0);
    return (1.0 - f) * low + f * high;
  };
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(low, 0.2, 0.2, 0.9);
  color->AddRGBPoint(at(150.0), 0.9, 0.9, 0.3);
  color->AddRGBPoint(high, 0.9, 0.2, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(low, 0.3);
  opacity->AddPoint(high, 0.9);
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetScalarOpacityUnitDistance(1.0);
}

// One window for every case of a group (creating X windows in quick succession makes Xvfb refuse
// connections now and then), a fresh mapper per case.
struct Harness
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  int Failures = 0;

  Harness()
  {
    this->Window->SetSize(120, 120);
    this->Window->SetMultiSamples(0);
    this->Renderer->SetBackground(0.1, 0.1, 0.15);
    this->Window->AddRenderer(this->Renderer);
  }

  struct Case
  {
    vtkNew<vtkSAVRVolumeMapper> Mapper;
    vtkNew<vtkVolumeProperty> Property;
    vtkNew<vtkVolume> Volume;
    ErrorCatcher Errors;
    vtkNew<vtkCallbackCommand> Callback;
  };

  std::unique_ptr<Case> Start(vtkDataObject* input)
  {
    auto c = std::make_unique<Case>();
    c->Mapper->SetInputDataObject(input);
    savr_scenes::WaveletProperty(c->Property);
    c->Volume->SetMapper(c->Mapper);
    c->Volume->SetProperty(c->Property);
    c->Callback->SetCallback(CatchError);
    c->Callback->SetClientData(&c->Errors);
    c->Mapper->AddObserver(vtkCommand::ErrorEvent, c->Callback);
    this->Renderer->RemoveAllViewProps();
    this->Renderer->AddVolume(c->Volume);
    this->Frame(-10, 10);
    return c;
  }

  void Frame(double low, double high)
  {
    vtkNew<vtkCamera> camera;
    this->Renderer->SetActiveCamera(camera);
    this->Renderer->ResetCamera(low, high, low, high, low, high);
    camera->Azimuth(30.0);
    camera->Elevation(20.0);
    this->Renderer->ResetCameraClippingRange(low, high, low, high, low, high);
  }

  /**
   * The README's loop, bounded by `maxRenders`; then checks that it ended, that the mapper
   * raised exactly one error containing `expectedError` (none when null) and whether the image
   * covers the window.
   */
  void Check(const std::string& name, Case& c, const char* expectedError, bool expectImage,
    int maxRenders = 32)
  {
    int renders = 0;
    while (!c.Mapper->GetRefinementComplete() && renders < maxRenders)
    {
      this->Window->Render();
      ++renders;
    }
    const bool ended = c.Mapper->GetRefinementComplete();
    this->Window->Render(); // once more after completion: no new message, no crash
    const double covered = savr_scenes::CoveredFraction(
      savr_scenes::Capture(this->Window), this->Renderer->GetBackground());
    const bool errorAsExpected =
      expectedError ? c.Errors.Count == 1 && c.Errors.Last.find(expectedError) != std::string::npos
                    : c.Errors.Count == 0;
    const bool ok = ended && errorAsExpected && (covered > 0.01) == expectImage;
    std::cout << (ok ? "ok     " : "FAILED ") << name << ": renders " << renders
              << (ended ? " (complete)" : " (NOT complete)") << ", errors " << c.Errors.Count
              << ", covered " << covered
              << (c.Errors.Last.empty() ? "" : ", last message: " + c.Errors.Last) << "\n";
    this->Failures += !ok;
    this->Renderer->RemoveAllViewProps();
  }

  void Expect(const std::string& name, bool ok)
  {
    std::cout << (ok ? "ok     " : "FAILED ") << name << "\n";
    this->Failures += !ok;
  }
};

// Images whose point count overflows: refused from the extent, never allocated for.
void Crash(Harness& h)
{
  for (int log2 : { 21, 22 })
  {
    auto huge = vtkSmartPointer<vtkImageData>::New();
    huge->SetDimensions(1 << log2, 1 << log2, 1 << log2);
    huge->GetPointData()->SetScalars(Ramp<vtkFloatArray>(1000, 10, 37.0, 276.0));
    auto c = h.Start(huge);
    h.Check("2^" + std::to_string(log2) + " points per axis, 1000 values", *c,
      "shorter than the image", false);
  }
}

void Endless(Harness& h)
{
  {
    auto image = RampImage(21);
    image->SetOrigin(kNaN, 0, 0);
    auto c = h.Start(image);
    h.Check("NaN origin", *c, "not finite", false);
  }
  {
    auto image = RampImage(21);
    image->SetSpacing(1, kNaN, 1);
    auto c = h.Start(image);
    h.Check("NaN spacing", *c, "not finite", false);
  }
  {
    // A cell 1e-30 across, the camera framing it: VTK culls it without calling Render.
    auto c = h.Start(Hexahedron(1e-30));
    h.Frame(-1e-30, 1e-30);
    h.Check("unstructured points about 1e-30", *c, "too small", false);
  }
  {
    auto c = h.Start(nullptr);
    h.Check("input never set", *c, "no input", false);
  }
  {
    auto c = h.Start(RampImage(21));
    h.Window->Render();
    c->Mapper->SetInputDataObject(nullptr);
    h.Check("input removed with SetInputDataObject(nullptr)", *c, "no input", false);
  }
  {
    auto c = h.Start(RampImage(21));
    h.Window->Render();
    c->Mapper->RemoveAllInputConnections(0);
    h.Check("input removed with RemoveAllInputConnections", *c, "no input", false);
  }
  {
    auto c = h.Start(nullptr);
    c->Mapper->SetInputData(Hexahedron(20.0));
    h.Check("SetInputData(vtkUnstructuredGrid*)", *c, nullptr, true);
  }
  {
    vtkSmartPointer<vtkDataSet> grid = Hexahedron(20.0);
    auto c = h.Start(nullptr);
    c->Mapper->SetInputData(grid);
    h.Check("SetInputData(vtkDataSet*) of an unstructured grid", *c, nullptr, true);
  }
  {
    auto c = h.Start(RampImage(21));
    c->Mapper->CroppingOn();
    c->Mapper->SetCroppingRegionPlanes(-5, 5, -5, kNaN, -5, 5);
    h.Check("NaN cropping plane", *c, "cropping", false);
  }
  {
    auto c = h.Start(RampImage(21));
    c->Mapper->SetSampleDistance(std::numeric_limits<double>::infinity());
    h.Check("infinite sample distance", *c, "sample distance", false);
  }
}

void Extremes(Harness& h)
{
  const double big = 1.7e308;
  {
    auto c = h.Start(RampImage(21, -big, big));
    SpreadProperty(c->Property, -big, big);
    h.Check("image of doubles from -1.7e308 to 1.7e308", *c, "range", false);
  }
  {
    auto c = h.Start(Hexahedron(20.0, -big, big));
    SpreadProperty(c->Property, -big, big);
    h.Check("unstructured doubles from -1.7e308 to 1.7e308", *c, "range", false);
  }
  {
    auto c = h.Start(RampImage(21, 0.0, 1e-310));
    SpreadProperty(c->Property, 0.0, 1e-310);
    h.Check("image of denormal doubles up to 1e-310", *c, "range", false);
  }
  {
    auto c = h.Start(Hexahedron(20.0, 0.0, 1e-310));
    SpreadProperty(c->Property, 0.0, 1e-310);
    h.Check("unstructured denormal doubles up to 1e-310", *c, "range", false);
  }
  // Samples are floats: values to tell apart beyond a float's range are refused with the
  // reason; beyond the transfer functions' nodes, values take their ends', and draw.
  {
    auto c = h.Start(RampImage(21, 1e300, 2e300));
    SpreadProperty(c->Property, 1e300, 2e300);
    h.Check("image of doubles from 1e300 to 2e300", *c, "float", false);
  }
  {
    auto c = h.Start(RampImage(21, -big, big));
    SpreadProperty(c->Property, -1.0, 1.0);
    h.Check("image of doubles from -1.7e308 to 1.7e308, functions over [-1, 1]", *c, nullptr, true);
  }
  {
    auto c = h.Start(RampImage(21, 1e300, 2e300));
    SpreadProperty(c->Property, -1.0, 1.0);
    h.Check("image of doubles from 1e300 to 2e300, functions over [-1, 1]", *c, nullptr, true);
  }
  {
    auto c = h.Start(RampImage(21));
    c->Property->GetRGBTransferFunction(0)->AddRGBPoint(kNaN, 1, 1, 1);
    h.Check("NaN value in the colour function", *c, "transfer function", false);
  }
  {
    auto c = h.Start(RampImage(21));
    c->Property->GetRGBTransferFunction(0)->AddRGBPoint(200.0, kNaN, 0.5, 0.5);
    h.Check("NaN colour in the colour function", *c, "transfer function", false);
  }
  {
    auto c = h.Start(RampImage(21));
    c->Property->GetScalarOpacity(0)->AddPoint(200.0, kNaN);
    h.Check("NaN opacity in the opacity function", *c, "transfer function", false);
  }
}

// A 32 x 32 x 400 ramp seen end-on, filling a 512 x 512 window: one frame at the voxel spacing
// would take more than 2^26 samples, so the step is coarsened. A step the mapper chose itself
// (SampleDistance 0) is reported as state only; a step the user set is warned about once.
void CoarsenedSteps(Harness& h)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(32, 32, 400);
  image->SetOrigin(-15.5, -15.5, -199.5);
  const vtkIdType points = vtkIdType(32) * 32 * 400;
  image->GetPointData()->SetScalars(Ramp<vtkDoubleArray>(points, 32, 37.0, 276.0));
  h.Window->SetSize(512, 512);
  for (const bool userStep : { false, true })
  {
    auto c = h.Start(image);
    ErrorCatcher warnings;
    vtkNew<vtkCallbackCommand> onWarning;
    onWarning->SetCallback(CatchError);
    onWarning->SetClientData(&warnings);
    c->Mapper->AddObserver(vtkCommand::WarningEvent, onWarning);
    if (userStep)
    {
      c->Mapper->SetSampleDistance(1.0); // the default's value, set by the user
    }
    vtkCamera* camera = h.Renderer->GetActiveCamera();
    camera->ParallelProjectionOn();
    camera->SetPosition(0, 0, 1000);
    camera->SetFocalPoint(0, 0, 0);
    camera->SetViewUp(0, 1, 0);
    camera->SetParallelScale(14.0); // the cross-section covers the window
    h.Renderer->ResetCameraClippingRange();
    h.Window->Render();
    h.Window->Render();
    const std::string what = (userStep ? "a step the user set" : "the default step");
    h.Expect(
      what + " is coarsened (" + std::to_string(c->Mapper->GetEffectiveSampleDistance()) + ")",
      c->Mapper->GetEffectiveSampleDistance() >= 2.0 && c->Errors.Count == 0);
    h.Expect(what + (userStep ? " warns once" : " warns nothing") + " (warnings: " +
               std::to_string(warnings.Count) + (warnings.Count ? ", " + warnings.Last : "") + ")",
      warnings.Count == (userStep ? 1 : 0));
  }
  h.Window->SetSize(120, 120);
}

void Messages(Harness& h)
{
  CoarsenedSteps(h);
  {
    auto c = h.Start(RampImage(21));
    h.Renderer->GetActiveCamera()->SetPosition(0, 0, 50);
    h.Renderer->GetActiveCamera()->SetFocalPoint(0, 0, 0);
    h.Renderer->GetActiveCamera()->SetViewUp(0, 0, 1);
    h.Check("view-up parallel to the view direction", *c, "view-up is parallel", false);
  }
  {
    auto c = h.Start(RampImage(21));
    vtkCamera* camera = h.Renderer->GetActiveCamera();
    // VTK keeps the focal point off the position; set both through the view transform.
    camera->SetPosition(0, 0, 50);
    camera->SetFocalPoint(0, 0, 50);
    h.Check("camera at its focal point", *c, "focal point", false);
  }
  {
    auto c = h.Start(RampImage(21));
    h.Renderer->GetActiveCamera()->SetClippingRange(0.0, 100.0);
    h.Check("near plane at 0", *c, "near plane", false);
  }
  {
    auto image = RampImage(21);
    image->SetOrigin(1e30, 1e30, 1e30);
    auto c = h.Start(image);
    h.Frame(1e30 - 10, 1e30 + 10);
    h.Check("data at 1e30", *c, "far from the origin", false);
  }
  {
    auto c = h.Start(RampImage(21));
    c->Mapper->SetSampleDistance(1e-9);
    h.Check("tiny sample distance", *c, "1e-09", false);
  }
  {
    // The image sampler holds the array it samples in place.
    auto image = RampImage(5);
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    vtkNew<vtkSAVRImageSampler> sampler;
    const int before = scalars->GetReferenceCount();
    sampler->Build(image, scalars, false, nullptr, VTK_LINEAR_INTERPOLATION);
    h.Expect("the image sampler holds its array", scalars->GetReferenceCount() == before + 1);
  }
}
struct TickCounts
{
  int Ticks = 0;
  int Renders = 0;
  // Renders while the observers of one TimerEvent run, and the most of any tick: renders between
  // ticks (the loop's start, expose events, more of them on a busy machine) are not a tick's.
  bool InTick = false;
  int TickRenders = 0;
  int MostInOneTick = 0;
  std::chrono::steady_clock::time_point Until;
};

// Runs the interactor's event loop until `until` passes; counts its timer events and renders.
TickCounts RunLoop(vtkRenderWindowInteractor* interactor, double seconds)
{
  TickCounts counts;
  counts.Until =
    std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<int>(1000 * seconds));
  vtkNew<vtkCallbackCommand> onTick;
  onTick->SetClientData(&counts);
  onTick->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void*)
    {
      auto* c = static_cast<TickCounts*>(clientData);
      ++c->Ticks;
      c->InTick = true;
      c->TickRenders = 0;
      if (std::chrono::steady_clock::now() > c->Until)
      {
        static_cast<vtkRenderWindowInteractor*>(caller)->TerminateApp();
      }
    });
  vtkNew<vtkCallbackCommand> onTickEnd;
  onTickEnd->SetClientData(&counts);
  onTickEnd->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*)
    {
      auto* c = static_cast<TickCounts*>(clientData);
      c->InTick = false;
      c->MostInOneTick = std::max(c->MostInOneTick, c->TickRenders);
    });
  vtkNew<vtkCallbackCommand> onRender;
  onRender->SetClientData(&counts);
  onRender->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*)
    {
      auto* c = static_cast<TickCounts*>(clientData);
      ++c->Renders;
      c->TickRenders += c->InTick;
    });
  // Before and after the drivers' observers: a tick's renders are counted between the two.
  const unsigned long tickTag = interactor->AddObserver(vtkCommand::TimerEvent, onTick, 1.0f);
  const unsigned long tickEndTag =
    interactor->AddObserver(vtkCommand::TimerEvent, onTickEnd, -1.0f);
  const unsigned long renderTag =
    interactor->GetRenderWindow()->AddObserver(vtkCommand::StartEvent, onRender);
  interactor->SetDone(false); // the last loop's TerminateApp would end this one at once
  interactor->Start();
  interactor->RemoveObserver(tickTag);
  interactor->RemoveObserver(tickEndTag);
  interactor->GetRenderWindow()->RemoveObserver(renderTag);
  return counts;
}

// Two volumes in two viewports of one window, each mapper with its own refinement driver on the
// one interactor: each tick renders the window once at most, a foreign timer renders nothing,
// and SetTimerInterval after attaching takes effect.
void Driver(Harness& h)
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(10);
  h.Window->SetSize(240, 120);
  h.Renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
  vtkNew<vtkRenderer> right;
  right->SetViewport(0.5, 0.0, 1.0, 1.0);
  h.Window->AddRenderer(right);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(h.Window);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  interactor->Initialize();

  auto left = h.Start(data);
  left->Mapper->SetMaximumNumberOfFrames(64);
  vtkNew<vtkVolume> rightVolume;
  vtkNew<vtkSAVRVolumeMapper> rightMapper;
  rightMapper->SetInputData(data);
  rightMapper->SetMaximumNumberOfFrames(64);
  rightVolume->SetMapper(rightMapper);
  rightVolume->SetProperty(left->Property);
  right->AddVolume(rightVolume);
  right->ResetCamera();
  h.Window->Render();

  vtkNew<vtkSAVRRefinementDriver> drivers[2];
  drivers[0]->SetMapper(left->Mapper);
  drivers[1]->SetMapper(rightMapper);
  for (auto& driver : drivers)
  {
    driver->SetInteractor(interactor);
  }

  TickCounts foreign;
  vtkNew<vtkCallbackCommand> onRender;
  onRender->SetClientData(&foreign);
  onRender->SetCallback([](vtkObject*, unsigned long, void* clientData, void*)
    { ++static_cast<TickCounts*>(clientData)->Renders; });
  h.Window->AddObserver(vtkCommand::StartEvent, onRender);
  int someoneElsesTimer = -7;
  interactor->InvokeEvent(vtkCommand::TimerEvent, &someoneElsesTimer);
  h.Window->RemoveObserver(onRender);
  h.Expect("a timer the drivers did not create renders nothing (renders: " +
             std::to_string(foreign.Renders) + ")",
    foreign.Renders == 0);

  // A second event loop on this interactor ends at once under Xvfb: measure both in one.
  for (auto& driver : drivers)
  {
    driver->SetTimerInterval(100);
  }
  const TickCounts ticks = RunLoop(interactor, 1.0);
  const std::string counts = " (ticks " + std::to_string(ticks.Ticks) + ", renders " +
                             std::to_string(ticks.Renders) + ", most in one tick " +
                             std::to_string(ticks.MostInOneTick) + ")";
  // At 10 ms, two drivers tick some 40 times in a second even with renders in between.
  h.Expect("SetTimerInterval(100) after attaching slows the ticks" + counts,
    ticks.Ticks > 0 && ticks.Ticks <= 24);
  h.Expect("each tick renders once at most" + counts, ticks.MostInOneTick == 1);
  for (auto& driver : drivers)
  {
    driver->SetInteractor(nullptr);
  }
  h.Window->RemoveRenderer(right);
}
} // namespace

int TestSAVRInputsEndWell(int argc, char* argv[])
{
  Harness harness;
  const std::string group = argc > 1 ? argv[1] : "";
  if (group == "crash")
  {
    Crash(harness);
  }
  else if (group == "endless")
  {
    Endless(harness);
  }
  else if (group == "extremes")
  {
    Extremes(harness);
  }
  else if (group == "messages")
  {
    Messages(harness);
  }
  else if (group == "driver")
  {
    Driver(harness);
  }
  else
  {
    std::cerr << "usage: TestSAVRInputsEndWell crash|endless|extremes|messages|driver\n";
    return EXIT_FAILURE;
  }
  return harness.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

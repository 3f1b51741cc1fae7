// Bounded time, whatever the settings: one Render takes a bounded number of samples however
// small SampleDistance is.
//
// One argument picks the group: "time"; a second, optional, the window's edge in pixels (160 by
// default).

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkPointData.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
savr_scenes::Expectations Expect;

// What the mapper promises one frame takes at most: 2^24 samples over the rays' lengths, plus one
// per ray.
constexpr double kSamplesPerFrame = double(1 << 24);
// A hang is what this bounds, not speed: one such frame takes well under a second here.
constexpr double kSecondsPerRender = 10.0;

struct Messages
{
  int Errors = 0;
  int Warnings = 0;
  std::string Last;
};

void CatchMessage(vtkObject*, unsigned long event, void* clientData, void* callData)
{
  auto* messages = static_cast<Messages*>(clientData);
  ++(event == vtkCommand::ErrorEvent ? messages->Errors : messages->Warnings);
  const std::string text = callData ? static_cast<const char*>(callData) : "";
  messages->Last = text.substr(text.find('\n') + 1);
}

// A 21^3 ramp of doubles, 1 unit apart, centred on the origin.
vtkSmartPointer<vtkImageData> RampImage()
{
  const int n = 21;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  image->SetOrigin(-0.5 * (n - 1), -0.5 * (n - 1), -0.5 * (n - 1));
  vtkNew<vtkDoubleArray> values;
  values->SetNumberOfTuples(vtkIdType(n) * n * n);
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetValue(i, 37.0 + (276.0 - 37.0) * static_cast<double>(i % n) / (n - 1));
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

struct Watched
{
  Messages Caught;
  vtkNew<vtkCallbackCommand> Callback;
  explicit Watched(vtkSAVRVolumeMapper* mapper)
  {
    this->Callback->SetCallback(CatchMessage);
    this->Callback->SetClientData(&this->Caught);
    mapper->AddObserver(vtkCommand::ErrorEvent, this->Callback);
    mapper->AddObserver(vtkCommand::WarningEvent, this->Callback);
  }
};

double Seconds(std::chrono::steady_clock::time_point since)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

std::string Number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

// A step far finer than the frame can afford: one Render samples at a coarser step (saying so
// once), refinement ends within the frame limit, and the refined image is the image of a
// normal step refined as far.
void Time(int edge)
{
  vtkSmartPointer<vtkImageData> image = RampImage();
  savr_scenes::Scene reference(image, edge, edge);
  savr_scenes::WaveletProperty(reference.Property);
  reference.Mapper->SetSampleDistance(0.25);
  reference.Mapper->SetMaximumNumberOfFrames(64);
  while (!reference.Mapper->GetRefinementComplete())
  {
    reference.Window->Render();
  }
  vtkSmartPointer<vtkImageData> converged = savr_scenes::Capture(reference.Window);

  for (const double step : { 4e-5, 1e-5 })
  {
    savr_scenes::Scene scene(image, edge, edge);
    savr_scenes::WaveletProperty(scene.Property);
    scene.Renderer->SetActiveCamera(reference.Renderer->GetActiveCamera());
    Watched watched(scene.Mapper);
    scene.Mapper->SetSampleDistance(step);
    const std::string name = "SampleDistance " + Number(step) + " at " + std::to_string(edge) +
                             "x" + std::to_string(edge) + ": ";
    const auto start = std::chrono::steady_clock::now();
    scene.Window->Render();
    const double seconds = Seconds(start);
    const double samples = static_cast<double>(scene.Mapper->GetNumberOfSamplesTaken());
    const double used = scene.Mapper->GetEffectiveSampleDistance();
    std::cout << name << "first Render " << seconds << " s, " << samples << " samples, step "
              << used << ", frame limit " << scene.Mapper->GetFrameLimit()
              << "; warning: " << watched.Caught.Last << "\n";
    Expect(samples <= kSamplesPerFrame + double(edge) * edge,
      name + "one frame takes at most 2^24 samples plus one per pixel");
    Expect(seconds < kSecondsPerRender, name + "one Render returns within seconds");
    Expect(used > step && watched.Caught.Warnings == 1 && watched.Caught.Errors == 0 &&
             watched.Caught.Last.find(Number(step)) != std::string::npos &&
             watched.Caught.Last.find(Number(used)) != std::string::npos,
      name + "one warning names the step asked and the step used");

    // The README's loop ends, each frame bounded, and no second warning for the same setting.
    int renders = 1;
    double slowest = seconds;
    while (!scene.Mapper->GetRefinementComplete() && renders < (1 << 16))
    {
      const auto frameStart = std::chrono::steady_clock::now();
      scene.Window->Render();
      slowest = std::max(slowest, Seconds(frameStart));
      ++renders;
    }
    const double estimate = scene.Mapper->GetErrorEstimate();
    const savr_scenes::Difference difference =
      savr_scenes::Compare(savr_scenes::Capture(scene.Window), converged);
    std::cout << name << renders << " renders (frame limit " << scene.Mapper->GetFrameLimit()
              << ", slowest " << slowest << " s), error estimate " << estimate
              << ", against step 0.25 / 64: mean " << difference.Mean << " max " << difference.Max
              << " levels\n";
    Expect(scene.Mapper->GetRefinementComplete() && renders <= scene.Mapper->GetFrameLimit(),
      name + "refinement ends at the frame limit");
    Expect(slowest < kSecondsPerRender && watched.Caught.Warnings == 1,
      name + "every frame is bounded, and the warning is not repeated");
    Expect(estimate >= 0.0 && estimate < 0.01 && difference.Mean < 0.5 && difference.Max <= 8.0,
      name + "the refined image converged (the estimate says so, and a reference agrees)");
  }
}

} // namespace

int TestSAVRBudgets(int argc, char* argv[])
{
  const std::string group = argc > 1 ? argv[1] : "";
  const int edge = argc > 2 ? std::atoi(argv[2]) : 0;
  if (group == "time")
  {
    Time(edge > 0 ? edge : 160);
  }
  else
  {
    std::cerr << "usage: TestSAVRBudgets time [edge]\n";
    return EXIT_FAILURE;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

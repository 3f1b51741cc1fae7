// Bounded time and memory, whatever the settings: one Render takes a bounded number of samples
// however small SampleDistance is, and MemoryBudget bounds all the memory the mapper adds, its
// per-pixel images and display included.
//
// One argument picks the group: "time" or "memory"; a second, optional, the window's edge in
// pixels ("time": 160 by default; "memory": 1024 and 8192).

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
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace
{
savr_scenes::Expectations Expect;

// What the mapper promises one frame takes at most: 2^26 samples over the rays' lengths, plus one
// per ray.
constexpr double kSamplesPerFrame = double(1 << 26);
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
      name + "one frame takes at most 2^26 samples plus one per pixel");
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

// The largest resident memory since the last ResetPeak (VmHWM), in MiB.
double PeakResidentMiB()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.compare(0, 6, "VmHWM:") == 0)
    {
      return std::stod(line.substr(6)) / 1024.0;
    }
  }
  return 0.0;
}

// Makes the peak the current resident memory (Linux: "5" to clear_refs).
bool ResetPeak()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return clear.good();
}

// The peak resident memory the mapper's renders add, over that of the window's own renders
// (measured with the volume hidden; an offscreen 8192x8192 window takes about 2.1 GiB, 4096x4096
// about 0.5 GiB, its framebuffers and the driver's), must stay within MemoryBudget plus a slack.
// When the images alone do not fit the budget, one error says so and nothing is drawn.
void Memory(int edge)
{
  constexpr double budgetMiB = 256.0;
  // What the first volume render loads besides the mapper's own memory, whatever the window's
  // size: code, the driver's compiled shaders, the transfer-function tables (measured: about
  // 31 MiB at 512x512, 29 MiB at 1024x1024).
  constexpr double slackMiB = 48.0;
  savr_scenes::Scene scene(savr_scenes::Wavelet(20), edge, edge);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Window->SetOffScreenRendering(1);
  scene.Mapper->SetMemoryBudget(vtkTypeUInt64(budgetMiB) << 20);
  Watched watched(scene.Mapper);
  scene.Volume->VisibilityOff();
  const double start = PeakResidentMiB();
  scene.Window->Render();
  scene.Window->Render();
  if (!ResetPeak())
  {
    std::cout << "cannot reset the peak resident memory (/proc/self/clear_refs)\n";
    ++Expect.Failures;
    return;
  }
  const double withWindow = PeakResidentMiB();
  scene.Volume->VisibilityOn();
  int renders = 0;
  while (!scene.Mapper->GetRefinementComplete() && renders < 64)
  {
    scene.Window->Render();
    ++renders;
  }
  const double growth = PeakResidentMiB() - withWindow;
  const std::string name = std::to_string(edge) + "x" + std::to_string(edge) + ": ";
  std::cout << name << "MemoryBudget " << budgetMiB << " MiB; VTK's window " << withWindow - start
            << " MiB; the mapper's " << renders << " renders add at most " << growth << " MiB ("
            << 1048576.0 * growth / (double(edge) * edge) << " bytes per pixel); image memory "
            << scene.Mapper->GetImageMemoryInUse() / 1048576.0 << " MiB, samples "
            << scene.Mapper->GetMemoryInUse() / 1048576.0 << " MiB, frames "
            << scene.Mapper->GetNumberOfFramesAccumulated() << "\n"
            << "  message: " << watched.Caught.Last << "\n";
  Expect(growth < budgetMiB + slackMiB, name + "the mapper's memory stays within the budget");
  Expect(scene.Mapper->GetRefinementComplete(), name + "refinement ends");
  Expect(scene.Mapper->GetImageMemoryInUse() + scene.Mapper->GetMemoryInUse() <=
           (vtkTypeUInt64(budgetMiB) << 20),
    name + "the memory the mapper counts is within the budget");
  if (scene.Mapper->GetNumberOfFramesAccumulated() == 0)
  {
    Expect(watched.Caught.Errors == 1 && watched.Caught.Last.find(std::to_string(
                                           vtkTypeUInt64(budgetMiB) << 20)) != std::string::npos,
      name + "one error names the budget");
    Expect(savr_scenes::CoveredFraction(
             savr_scenes::Capture(scene.Window), scene.Renderer->GetBackground()) == 0.0,
      name + "nothing is drawn");
  }
  else
  {
    Expect(watched.Caught.Errors == 0 && scene.Mapper->GetNumberOfFramesAccumulated() > 1,
      name + "frames accumulate without an error when the images fit");
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
  else if (group == "memory")
  {
    // Images that fit the budget with room for samples, then images that do not.
    for (const int size : { 1024, 8192 })
    {
      Memory(edge > 0 ? edge : size);
      if (edge > 0)
      {
        break;
      }
    }
  }
  else
  {
    std::cerr << "usage: TestSAVRBudgets time|memory [edge]\n";
    return EXIT_FAILURE;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

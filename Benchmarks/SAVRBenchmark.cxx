// Benchmark: vtkSAVRVolumeMapper next to vtkFixedPointVolumeRayCastMapper on the MRI head, in one
// run, same window size, camera and step. Prints medians (seconds per whole Render()) and ratios.
//
//   savr_benchmark [--size 512] [--repeats 9] [--step 1.0] [--shade 0] [--opaque 0]

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"

#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

using savr_benchmarks::Median;
using savr_benchmarks::Seconds;

namespace
{
/// Every measurement of one run, as whole Render() calls in seconds.
struct Timings
{
  std::vector<double> FixedStep;
  std::vector<double> FixedQuarter;
  std::vector<double> Interacting;
  std::vector<double> InteractingQuarter;
  std::vector<double> FirstAccumulating;
  std::vector<double> LaterAccumulating;
  // The exact pass the refined image equals, measured next to each refinement: one frame at a
  // quarter of the step, every sample of every ray taken and stored (no early termination, no
  // skipping).
  std::vector<double> ExactQuarter;
  std::vector<double> Refine;
  std::vector<double> RefineOverExact;
  std::vector<double> Reuse;
  std::vector<double> Reblend;
  double FirstFrame = 0.0;
  double BytesPerSample = 0.0;
  double MemoryMiB = 0.0;
};

/// One row of the table: a measurement's median and, when `reference` is positive, its ratio to
/// it; a negative `seconds` leaves the seconds column empty.
void Row(const char* what, double seconds, double reference)
{
  char secondsText[32] = "";
  char ratioText[32] = "";
  if (seconds >= 0.0)
  {
    std::snprintf(secondsText, sizeof(secondsText), "%.4f", seconds);
  }
  if (reference > 0.0)
  {
    std::snprintf(ratioText, sizeof(ratioText), "%.2f", seconds / reference);
  }
  std::printf("%-58s %10s %10s\n", what, secondsText, ratioText);
}

void PrintReport(const Timings& t)
{
  const double fixedStep = Median(t.FixedStep);
  const double fixedQuarter = Median(t.FixedQuarter);
  const double interacting = Median(t.Interacting);
  const double quarter = Median(t.InteractingQuarter);
  const double exact = Median(t.ExactQuarter);
  const double refine = Median(t.Refine);
  std::printf(
    "\n%-58s %10s %10s\n", "measurement (median of whole Render() calls)", "seconds", "ratio");
  Row("fixed point, step 1x", fixedStep, fixedStep);
  Row("fixed point, step 1/4x", fixedQuarter, fixedStep);
  Row("SAVR interacting frame, step 1x (vs fixed point 1x)", interacting, fixedStep);
  Row("SAVR first accumulating frame (vs interacting)", Median(t.FirstAccumulating), interacting);
  Row("SAVR later accumulating frames (vs interacting)", Median(t.LaterAccumulating), interacting);
  Row("SAVR interacting pass, step 1/4x", quarter, quarter);
  Row("SAVR exact single pass, step 1/4x (vs interacting 1/4x)", exact, quarter);
  Row("SAVR refine to 4 frames, step 1/4x (vs interacting 1/4x)", refine, quarter);
  Row("SAVR refine to 4 frames, step 1/4x (vs exact pass 1/4x)", refine, exact);
  std::printf("%-58s %10s %10.2f\n", "  the same, median of each refinement over its exact pass",
    "", Median(t.RefineOverExact));
  Row("SAVR refine to 4 frames (vs fixed point 1/4x)", refine, fixedQuarter);
  Row("SAVR frame after completion, nothing changed", Median(t.Reuse), 0.0);
  Row("SAVR transfer-function re-blend (vs interacting)", Median(t.Reblend), interacting);
  Row("SAVR first frame of the data (vs fixed point 1x)", t.FirstFrame, fixedStep);
  std::printf("%-58s %10.2f %10s\n", "SAVR stored-sample memory, MiB", t.MemoryMiB, "");
  std::printf("%-58s %10.3f %10s\n", "SAVR bytes per stored sample", t.BytesPerSample, "");
}

/// Interacting frames with the window's DesiredUpdateRate at `rate`: each mapper keeps within
/// the time VTK allocates the volume by its own means (the fixed-point mapper's
/// AutoAdjustSampleDistances, on by default, coarsens its sampling and image; SAVR's its step,
/// then its pixels per ray).
/// The first frames let both settle; then the two are measured alternately.
int InteractingAtRate(savr_scenes::Scene& scene, vtkFixedPointVolumeRayCastMapper* fixedPoint,
  const std::function<void(bool)>& show, double step, double rate, int repeats)
{
  vtkSAVRVolumeMapper* savr = scene.Mapper;
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  fixedPoint->AutoAdjustSampleDistancesOn();
  fixedPoint->SetSampleDistance(step);
  savr->SetSampleDistance(step);
  savr->InteractiveOn();
  scene.Window->SetDesiredUpdateRate(rate);
  std::vector<double> peerTimes;
  std::vector<double> savrTimes;
  for (int r = -4; r < repeats; ++r)
  {
    camera->Azimuth(0.5);
    show(false);
    const double peer = Seconds([&] { scene.Window->Render(); });
    show(true);
    const double ours = Seconds([&] { scene.Window->Render(); });
    if (r >= 0)
    {
      peerTimes.push_back(peer);
      savrTimes.push_back(ours);
    }
  }
  const double peer = Median(peerTimes);
  const double ours = Median(savrTimes);
  std::printf(
    "interacting at DesiredUpdateRate %g (%.3f s a frame for the window):\n", rate, 1.0 / rate);
  std::printf("  vtkFixedPointVolumeRayCastMapper (AutoAdjustSampleDistances) %8.3f s\n", peer);
  const int stride = savr->GetInteractivePixelStride();
  std::printf("  SAVR single pass (AutoAdjustSampleDistances, step %.2f base steps, %dx%d pixels a "
              "ray) %8.3f s  ratio %.2f\n",
    savr->GetInteractiveSampleDistance() / savr->GetEffectiveSampleDistance(), stride, stride, ours,
    ours / peer);
  return EXIT_SUCCESS;
}
struct Options
{
  int Size = 512;
  int Repeats = 9;
  double Step = 1.0;
  int Shade = 0;
  int Opaque = 0;
  double Rate = 0.0;
  std::string File;
};

// The command line into `o`; false (with the exit code in `code`) for --help or a bad option.
bool ParseOptions(int argc, char* argv[], Options& o, int& code)
{
  savr_scenes::Arguments arguments(argc, argv,
    "savr_benchmark: vtkSAVRVolumeMapper next to vtkFixedPointVolumeRayCastMapper on the MRI "
    "head;\nprints medians of whole Render() calls and their ratios.");
  arguments.Option("--size", &o.Size, "Window width and height in pixels (512).");
  arguments.Option("--repeats", &o.Repeats, "Measurements of each kind (9).");
  arguments.Option("--step", &o.Step, "Base sample distance in world units (1.0).");
  arguments.Option("--shade", &o.Shade,
    "1 lights both mappers (ambient 0.2, diffuse 0.7, specular 0.3, power 12), 0 not (0).");
  arguments.Option("--opaque", &o.Opaque,
    "1 makes the skin and bone opaque (opacity 0 to 40, 0.5 at 70, 1 from 100), so that rays end "
    "early, 0 keeps the default translucent transfer function (0).");
  arguments.Option("--rate", &o.Rate,
    "With a rate R > 0, only interacting frames at the window's DesiredUpdateRate R (what VTK's "
    "interactor styles set during a drag), both mappers adjusting their sample distances to the "
    "time it allocates (0).");
  arguments.Option("--file", &o.File,
    "A NIfTI image (.nii or .nii.gz) instead of the MRI head (its transfer function).");
  if (!arguments.Parse())
  {
    code = arguments.ExitCode();
    return false;
  }
  return true;
}

// The MRI head, or the image in `file`; null (with a message) when it cannot be read or is empty.
vtkSmartPointer<vtkImageData> LoadVolume(const std::string& file)
{
  vtkSmartPointer<vtkImageData> head;
  if (file.empty())
  {
    head = savr_scenes::Head();
  }
  else
  {
    std::string error;
    head = vtkImageData::SafeDownCast(savr_scenes::ReadDataFile(file, error));
    if (!head)
    {
      std::fprintf(stderr, "savr_benchmark: %s: %s\n", file.c_str(), error.c_str());
      return nullptr;
    }
  }
  return head->GetNumberOfPoints() > 0 ? head : nullptr;
}

// The head's transfer function, made opaque and lit as the options ask.
void ConfigureProperty(vtkVolumeProperty* property, const Options& o)
{
  savr_scenes::HeadProperty(property);
  if (o.Opaque)
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(40.0, 0.0);
    opacity->AddPoint(70.0, 0.5);
    opacity->AddPoint(100.0, 1.0);
    opacity->AddPoint(255.0, 1.0);
    property->SetScalarOpacity(opacity);
  }
  if (o.Shade)
  {
    property->ShadeOn();
    property->SetAmbient(0.2);
    property->SetDiffuse(0.7);
    property->SetSpecular(0.3);
    property->SetSpecularPower(12.0);
  }
}

// SAVR and the peer, each in its own volume of the same window: the two are measured
// alternately, frame by frame, so that both see the same machine load.
struct SideBySide
{
  savr_scenes::Scene& Scene;
  vtkFixedPointVolumeRayCastMapper* FixedPoint;
  vtkVolume* Peer;

  void Show(bool savrVisible)
  {
    this->Scene.Volume->SetVisibility(savrVisible);
    this->Peer->SetVisibility(!savrVisible);
  }
  double RenderPeer(double sampleDistance)
  {
    this->Show(false);
    this->FixedPoint->SetSampleDistance(sampleDistance);
    return Seconds([&] { this->Scene.Window->Render(); });
  }
  double RenderSavr()
  {
    this->Show(true);
    return Seconds([&] { this->Scene.Window->Render(); });
  }
};

// Interacting frames: single passes at the base step while the camera moves, next to the peer
// at the same step; then our single pass at a quarter of the step.
void MeasureInteracting(SideBySide& bench, double step, int repeats, Timings& t)
{
  vtkSAVRVolumeMapper* savr = bench.Scene.Mapper;
  vtkCamera* camera = bench.Scene.Renderer->GetActiveCamera();
  savr->InteractiveOn();
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(0.5);
    t.FixedStep.push_back(bench.RenderPeer(step));
    savr->SetSampleDistance(step);
    t.Interacting.push_back(bench.RenderSavr());
    savr->SetSampleDistance(step / 4);
    t.InteractingQuarter.push_back(bench.RenderSavr());
  }
  savr->InteractiveOff();
  savr->SetSampleDistance(step);
}

// Accumulation to 4 frames (quarter step) next to the peer at a quarter step and to the exact
// pass it equals, then reuse and re-blend.
void MeasureRefinement(SideBySide& bench, double step, int repeats, Timings& t)
{
  vtkSAVRVolumeMapper* savr = bench.Scene.Mapper;
  vtkCamera* camera = bench.Scene.Renderer->GetActiveCamera();
  vtkPiecewiseFunction* opacity = bench.Scene.Property->GetScalarOpacity();
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(0.5);
    t.FixedQuarter.push_back(bench.RenderPeer(step / 4));
    savr->SetMaximumNumberOfFrames(1);
    savr->SetSampleDistance(step / 4);
    t.ExactQuarter.push_back(bench.RenderSavr());
    savr->SetMaximumNumberOfFrames(4);
    savr->SetSampleDistance(step);
    camera->Azimuth(0.5);
    double total = 0.0;
    int frame = 0;
    do
    {
      const double seconds = bench.RenderSavr();
      (frame == 0 ? t.FirstAccumulating : t.LaterAccumulating).push_back(seconds);
      total += seconds;
      ++frame;
    } while (!savr->GetRefinementComplete());
    t.Refine.push_back(total);
    t.RefineOverExact.push_back(total / t.ExactQuarter.back());
    t.BytesPerSample = savr_scenes::BytesPerStoredSample(savr);
    t.MemoryMiB = savr->GetMemoryInUse() / 1048576.0;
    for (int k = 0; k < 3; ++k)
    {
      t.Reuse.push_back(bench.RenderSavr());
    }
    // An edit, measured, then undone: every repetition refines the same function.
    vtkNew<vtkPiecewiseFunction> kept;
    kept->DeepCopy(opacity);
    opacity->AddPoint(200.0, r % 2 ? 0.5 : 0.4);
    t.Reblend.push_back(bench.RenderSavr());
    opacity->DeepCopy(kept);
  }
}
} // namespace

int main(int argc, char* argv[])
{
  Options o;
  int code = 0;
  if (!ParseOptions(argc, argv, o, code))
  {
    return code;
  }
  vtkSmartPointer<vtkImageData> head = LoadVolume(o.File);
  if (!head)
  {
    return EXIT_FAILURE;
  }
  int dims[3];
  head->GetDimensions(dims);
  std::printf("scene: MRI head %dx%dx%d, %s, window %dx%d, base step %g, %d repeats, %s, %s\n",
    dims[0], dims[1], dims[2], head->GetScalarTypeAsString(), o.Size, o.Size, o.Step, o.Repeats,
    o.Shade ? "shaded" : "unshaded", o.Opaque ? "opaque" : "translucent");

  savr_scenes::Scene scene(head, o.Size, o.Size);
  ConfigureProperty(scene.Property, o);
  scene.Window->SetOffScreenRendering(1);
  savr_scenes::FaceTheHead(scene.Renderer);

  vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
  fixedPoint->SetInputData(head);
  fixedPoint->AutoAdjustSampleDistancesOff();
  fixedPoint->SetImageSampleDistance(1.0);
  vtkNew<vtkVolume> peer;
  peer->SetMapper(fixedPoint);
  peer->SetProperty(scene.Property);
  scene.Renderer->AddVolume(peer);
  SideBySide bench{ scene, fixedPoint, peer };
  if (o.Rate > 0.0)
  {
    return InteractingAtRate(
      scene, fixedPoint, [&](bool savrVisible) { bench.Show(savrVisible); }, o.Step, o.Rate,
      o.Repeats);
  }
  bench.RenderPeer(o.Step); // warm-up (the peer's gradients, when shading)
  // Our first frame of the data: the first accumulating frame, with whatever is prepared once
  // per data change (gradients, when shading).
  Timings timings;
  scene.Mapper->SetSampleDistance(o.Step);
  timings.FirstFrame = bench.RenderSavr();
  MeasureInteracting(bench, o.Step, o.Repeats, timings);
  MeasureRefinement(bench, o.Step, o.Repeats, timings);
  PrintReport(timings);
  return EXIT_SUCCESS;
}

// Benchmark: vtkSAVRVolumeMapper next to vtkFixedPointVolumeRayCastMapper on the MRI head, in one
// run, same window size, camera and step. Prints medians (seconds per whole Render()) and ratios.
//
//   savr_benchmark [--size 512] [--repeats 9] [--step 1.0] [--shade 0] [--opaque 0]

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"

#include "vtkFixedPointVolumeRayCastMapper.h"
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
  const std::vector<double>& FixedStep;
  const std::vector<double>& FixedQuarter;
  const std::vector<double>& Interacting;
  const std::vector<double>& InteractingQuarter;
  const std::vector<double>& FirstAccumulating;
  const std::vector<double>& LaterAccumulating;
  const std::vector<double>& ExactQuarter;
  const std::vector<double>& Refine;
  const std::vector<double>& RefineOverExact;
  const std::vector<double>& Reuse;
  const std::vector<double>& Reblend;
  double FirstFrame;
  double BytesPerSample;
  double MemoryMiB;
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
/// AutoAdjustSampleDistances, on by default, coarsens its sampling and image; SAVR's its step).
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
  std::printf("  SAVR single pass (AutoAdjustSampleDistances, step %.2f base steps) %8.3f s  "
              "ratio %.2f\n",
    savr->GetInteractiveSampleDistance() / savr->GetEffectiveSampleDistance(), ours, ours / peer);
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char* argv[])
{
  int size = 512;
  int repeats = 9;
  double step = 1.0;
  int shade = 0;
  int opaque = 0;
  double rate = 0.0;
  std::string file;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_benchmark: vtkSAVRVolumeMapper next to vtkFixedPointVolumeRayCastMapper on the MRI "
    "head;\nprints medians of whole Render() calls and their ratios.");
  arguments.Option("--size", &size, "Window width and height in pixels (512).");
  arguments.Option("--repeats", &repeats, "Measurements of each kind (9).");
  arguments.Option("--step", &step, "Base sample distance in world units (1.0).");
  arguments.Option("--shade", &shade,
    "1 lights both mappers (ambient 0.2, diffuse 0.7, specular 0.3, power 12), 0 not (0).");
  arguments.Option("--opaque", &opaque,
    "1 makes the skin and bone opaque (opacity 0 to 40, 0.5 at 70, 1 from 100), so that rays end "
    "early, 0 keeps the default translucent transfer function (0).");
  arguments.Option("--rate", &rate,
    "With a rate R > 0, only interacting frames at the window's DesiredUpdateRate R (what VTK's "
    "interactor styles set during a drag), both mappers adjusting their sample distances to the "
    "time it allocates (0).");
  arguments.Option("--file", &file,
    "A NIfTI image (.nii or .nii.gz) instead of the MRI head (its transfer function).");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
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
      return EXIT_FAILURE;
    }
  }
  if (head->GetNumberOfPoints() == 0)
  {
    return EXIT_FAILURE;
  }
  int dims[3];
  head->GetDimensions(dims);
  std::printf("scene: MRI head %dx%dx%d, %s, window %dx%d, base step %g, %d repeats, %s, %s\n",
    dims[0], dims[1], dims[2], head->GetScalarTypeAsString(), size, size, step, repeats,
    shade ? "shaded" : "unshaded", opaque ? "opaque" : "translucent");

  savr_scenes::Scene scene(head, size, size);
  savr_scenes::HeadProperty(scene.Property);
  if (opaque)
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(40.0, 0.0);
    opacity->AddPoint(70.0, 0.5);
    opacity->AddPoint(100.0, 1.0);
    opacity->AddPoint(255.0, 1.0);
    scene.Property->SetScalarOpacity(opacity);
  }
  if (shade)
  {
    scene.Property->ShadeOn();
    scene.Property->SetAmbient(0.2);
    scene.Property->SetDiffuse(0.7);
    scene.Property->SetSpecular(0.3);
    scene.Property->SetSpecularPower(12.0);
  }
  scene.Window->SetOffScreenRendering(1);
  savr_scenes::FaceTheHead(scene.Renderer);
  vtkCamera* camera = scene.Renderer->GetActiveCamera();

  // The peer in its own volume, in the same window; the two are measured alternately, frame by
  // frame, so that both see the same machine load.
  vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
  fixedPoint->SetInputData(head);
  fixedPoint->AutoAdjustSampleDistancesOff();
  fixedPoint->SetImageSampleDistance(1.0);
  vtkNew<vtkVolume> peer;
  peer->SetMapper(fixedPoint);
  peer->SetProperty(scene.Property);
  scene.Renderer->AddVolume(peer);
  vtkSAVRVolumeMapper* savr = scene.Mapper;
  auto show = [&](bool savrVisible)
  {
    scene.Volume->SetVisibility(savrVisible);
    peer->SetVisibility(!savrVisible);
  };
  auto renderPeer = [&](double sampleDistance)
  {
    show(false);
    fixedPoint->SetSampleDistance(sampleDistance);
    return Seconds([&] { scene.Window->Render(); });
  };
  if (rate > 0.0)
  {
    return InteractingAtRate(scene, fixedPoint, show, step, rate, repeats);
  }
  renderPeer(step); // warm-up (the peer's gradients, when shading)
  // Our first frame of the data: the first accumulating frame, with whatever is prepared once
  // per data change (gradients, when shading).
  show(true);
  savr->SetSampleDistance(step);
  const double firstFrame = Seconds([&] { scene.Window->Render(); });

  // Interacting frames: single passes at the base step while the camera moves, next to the
  // peer at the same step; then our single pass at a quarter of the step.
  std::vector<double> fixedStepTimes;
  std::vector<double> interacting;
  std::vector<double> quarterPass;
  savr->InteractiveOn();
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(0.5);
    fixedStepTimes.push_back(renderPeer(step));
    show(true);
    savr->SetSampleDistance(step);
    interacting.push_back(Seconds([&] { scene.Window->Render(); }));
    savr->SetSampleDistance(step / 4);
    quarterPass.push_back(Seconds([&] { scene.Window->Render(); }));
  }
  savr->InteractiveOff();
  savr->SetSampleDistance(step);

  // Accumulation to 4 frames (quarter step) next to the peer at a quarter step, then reuse and
  // re-blend.
  std::vector<double> fixedQuarterTimes;
  std::vector<double> refine;
  std::vector<double> firstAccumulating;
  std::vector<double> laterAccumulating;
  std::vector<double> reuse;
  std::vector<double> reblend;
  // The exact pass the refined image equals, measured next to each refinement: one frame at a
  // quarter of the step, every sample of every ray taken and stored (no early termination, no
  // skipping).
  std::vector<double> exactQuarter;
  std::vector<double> refineOverExact;
  double bytesPerSample = 0.0;
  double memoryMiB = 0.0;
  vtkPiecewiseFunction* opacity = scene.Property->GetScalarOpacity();
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(0.5);
    fixedQuarterTimes.push_back(renderPeer(step / 4));
    show(true);
    savr->SetMaximumNumberOfFrames(1);
    savr->SetSampleDistance(step / 4);
    exactQuarter.push_back(Seconds([&] { scene.Window->Render(); }));
    savr->SetMaximumNumberOfFrames(4);
    savr->SetSampleDistance(step);
    camera->Azimuth(0.5);
    double total = 0.0;
    int frame = 0;
    do
    {
      const double t = Seconds([&] { scene.Window->Render(); });
      (frame == 0 ? firstAccumulating : laterAccumulating).push_back(t);
      total += t;
      ++frame;
    } while (!savr->GetRefinementComplete());
    refine.push_back(total);
    refineOverExact.push_back(total / exactQuarter.back());
    bytesPerSample = savr_scenes::BytesPerStoredSample(savr);
    memoryMiB = savr->GetMemoryInUse() / 1048576.0;
    for (int k = 0; k < 3; ++k)
    {
      reuse.push_back(Seconds([&] { scene.Window->Render(); }));
    }
    opacity->AddPoint(200.0, r % 2 ? 0.5 : 0.4);
    reblend.push_back(Seconds([&] { scene.Window->Render(); }));
  }

  Timings timings{ fixedStepTimes, fixedQuarterTimes, interacting, quarterPass, firstAccumulating,
    laterAccumulating, exactQuarter, refine, refineOverExact, reuse, reblend, firstFrame,
    bytesPerSample, memoryMiB };
  PrintReport(timings);
  return EXIT_SUCCESS;
}

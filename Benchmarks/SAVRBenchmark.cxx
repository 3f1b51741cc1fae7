// Benchmark: vtkSAVRVolumeMapper next to vtkFixedPointVolumeRayCastMapper on the MRI head, in one
// run, same window size, camera and step. Prints medians (seconds per whole Render()) and ratios.
//
//   savr_benchmark [--size 512] [--repeats 9] [--step 1.0]

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"

#include "vtkFixedPointVolumeRayCastMapper.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

using savr_benchmarks::Median;
using savr_benchmarks::Seconds;

int main(int argc, char* argv[])
{
  int size = 512;
  int repeats = 9;
  double step = 1.0;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_benchmark: vtkSAVRVolumeMapper next to vtkFixedPointVolumeRayCastMapper on the MRI "
    "head;\nprints medians of whole Render() calls and their ratios.");
  arguments.Option("--size", &size, "Window width and height in pixels (512).");
  arguments.Option("--repeats", &repeats, "Measurements of each kind (9).");
  arguments.Option("--step", &step, "Base sample distance in world units (1.0).");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkImageData> head = savr_scenes::Head();
  if (head->GetNumberOfPoints() == 0)
  {
    return EXIT_FAILURE;
  }
  int dims[3];
  head->GetDimensions(dims);
  std::printf("scene: MRI head %dx%dx%d, %s, window %dx%d, base step %g, %d repeats\n", dims[0],
    dims[1], dims[2], head->GetScalarTypeAsString(), size, size, step, repeats);

  savr_scenes::Scene scene(head, size, size);
  savr_scenes::HeadProperty(scene.Property);
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
  renderPeer(step); // warm-up

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

  const double fixedStep = Median(fixedStepTimes);
  const double fixedQuarter = Median(fixedQuarterTimes);
  const double interactingMedian = Median(interacting);
  const double quarterMedian = Median(quarterPass);
  const double refineMedian = Median(refine);
  std::printf(
    "\n%-58s %10s %10s\n", "measurement (median of whole Render() calls)", "seconds", "ratio");
  std::printf("%-58s %10.4f %10s\n", "fixed point, step 1x", fixedStep, "1.00");
  std::printf(
    "%-58s %10.4f %10.2f\n", "fixed point, step 1/4x", fixedQuarter, fixedQuarter / fixedStep);
  std::printf("%-58s %10.4f %10.2f\n", "SAVR interacting frame, step 1x (vs fixed point 1x)",
    interactingMedian, interactingMedian / fixedStep);
  std::printf("%-58s %10.4f %10.2f\n", "SAVR first accumulating frame (vs interacting)",
    Median(firstAccumulating), Median(firstAccumulating) / interactingMedian);
  std::printf("%-58s %10.4f %10.2f\n", "SAVR later accumulating frames (vs interacting)",
    Median(laterAccumulating), Median(laterAccumulating) / interactingMedian);
  std::printf("%-58s %10.4f %10s\n", "SAVR interacting pass, step 1/4x", quarterMedian, "1.00");
  std::printf("%-58s %10.4f %10.2f\n", "SAVR exact single pass, step 1/4x (vs interacting 1/4x)",
    Median(exactQuarter), Median(exactQuarter) / quarterMedian);
  std::printf("%-58s %10.4f %10.2f\n", "SAVR refine to 4 frames, step 1/4x (vs interacting 1/4x)",
    refineMedian, refineMedian / quarterMedian);
  std::printf("%-58s %10.4f %10.2f\n", "SAVR refine to 4 frames, step 1/4x (vs exact pass 1/4x)",
    refineMedian, refineMedian / Median(exactQuarter));
  std::printf("%-58s %10s %10.2f\n", "  the same, median of each refinement over its exact pass",
    "", Median(refineOverExact));
  std::printf("%-58s %10.4f %10.2f\n", "SAVR refine to 4 frames (vs fixed point 1/4x)",
    refineMedian, refineMedian / fixedQuarter);
  std::printf(
    "%-58s %10.4f %10s\n", "SAVR frame after completion, nothing changed", Median(reuse), "");
  std::printf("%-58s %10.4f %10.2f\n", "SAVR transfer-function re-blend (vs interacting)",
    Median(reblend), Median(reblend) / interactingMedian);
  std::printf("%-58s %10.2f %10s\n", "SAVR stored-sample memory, MiB", memoryMiB, "");
  std::printf("%-58s %10.3f %10s\n", "SAVR bytes per stored sample", bytesPerSample, "");
  return EXIT_SUCCESS;
}

// Benchmark: vtkSAVRVolumeMapper on an unstructured grid next to VTK's two unstructured volume
// mappers, vtkUnstructuredGridVolumeRayCastMapper and vtkProjectedTetrahedraMapper, in one run:
// the wavelet on 48^3 points cut into tetrahedra by vtkDataSetTriangleFilter (519,115 cells),
// same window, camera and transfer function, black background.
//
//   savr_unstructured_benchmark [--size 512] [--repeats 5] [--points 48] [--step S]
//                               [--reference-step S]
//
// Per mapper it prints the first Render() (which includes building the mapper's structures),
// the median Render() after a camera change (repeats, the camera moving between two positions),
// and for SAVR the median time from a camera change until refinement completes, and the
// interacting frame. Error: RMSE and largest error of each image's RGB in [0, 1] against a
// reference integrated in double precision along each ray at a step of 1/64 of a cell, through
// the same tetrahedra.

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"

#include "vtkProjectedTetrahedraMapper.h"
#include "vtkUnstructuredGridVolumeRayCastMapper.h"

#include <cmath>
#include <cstdio>

using savr_benchmarks::Median;
using savr_benchmarks::Seconds;
using savr_benchmarks::WindowError;

int main(int argc, char* argv[])
{
  int size = 512;
  int repeats = 5;
  int points = 48;
  double referenceStep = 0.0;
  double step = 0.0; // SAVR's base step: 0 = the typical cell size
  savr_scenes::Arguments arguments(argc, argv,
    "savr_unstructured_benchmark: vtkSAVRVolumeMapper next to VTK's unstructured volume mappers "
    "on\nthe wavelet cut into tetrahedra; prints times and errors against a double-precision "
    "reference.");
  arguments.Option("--size", &size, "Window width and height in pixels (512).");
  arguments.Option("--repeats", &repeats, "Measurements after a camera change (5).");
  arguments.Option("--points", &points, "Wavelet points along each axis (48).");
  arguments.Option("--step", &step, "SAVR's base step (0: the typical cell size).");
  arguments.Option(
    "--reference-step", &referenceStep, "The reference's step (0: 1/64 of the cell size).");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkUnstructuredGrid> tets = savr_scenes::TetrahedralWavelet(points);
  std::printf("scene: wavelet %d^3 points cut into %lld tetrahedra, window %dx%d, %d repeats\n",
    points, static_cast<long long>(tets->GetNumberOfCells()), size, size, repeats);

  // One window per mapper, one camera for all.
  savr_scenes::Scene savrScene(tets, size, size);
  savr_scenes::Scene rayCastScene(tets, size, size);
  savr_scenes::Scene projectedScene(tets, size, size);
  vtkNew<vtkUnstructuredGridVolumeRayCastMapper> rayCast;
  rayCast->SetInputData(tets);
  rayCastScene.Volume->SetMapper(rayCast);
  vtkNew<vtkProjectedTetrahedraMapper> projected;
  projected->SetInputData(tets);
  projectedScene.Volume->SetMapper(projected);
  savrScene.Mapper->SetSampleDistance(step);
  vtkCamera* camera = savrScene.Renderer->GetActiveCamera();
  for (savr_scenes::Scene* scene : { &savrScene, &rayCastScene, &projectedScene })
  {
    savr_scenes::WaveletProperty(scene->Property);
    scene->Renderer->SetBackground(0, 0, 0);
    scene->Renderer->SetActiveCamera(camera);
    scene->Window->SetOffScreenRendering(1);
  }

  // The reference through the same tetrahedra.
  double cell = 1.0;
  std::string error;
  std::shared_ptr<const savr::Sampler> sampler = savr_benchmarks::SamplerFor(tets, cell, error);
  if (!sampler)
  {
    std::fprintf(stderr, "cannot sample the tetrahedra: %s\n", error.c_str());
    return EXIT_FAILURE;
  }
  referenceStep = referenceStep > 0.0 ? referenceStep : cell / 64.0;
  std::vector<float> reference;
  const double referenceTime = Seconds(
    [&]
    {
      reference = savr_benchmarks::Reference(
        savr_benchmarks::ViewOf(camera, size, size), *sampler, savrScene.Property, referenceStep);
    });
  std::printf("reference at step %g computed in %.1f s\n\n", referenceStep, referenceTime);

  // First renders: each mapper builds what it needs.
  vtkSAVRVolumeMapper* mapper = savrScene.Mapper;
  const double savrFirst = Seconds([&] { savrScene.Window->Render(); });
  const savr_scenes::ImageError savrFirstError = WindowError(savrScene.Window, reference);
  double savrConverge = savrFirst;
  while (!mapper->GetRefinementComplete())
  {
    savrConverge += Seconds([&] { savrScene.Window->Render(); });
  }
  const savr_scenes::ImageError savrConverged = WindowError(savrScene.Window, reference);
  const int frames = mapper->GetNumberOfFramesAccumulated();
  // The same frames in the engine alone (no window, no 8-bit image): where the error goes.
  savr_scenes::ImageError engineError;
  {
    savr::FrameSettings settings;
    settings.SampleDistance = mapper->GetEffectiveSampleDistance();
    settings.MaximumFrames = frames;
    savr::FrameLoop loop;
    loop.Reset(savr_benchmarks::ViewOf(camera, size, size), sampler, settings);
    savr::TransferFunctionTable table;
    savr_benchmarks::BuildTable(loop.Encoding(), savrScene.Property, table);
    for (int k = 0; k < frames; ++k)
    {
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
    }
    engineError = savr_scenes::ErrorAgainst(loop.Image(), reference, false);
  }
  const double rayCastFirst = Seconds([&] { rayCastScene.Window->Render(); });
  const savr_scenes::ImageError rayCastError = WindowError(rayCastScene.Window, reference);
  const double projectedFirst = Seconds([&] { projectedScene.Window->Render(); });
  const savr_scenes::ImageError projectedError = WindowError(projectedScene.Window, reference);

  // Renders after a camera change, interleaved.
  std::vector<double> savrFrame;
  std::vector<double> savrRefine;
  std::vector<double> savrInteracting;
  std::vector<double> rayCastFrame;
  std::vector<double> projectedFrame;
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(r % 2 ? -1.0 : 1.0);
    mapper->InteractiveOn();
    savrInteracting.push_back(Seconds([&] { savrScene.Window->Render(); }));
    mapper->InteractiveOff();
    camera->Azimuth(r % 2 ? 1.0 : -1.0);
    double total = Seconds([&] { savrScene.Window->Render(); });
    savrFrame.push_back(total);
    while (!mapper->GetRefinementComplete())
    {
      total += Seconds([&] { savrScene.Window->Render(); });
    }
    savrRefine.push_back(total);
    rayCastFrame.push_back(Seconds([&] { rayCastScene.Window->Render(); }));
    projectedFrame.push_back(Seconds([&] { projectedScene.Window->Render(); }));
  }

  std::printf(
    "%-44s %12s %12s %10s %10s\n", "mapper", "first (s)", "median (s)", "RMSE", "max error");
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n", "SAVR, first frame", savrFirst,
    Median(savrFrame), savrFirstError.Rmse, savrFirstError.Max);
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n",
    ("SAVR, refined (" + std::to_string(frames) + " frames)").c_str(), savrConverge,
    Median(savrRefine), savrConverged.Rmse, savrConverged.Max);
  std::printf("%-44s %12s %12s %10.2e %10.3f\n",
    ("SAVR engine alone, " + std::to_string(frames) + " frames (no window)").c_str(), "", "",
    engineError.Rmse, engineError.Max);
  std::printf("%-44s %12s %12.3f %10s %10s\n", "SAVR, interacting frame", "",
    Median(savrInteracting), "", "");
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n", "vtkUnstructuredGridVolumeRayCastMapper",
    rayCastFirst, Median(rayCastFrame), rayCastError.Rmse, rayCastError.Max);
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n", "vtkProjectedTetrahedraMapper", projectedFirst,
    Median(projectedFrame), projectedError.Rmse, projectedError.Max);
  std::printf("\nratios of medians: SAVR first frame / ray cast %.2f, / projected %.2f; SAVR "
              "refined / ray cast %.2f, / projected %.2f\n",
    Median(savrFrame) / Median(rayCastFrame), Median(savrFrame) / Median(projectedFrame),
    Median(savrRefine) / Median(rayCastFrame), Median(savrRefine) / Median(projectedFrame));
  std::printf("SAVR base step %g, %d frames, memory %.1f MiB\n",
    mapper->GetEffectiveSampleDistance(), frames, mapper->GetMemoryInUse() / 1048576.0);
  return EXIT_SUCCESS;
}

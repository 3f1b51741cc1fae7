// Benchmark: vtkSAVRVolumeMapper on an unstructured grid next to VTK's two unstructured volume
// mappers, vtkUnstructuredGridVolumeRayCastMapper and vtkProjectedTetrahedraMapper, in one run,
// same window, camera and transfer function, black background, on one of three meshes:
// - tetra: the wavelet on 48^3 points cut into tetrahedra by vtkDataSetTriangleFilter (519,115
//   cells);
// - hexahedra: the wavelet on 41^3 points of a smoothly warped curvilinear mesh of hexahedra
//   (64,000 cells);
// - mixed: the same with every other slab of hexahedra split into wedges (32,000 hexahedra and
//   64,000 wedges).
// SAVR and the reference sample the mesh's own cells; VTK's mappers, which draw tetrahedra only,
// are given the mesh cut into tetrahedra by vtkDataSetTriangleFilter (with --savr-cells
// tetrahedra, SAVR is given them too, at the native mesh's step).
//
//   savr_unstructured_benchmark [--mesh tetra|hexahedra|mixed] [--size 512] [--repeats 5]
//                               [--points 48 or 41] [--step S] [--reference-step S]
//                               [--savr-cells native|tetrahedra]
//
// Per mapper it prints the first Render() (which includes building the mapper's structures),
// the median Render() after a camera change (repeats, the camera moving between two positions),
// and for SAVR the median time from a camera change until refinement completes, and the
// interacting frame, then SAVR's interacting frame and refinement to completion against the faster
// of VTK's two mappers after a camera change. Error: RMSE and largest error of each image's RGB in
// [0, 1] against a reference integrated in double precision along each ray at a step of 1/64 of a
// cell, through the same cells. Last, SAVR's frames in the engine alone (no window), frame by
// frame, reading each ray's path after the first frame (the default) and walking every frame.

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"

#include "vtkCellTypes.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkProjectedTetrahedraMapper.h"
#include "vtkUnstructuredGridVolumeRayCastMapper.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <tuple>

using savr_benchmarks::Median;
using savr_benchmarks::Seconds;
using savr_benchmarks::WindowError;

namespace
{
// "32000 hexahedra + 64000 wedges": how many cells of each type the mesh has.
std::string CellCounts(vtkUnstructuredGrid* mesh)
{
  std::map<int, vtkIdType> counts;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    ++counts[mesh->GetCellType(c)];
  }
  const std::map<int, const char*> names = { { VTK_TETRA, "tetrahedra" },
    { VTK_HEXAHEDRON, "hexahedra" }, { VTK_WEDGE, "wedges" } };
  std::string text;
  for (const auto& count : counts)
  {
    const auto name = names.find(count.first);
    text +=
      (text.empty() ? "" : " + ") + std::to_string(count.second) + " " +
      (name != names.end() ? name->second : vtkCellTypes::GetClassNameFromTypeId(count.first));
  }
  return text;
}

// The mesh `kind` names on `points`^3 points (0: 48 for tetra, 41 otherwise, set here) and, for
// VTK's mappers, the same cut into tetrahedra; false, with a message, for an unknown kind.
bool BuildMeshes(const std::string& kind, int& points, vtkSmartPointer<vtkUnstructuredGrid>& mesh,
  vtkSmartPointer<vtkUnstructuredGrid>& tets)
{
  if (kind == "tetra")
  {
    points = points > 0 ? points : 48;
    mesh = tets = savr_scenes::TetrahedralWavelet(points);
    return true;
  }
  if (kind != "hexahedra" && kind != "mixed")
  {
    std::fprintf(stderr, "--mesh must be tetra, hexahedra or mixed, not %s\n", kind.c_str());
    return false;
  }
  points = points > 0 ? points : 41;
  mesh = savr_scenes::HexahedralWavelet(points, kind == "mixed");
  vtkNew<vtkDataSetTriangleFilter> tetrahedralize;
  tetrahedralize->SetInputData(mesh);
  tetrahedralize->Update();
  tets = tetrahedralize->GetOutput();
  return true;
}

// SAVR's medians over the peers': its first frame and its refinement against each, then its
// interacting frame and its refinement to completion against the faster peer.
void PrintRatios(const std::vector<double>& savrInteracting, const std::vector<double>& savrFrame,
  const std::vector<double>& savrRefine, const std::vector<double>& rayCastFrame,
  const std::vector<double>& projectedFrame)
{
  std::printf("\nratios of medians: SAVR first frame / ray cast %.2f, / projected %.2f; SAVR "
              "refined / ray cast %.2f, / projected %.2f\n",
    Median(savrFrame) / Median(rayCastFrame), Median(savrFrame) / Median(projectedFrame),
    Median(savrRefine) / Median(rayCastFrame), Median(savrRefine) / Median(projectedFrame));
  const bool rayCastFaster = Median(rayCastFrame) <= Median(projectedFrame);
  const double fasterPeer = std::min(Median(rayCastFrame), Median(projectedFrame));
  std::printf("against the faster peer (%s, %.3f s): SAVR interacting frame %.2f, refinement to "
              "completion %.2f\n",
    rayCastFaster ? "ray cast" : "projected", fasterPeer, Median(savrInteracting) / fasterPeer,
    Median(savrRefine) / fasterPeer);
}

// The engine alone (no window, no 8-bit image) on the same frames: its error, and each frame's
// time with the rays' paths (the default) and walking every frame, alternately, summed over the
// runs; the paths' memory is what the first frame adds to the stored samples.
struct EngineAlone
{
  savr_scenes::ImageError Error;
  std::vector<double> PathFrames;
  std::vector<double> WalkFrames;
  double PathMemory = 0.0;
  double WalkMemory = 0.0;
};

EngineAlone MeasureEngineAlone(const savr::View& view,
  const std::shared_ptr<const savr::Sampler>& sampler, vtkVolumeProperty* property, double step,
  int frames, int repeats, const std::vector<float>& reference)
{
  EngineAlone result;
  savr::FrameSettings settings;
  settings.SampleDistance = step;
  settings.MaximumFrames = frames;
  savr::FrameLoop loop;
  loop.Reset(view, sampler, settings);
  savr::TransferFunctionTable table;
  savr_benchmarks::BuildTable(loop.Encoding(), property, table);
  for (int k = 0; k < frames; ++k)
  {
    loop.AccumulateFrame(table, savr::BlendMode::Composite);
  }
  result.Error = savr_scenes::ErrorAgainst(loop.Image(), reference, false);
  for (int run = 0; run < 2 * std::max(repeats / 2, 1); ++run)
  {
    settings.TracePaths = run % 2 == 0;
    loop.Reset(view, sampler, settings);
    std::vector<double>& times = settings.TracePaths ? result.PathFrames : result.WalkFrames;
    times.resize(frames);
    for (int k = 0; k < frames; ++k)
    {
      times[k] += Seconds([&] { loop.AccumulateFrame(table, savr::BlendMode::Composite); });
      if (k == 0 && run < 2)
      {
        (settings.TracePaths ? result.PathMemory : result.WalkMemory) =
          loop.MemoryInUse() / 1048576.0;
      }
    }
  }
  return result;
}

// Renders after a camera change, interleaved: SAVR interacting, its first frame and its
// refinement, then each peer.
struct Interleaved
{
  std::vector<double> SavrFrame;
  std::vector<double> SavrRefine;
  std::vector<double> SavrInteracting;
  std::vector<double> RayCastFrame;
  std::vector<double> ProjectedFrame;
};

Interleaved MeasureInterleaved(vtkCamera* camera, savr_scenes::Scene& savrScene,
  savr_scenes::Scene& rayCastScene, savr_scenes::Scene& projectedScene, int repeats)
{
  Interleaved t;
  vtkSAVRVolumeMapper* mapper = savrScene.Mapper;
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(r % 2 ? -1.0 : 1.0);
    mapper->InteractiveOn();
    t.SavrInteracting.push_back(Seconds([&] { savrScene.Window->Render(); }));
    mapper->InteractiveOff();
    camera->Azimuth(r % 2 ? 1.0 : -1.0);
    double total = Seconds([&] { savrScene.Window->Render(); });
    t.SavrFrame.push_back(total);
    while (!mapper->GetRefinementComplete())
    {
      total += Seconds([&] { savrScene.Window->Render(); });
    }
    t.SavrRefine.push_back(total);
    t.RayCastFrame.push_back(Seconds([&] { rayCastScene.Window->Render(); }));
    t.ProjectedFrame.push_back(Seconds([&] { projectedScene.Window->Render(); }));
  }
  return t;
}

// Means over the runs of MeasureEngineAlone: frame k of a refinement, paths and walks.
void PrintEngineFrames(const EngineAlone& engine, int repeats)
{
  const double runs = std::max(repeats / 2, 1);
  for (const auto& [name, times, memory] :
    { std::make_tuple("paths", &engine.PathFrames, engine.PathMemory),
      std::make_tuple("walks", &engine.WalkFrames, engine.WalkMemory) })
  {
    std::printf("engine alone, %s, seconds per frame:", name);
    double total = 0.0;
    for (double t : *times)
    {
      std::printf(" %.3f", t / runs);
      total += t / runs;
    }
    std::printf("  (all %.3f; held after the first frame %.1f MiB)\n", total, memory);
  }
}

// The command line.
struct Options
{
  int Size = 512;
  int Repeats = 5;
  int Points = 0; // 0: 48 for tetrahedra, 41 for the other meshes
  std::string MeshKind = "tetra";
  double ReferenceStep = 0.0;
  double Step = 0.0; // SAVR's base step: 0 = the typical cell size
  std::string SavrCells = "native";
};

// False, with the exit code in `exitCode`, when the program should stop (help, a bad flag).
bool ParseOptions(int argc, char* argv[], Options& o, int& exitCode)
{
  savr_scenes::Arguments arguments(argc, argv,
    "savr_unstructured_benchmark: vtkSAVRVolumeMapper next to VTK's unstructured volume mappers "
    "on\nthe wavelet on tetrahedra, hexahedra or hexahedra and wedges; prints times and errors "
    "against a\ndouble-precision reference.");
  arguments.Option("--mesh", &o.MeshKind,
    "tetra (the wavelet cut into tetrahedra), hexahedra (a warped curvilinear mesh of hexahedra) "
    "or mixed (the same, every other slab of hexahedra split into wedges) (tetra).");
  arguments.Option("--size", &o.Size, "Window width and height in pixels (512).");
  arguments.Option("--repeats", &o.Repeats, "Measurements after a camera change (5).");
  arguments.Option(
    "--points", &o.Points, "Wavelet points along each axis (48 for tetra, 41 otherwise).");
  arguments.Option("--step", &o.Step, "SAVR's base step (0: the typical cell size).");
  arguments.Option("--savr-cells", &o.SavrCells,
    "native (SAVR samples the mesh's own cells) or tetrahedra (SAVR gets the tetrahedra VTK's "
    "mappers get, at the native mesh's step) (native).");
  arguments.Option(
    "--reference-step", &o.ReferenceStep, "The reference's step (0: 1/64 of the cell size).");
  if (!arguments.Parse())
  {
    exitCode = arguments.ExitCode();
    return false;
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  Options options;
  int exitCode = EXIT_SUCCESS;
  if (!ParseOptions(argc, argv, options, exitCode))
  {
    return exitCode;
  }
  const int size = options.Size;
  const int repeats = options.Repeats;
  int points = options.Points;
  const std::string& meshKind = options.MeshKind;
  double referenceStep = options.ReferenceStep;
  double step = options.Step;
  const std::string& savrCells = options.SavrCells;
  vtkSmartPointer<vtkUnstructuredGrid> mesh;
  vtkSmartPointer<vtkUnstructuredGrid> tets;
  if (!BuildMeshes(meshKind, points, mesh, tets))
  {
    return EXIT_FAILURE;
  }
  std::printf("scene: wavelet on %d^3 points, %s: %s; VTK's mappers given %s; window %dx%d, %d "
              "repeats\n",
    points, mesh == tets ? "cut into tetrahedra" : "warped", CellCounts(mesh).c_str(),
    mesh == tets ? "the same" : CellCounts(tets).c_str(), size, size, repeats);

  if (savrCells != "native" && savrCells != "tetrahedra")
  {
    std::fprintf(stderr, "--savr-cells must be native or tetrahedra, not %s\n", savrCells.c_str());
    return EXIT_FAILURE;
  }
  // The reference samples the mesh's own cells; SAVR these or the peers' tetrahedra.
  double cell = 1.0;
  std::string error;
  std::shared_ptr<const savr::Sampler> sampler = savr_benchmarks::SamplerFor(mesh, cell, error);
  if (!sampler)
  {
    std::fprintf(stderr, "cannot sample the mesh: %s\n", error.c_str());
    return EXIT_FAILURE;
  }
  vtkUnstructuredGrid* savrMesh = savrCells == "native" ? mesh.Get() : tets.Get();
  std::shared_ptr<const savr::Sampler> savrSampler = sampler;
  int nativeFrames = 1;
  if (savrMesh != mesh.Get())
  {
    double tetraCell = 1.0;
    savrSampler = savr_benchmarks::SamplerFor(savrMesh, tetraCell, error);
    step = step > 0.0 ? step : cell;
    // The frames the mapper would choose on the native cells (whose typical cell is larger).
    while (step / nativeFrames > 0.25 * cell * (1.0 + 1e-9))
    {
      nativeFrames *= 2;
    }
    std::printf("SAVR given the tetrahedra, at the native mesh's step %g and frames %d\n", step,
      nativeFrames);
  }

  // One window per mapper, one camera for all.
  savr_scenes::Scene savrScene(savrMesh, size, size);
  savr_scenes::Scene rayCastScene(tets, size, size);
  savr_scenes::Scene projectedScene(tets, size, size);
  vtkNew<vtkUnstructuredGridVolumeRayCastMapper> rayCast;
  rayCast->SetInputData(tets);
  rayCastScene.Volume->SetMapper(rayCast);
  vtkNew<vtkProjectedTetrahedraMapper> projected;
  projected->SetInputData(tets);
  projectedScene.Volume->SetMapper(projected);
  savrScene.Mapper->SetSampleDistance(step);
  if (savrMesh != mesh.Get())
  {
    savrScene.Mapper->SetMaximumNumberOfFrames(nativeFrames);
  }
  vtkCamera* camera = savrScene.Renderer->GetActiveCamera();
  for (savr_scenes::Scene* scene : { &savrScene, &rayCastScene, &projectedScene })
  {
    savr_scenes::WaveletProperty(scene->Property);
    scene->Renderer->SetBackground(0, 0, 0);
    scene->Renderer->SetActiveCamera(camera);
    scene->Window->SetOffScreenRendering(1);
  }

  // The reference through the mesh's own cells.
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
  // The same frames in the engine alone: where the error goes.
  const EngineAlone engine = MeasureEngineAlone(savr_benchmarks::ViewOf(camera, size, size),
    savrSampler, savrScene.Property, mapper->GetEffectiveSampleDistance(), frames, repeats,
    reference);
  const double rayCastFirst = Seconds([&] { rayCastScene.Window->Render(); });
  const savr_scenes::ImageError rayCastError = WindowError(rayCastScene.Window, reference);
  const double projectedFirst = Seconds([&] { projectedScene.Window->Render(); });
  const savr_scenes::ImageError projectedError = WindowError(projectedScene.Window, reference);

  const Interleaved t =
    MeasureInterleaved(camera, savrScene, rayCastScene, projectedScene, repeats);
  const std::vector<double>& savrFrame = t.SavrFrame;
  const std::vector<double>& savrRefine = t.SavrRefine;
  const std::vector<double>& savrInteracting = t.SavrInteracting;
  const std::vector<double>& rayCastFrame = t.RayCastFrame;
  const std::vector<double>& projectedFrame = t.ProjectedFrame;

  std::printf(
    "%-44s %12s %12s %10s %10s\n", "mapper", "first (s)", "median (s)", "RMSE", "max error");
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n", "SAVR, first frame", savrFirst,
    Median(savrFrame), savrFirstError.Rmse, savrFirstError.Max);
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n",
    ("SAVR, refined (" + std::to_string(frames) + " frames)").c_str(), savrConverge,
    Median(savrRefine), savrConverged.Rmse, savrConverged.Max);
  std::printf("%-44s %12s %12s %10.2e %10.3f\n",
    ("SAVR engine alone, " + std::to_string(frames) + " frames (no window)").c_str(), "", "",
    engine.Error.Rmse, engine.Error.Max);
  std::printf("%-44s %12s %12.3f %10s %10s\n", "SAVR, interacting frame", "",
    Median(savrInteracting), "", "");
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n", "vtkUnstructuredGridVolumeRayCastMapper",
    rayCastFirst, Median(rayCastFrame), rayCastError.Rmse, rayCastError.Max);
  std::printf("%-44s %12.3f %12.3f %10.2e %10.3f\n", "vtkProjectedTetrahedraMapper", projectedFirst,
    Median(projectedFrame), projectedError.Rmse, projectedError.Max);
  PrintRatios(savrInteracting, savrFrame, savrRefine, rayCastFrame, projectedFrame);
  std::printf("SAVR base step %g, %d frames, memory %.1f MiB\n",
    mapper->GetEffectiveSampleDistance(), frames, mapper->GetMemoryInUse() / 1048576.0);
  PrintEngineFrames(engine, repeats);
  return EXIT_SUCCESS;
}

// Benchmark: particles drawn as a volume. vtkSAVRVolumeMapper samples a clustered cloud of
// particles itself (SPH cubic kernel, one radius, normalized), next to ideal sampling (one pass
// at the step SAVR refines to, in the engine) and to the path VTK users take today
// (vtkSPHInterpolator to an image, then vtkGPUVolumeRayCastMapper), in one run, same window, camera
// and transfer function, black background.
//
//   savr_particle_benchmark [--size 512] [--points 2000000] [--clusters 300] [--frames 0]
//                           [--repeats 3] [--resample "32,64,128,256"] [--reference-factor 4]
//                           [--point-queries 0]
//
// Prints, as medians over camera moves: SAVR's interacting frame, its first accumulating frame
// and its refinement to completion, and one ideal frame at SAVR's final step, with the ratios
// the design targets (interacting / ideal, refinement / ideal); with --point-queries 1 also one
// ideal pass that queries the particle index once per sample, as the method's paper measures
// ideal sampling; memory; and per image
// resolution the resampling time, the GPU mapper's frame, the image's memory and its error,
// next to SAVR's error after the same time and the time SAVR takes to reach the image's error.
// Error: RMSE and largest error of RGB in [0, 1] against a reference integrated in double precision
// through the same particles at 1 / reference-factor of SAVR's final step.

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"
#include "SAVRParticleScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkSAVRParticleSampler.h"

#include <cstdio>
#include <sstream>

using savr_benchmarks::Median;
using savr_benchmarks::Seconds;
using savr_benchmarks::WindowError;

namespace
{

void Prepare(savr_scenes::Scene& scene, vtkCamera* camera)
{
  savr_scenes::CloudProperty(scene.Property);
  scene.Renderer->SetBackground(0, 0, 0);
  scene.Renderer->SetActiveCamera(camera);
  scene.Window->SetOffScreenRendering(1);
}

// Ideal sampling as the method's paper measures it: each sample found on its own, one query of
// the particle index per sample, as a renderer that samples a field point by point does (the
// particle sampler's own walk finds the particles of a whole piece of ray at once).
class PointQueries : public savr::Sampler
{
public:
  explicit PointQueries(std::shared_ptr<const savr::Sampler> inner)
    : Inner(std::move(inner))
  {
  }
  bool Clip(const savr::Ray& ray, double& tEnter, double& tExit) const override
  {
    return this->Inner->Clip(ray, tEnter, tExit);
  }
  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override
  {
    return this->Inner->HullCorners(corners);
  }
  std::array<double, 2> ValueRange() const override { return this->Inner->ValueRange(); }
  int ExactBits() const override { return this->Inner->ExactBits(); }
  bool MayReturnNaN() const override { return this->Inner->MayReturnNaN(); }
  void SampleRay(const savr::Ray& ray, double t0, double dt, int count, float* out,
    const savr::SkipMask* skip) const override
  {
    for (int i = 0; i < count; ++i)
    {
      this->Inner->SampleRay(ray, t0 + i * dt, dt, 1, out + i, skip);
    }
  }

private:
  std::shared_ptr<const savr::Sampler> Inner;
};

// The seconds of one pass at `step` in the engine, and its image in `image`.
double IdealPass(const savr::View& view, std::shared_ptr<const savr::Sampler> sampler,
  vtkVolumeProperty* property, double step, std::vector<float>& image)
{
  savr::FrameLoop loop;
  const double seconds = Seconds(
    [&]
    {
      savr::FrameSettings settings;
      settings.SampleDistance = step;
      settings.MaximumFrames = 1;
      settings.MemoryBudget = std::size_t(4) << 30;
      loop.Reset(view, std::move(sampler), settings);
      savr::TransferFunctionTable table;
      savr_benchmarks::BuildTable(loop.Encoding(), property, table);
      loop.AccumulateFrame(table, savr::BlendMode::Composite);
    });
  image = loop.Image();
  return seconds;
}

struct ResampledRow
{
  int Points;
  double ResampleSeconds;
  double FrameSeconds;
  double MiB;
  savr_scenes::ImageError Error;
};

std::vector<int> ParseSizes(const std::string& text)
{
  std::vector<int> sizes;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ','))
  {
    const int n = std::atoi(item.c_str());
    if (n >= 2)
    {
      sizes.push_back(n);
    }
  }
  return sizes;
}

struct Options
{
  int Size = 512;
  int Points = 2000000;
  int Clusters = 300;
  int Frames = 0;
  int Repeats = 3;
  int ReferenceFactor = 4;
  int PointQueryPass = 0;
  std::string Resample = "32,64,128,256";
  double FirstImageBound = 0.0;
};

// The command line into `o`; false (with the exit code in `code`) for --help or a bad option.
bool ParseOptions(int argc, char* argv[], Options& o, int& code)
{
  savr_scenes::Arguments arguments(argc, argv,
    "savr_particle_benchmark: vtkSAVRVolumeMapper on a clustered particle cloud next to ideal\n"
    "sampling and to vtkSPHInterpolator + vtkGPUVolumeRayCastMapper; prints times, memory and\n"
    "errors against a double-precision reference.");
  arguments.Option("--size", &o.Size, "Window width and height in pixels (512).");
  arguments.Option("--points", &o.Points, "Particles (2000000).");
  arguments.Option("--clusters", &o.Clusters, "Cluster centres (300).");
  arguments.Option("--frames", &o.Frames, "SAVR's frames (0: the mapper's choice).");
  arguments.Option("--repeats", &o.Repeats, "Camera moves measured (3).");
  arguments.Option(
    "--resample", &o.Resample, "Image sizes for vtkSPHInterpolator (32,64,128,256).");
  arguments.Option("--reference-factor", &o.ReferenceFactor,
    "The reference's step is SAVR's final step over this (4).");
  arguments.Option("--point-queries", &o.PointQueryPass,
    "1: also time ideal sampling with one index query per sample (slow; 0).");
  arguments.Option("--first-image", &o.FirstImageBound,
    "> 0: only time the first image of a fresh mapper whose MaximumRenderTime is this (ParaView's "
    "default is 0.2), and exit (0).");
  if (!arguments.Parse())
  {
    code = arguments.ExitCode();
    return false;
  }
  return true;
}

// SAVR's renders after camera moves, interleaved; the camera comes back to where the reference
// was taken at every other move.
struct SavrTimes
{
  std::vector<double> Interacting;
  std::vector<double> Accumulating;
  std::vector<double> Refine;
  // The last refinement's seconds so far and error at each render.
  std::vector<std::pair<double, savr_scenes::ImageError>> Progress;
};

SavrTimes MeasureSavr(
  savr_scenes::Scene& scene, vtkCamera* camera, const std::vector<float>& reference, int repeats)
{
  SavrTimes t;
  vtkSAVRVolumeMapper* mapper = scene.Mapper;
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(2.0);
    mapper->InteractiveOn();
    t.Interacting.push_back(Seconds([&] { scene.Window->Render(); }));
    mapper->InteractiveOff();
    camera->Azimuth(-2.0);
    double total = Seconds([&] { scene.Window->Render(); });
    t.Accumulating.push_back(total);
    t.Progress.clear();
    t.Progress.emplace_back(total, WindowError(scene.Window, reference));
    while (!mapper->GetRefinementComplete())
    {
      total += Seconds([&] { scene.Window->Render(); });
      t.Progress.emplace_back(total, WindowError(scene.Window, reference));
    }
    t.Refine.push_back(total);
  }
  return t;
}

// The cloud resampled to an n^3 image by vtkSPHInterpolator, drawn by the GPU mapper: the
// resampling's seconds, the median frame after camera moves and the error.
ResampledRow MeasureResampled(vtkPolyData* cloud, const double bounds[6], int n, double radius,
  vtkCamera* camera, int size, int repeats, const std::vector<float>& reference)
{
  ResampledRow row{ n, 0.0, 0.0, 0.0, {} };
  vtkSmartPointer<vtkImageData> image;
  row.ResampleSeconds =
    Seconds([&] { image = savr_scenes::ResampleCubic(cloud, bounds, n, radius); });
  row.MiB = image->GetPointData()->GetScalars()->GetActualMemorySize() / 1024.0;
  savr_scenes::Scene gpuScene(image, size, size);
  Prepare(gpuScene, camera);
  vtkNew<vtkGPUVolumeRayCastMapper> gpu;
  gpu->SetInputData(image);
  gpu->SetAutoAdjustSampleDistances(0);
  gpu->SetSampleDistance(0.5 * image->GetSpacing()[0]);
  gpuScene.Volume->SetMapper(gpu);
  gpuScene.Window->Render();
  std::vector<double> gpuFrames;
  for (int r = 0; r < repeats; ++r)
  {
    camera->Azimuth(2.0);
    gpuFrames.push_back(Seconds([&] { gpuScene.Window->Render(); }));
    camera->Azimuth(-2.0);
    gpuFrames.push_back(Seconds([&] { gpuScene.Window->Render(); }));
  }
  row.FrameSeconds = Median(gpuFrames);
  row.Error = WindowError(gpuScene.Window, reference);
  return row;
}

// Ideal sampling: one pass at SAVR's final step, in the engine (the mapper caps the samples of
// one frame and would refine instead; the engine alone also leaves out the window's work), and,
// when asked, with one index query per sample.
struct IdealTimes
{
  std::vector<double> Passes;
  savr_scenes::ImageError Error{};
  double PointQueries = 0.0;
  savr_scenes::ImageError PointQueriesError{};
};

IdealTimes MeasureIdeal(const savr::View& view, std::shared_ptr<const savr::Sampler> sampler,
  vtkVolumeProperty* property, double step, const std::vector<float>& reference, const Options& o)
{
  IdealTimes t;
  std::vector<float> image;
  for (int r = 0; r < o.Repeats; ++r)
  {
    t.Passes.push_back(IdealPass(view, sampler, property, step, image));
  }
  t.Error = savr_scenes::ErrorAgainst(image, reference, false);
  if (o.PointQueryPass)
  {
    t.PointQueries =
      IdealPass(view, std::make_shared<PointQueries>(sampler), property, step, image);
    t.PointQueriesError = savr_scenes::ErrorAgainst(image, reference, false);
  }
  return t;
}

void PrintSummary(double savrFirst, const SavrTimes& savr, const IdealTimes& ideal, int frames,
  bool pointQueryPass, double savrMiB)
{
  const double idealMedian = Median(ideal.Passes);
  const auto& first = savr.Progress.front().second;
  const auto& last = savr.Progress.back().second;
  std::printf("%-50s %10s %10s %10s %10s\n", "measurement (medians)", "seconds", "/ ideal", "RMSE",
    "max error");
  std::printf("%-50s %10.3f %10s %10s %10s\n", "SAVR first Render (builds the particle index)",
    savrFirst, "", "", "");
  std::printf("%-50s %10.3f %10.2f %10s %10s\n", "SAVR interacting frame", Median(savr.Interacting),
    Median(savr.Interacting) / idealMedian, "", "");
  std::printf("%-50s %10.3f %10.2f %10.2e %10.3f\n", "SAVR first accumulating frame",
    Median(savr.Accumulating), Median(savr.Accumulating) / idealMedian, first.Rmse, first.Max);
  std::printf("%-50s %10.3f %10.2f %10.2e %10.3f\n",
    ("SAVR refinement to completion (" + std::to_string(frames) + " frames)").c_str(),
    Median(savr.Refine), Median(savr.Refine) / idealMedian, last.Rmse, last.Max);
  std::printf("%-50s %10.3f %10.2f %10.2e %10.3f\n", "ideal sampling, one pass at the final step",
    idealMedian, 1.0, ideal.Error.Rmse, ideal.Error.Max);
  if (pointQueryPass)
  {
    std::printf("%-50s %10.3f %10.2f %10.2e %10.3f\n",
      "ideal sampling, one query per sample (once)", ideal.PointQueries,
      ideal.PointQueries / idealMedian, ideal.PointQueriesError.Rmse, ideal.PointQueriesError.Max);
    std::printf("ratios to one query per sample: SAVR interacting frame %.3f, refinement %.3f\n",
      Median(savr.Interacting) / ideal.PointQueries, Median(savr.Refine) / ideal.PointQueries);
  }
  std::printf("SAVR memory in use: %.1f MiB\n\n", savrMiB);
}

void PrintResampled(const std::vector<ResampledRow>& rows, const SavrTimes& savr)
{
  std::printf("%-8s %12s %10s %8s %10s %10s %16s %16s\n", "image", "resample (s)", "frame (s)",
    "MiB", "RMSE", "max error", "SAVR RMSE then", "SAVR there (s)");
  for (const ResampledRow& row : rows)
  {
    // SAVR's error at the last frame it finished within the resampled path's first image
    // (resampling and one frame), and when SAVR's error first fell to the image's.
    const double budget = row.ResampleSeconds + row.FrameSeconds;
    std::string then = "(no frame yet)";
    std::string there = "(not reached)";
    for (const auto& p : savr.Progress)
    {
      char text[32];
      if (p.first <= budget)
      {
        std::snprintf(text, sizeof(text), "%.2e", p.second.Rmse);
        then = text;
      }
      if (p.second.Rmse <= row.Error.Rmse && there[0] == '(')
      {
        std::snprintf(text, sizeof(text), "%.3f", p.first);
        there = text;
      }
    }
    std::printf("%-8s %12.3f %10.3f %8.1f %10.2e %10.3f %16s %16s\n",
      (std::to_string(row.Points) + "^3").c_str(), row.ResampleSeconds, row.FrameSeconds, row.MiB,
      row.Error.Rmse, row.Error.Max, then.c_str(), there.c_str());
  }
}
} // namespace

// The first image of the cloud in a fresh mapper whose renders are bounded by `bound` seconds:
// the first Render's seconds (the particle index built, part of the first frame sampled, the
// rest previewed with fewer rays), the part of the frame it sampled, the part of the window it
// covers against the complete first frame's, and the renders and seconds that frame takes.
void MeasureFirstImage(vtkPolyData* cloud, double radius, const Options& o)
{
  const auto scene = [&](savr_scenes::Scene& s)
  {
    s.Renderer->GetActiveCamera()->Zoom(1.6);
    Prepare(s, s.Renderer->GetActiveCamera());
    s.Mapper->SetParticleKernel(vtkSAVRParticleSampler::SPH_CUBIC);
    s.Mapper->SetParticleRadius(radius);
    s.Mapper->SetMemoryBudget(vtkTypeUInt64(4) << 30);
  };
  savr_scenes::Scene bounded(cloud, o.Size, o.Size);
  scene(bounded);
  bounded.Mapper->SetMaximumRenderTime(o.FirstImageBound);
  const double first = Seconds([&] { bounded.Window->Render(); });
  const double sampled = bounded.Mapper->GetFrameInProgress();
  const double background[3] = { 0.0, 0.0, 0.0 };
  const double covered =
    savr_scenes::CoveredFraction(savr_scenes::Capture(bounded.Window), background);
  double total = first;
  int renders = 1;
  while (bounded.Mapper->GetNumberOfFramesAccumulated() == 0 && renders < 100000)
  {
    total += Seconds([&] { bounded.Window->Render(); });
    ++renders;
  }
  const double complete =
    savr_scenes::CoveredFraction(savr_scenes::Capture(bounded.Window), background);
  std::printf("first image, MaximumRenderTime %g, %dx%d: first Render %.3f s, %.2f%% of the "
              "first frame sampled, window covered %.3f (the complete frame covers %.3f); the "
              "frame took %d renders, %.2f s\n",
    o.FirstImageBound, o.Size, o.Size, first, 100.0 * sampled, covered, complete, renders, total);
}

int main(int argc, char* argv[])
{
  Options o;
  int code = 0;
  if (!ParseOptions(argc, argv, o, code))
  {
    return code;
  }
  vtkSmartPointer<vtkPolyData> cloud;
  const double cloudSeconds =
    Seconds([&] { cloud = savr_scenes::ClusteredCloud(o.Points, o.Clusters); });
  const double radius = vtkSAVRParticleSampler::AutomaticRadius(cloud);
  std::printf("scene: %d particles around %d centres (made in %.1f s), SPH cubic kernel, radius "
              "%.3f, normalized; window %dx%d, %d repeats\n",
    o.Points, o.Clusters, cloudSeconds, radius, o.Size, o.Size, o.Repeats);
  if (o.FirstImageBound > 0.0)
  {
    MeasureFirstImage(cloud, radius, o);
    return EXIT_SUCCESS;
  }

  savr_scenes::Scene savrScene(cloud, o.Size, o.Size);
  vtkCamera* camera = savrScene.Renderer->GetActiveCamera();
  camera->Zoom(1.6);
  Prepare(savrScene, camera);
  vtkSAVRVolumeMapper* mapper = savrScene.Mapper;
  mapper->SetParticleKernel(vtkSAVRParticleSampler::SPH_CUBIC);
  mapper->SetParticleRadius(radius);
  mapper->SetMemoryBudget(vtkTypeUInt64(4) << 30);
  mapper->SetMaximumNumberOfFrames(o.Frames);
  const double savrFirst = Seconds([&] { savrScene.Window->Render(); });
  const double baseStep = mapper->GetEffectiveSampleDistance();
  while (!mapper->GetRefinementComplete())
  {
    savrScene.Window->Render();
  }
  const int frames = mapper->GetNumberOfFramesAccumulated();
  const double finalStep = baseStep / frames;

  // The reference through the same particles.
  vtkNew<vtkSAVRParticleSampler> adaptor;
  if (!adaptor->Build(cloud, cloud->GetPointData()->GetScalars(), radius,
        static_cast<vtkDataArray*>(nullptr), vtkSAVRParticleSampler::SPH_CUBIC, true, nullptr))
  {
    std::fprintf(stderr, "cannot sample the particles: %s\n", adaptor->GetErrorMessage().c_str());
    return EXIT_FAILURE;
  }
  const double referenceStep = finalStep / o.ReferenceFactor;
  std::vector<float> reference;
  const double referenceSeconds = Seconds(
    [&]
    {
      reference = savr_benchmarks::Reference(savr_benchmarks::ViewOf(camera, o.Size, o.Size),
        *adaptor->GetSampler(), savrScene.Property, referenceStep);
    });
  std::printf("SAVR base step %g, %d frames (final step %g); reference at step %g computed in "
              "%.1f s\n\n",
    baseStep, frames, finalStep, referenceStep, referenceSeconds);

  const SavrTimes savr = MeasureSavr(savrScene, camera, reference, o.Repeats);
  const double savrMiB = mapper->GetMemoryInUse() / 1048576.0;
  const IdealTimes ideal = MeasureIdeal(savr_benchmarks::ViewOf(camera, o.Size, o.Size),
    adaptor->GetSampler(), savrScene.Property, finalStep, reference, o);

  double bounds[6];
  vtkSAVRParticleSampler::SupportBounds(
    cloud, radius, nullptr, vtkSAVRParticleSampler::SPH_CUBIC, bounds);
  std::vector<ResampledRow> rows;
  for (int n : ParseSizes(o.Resample))
  {
    rows.push_back(
      MeasureResampled(cloud, bounds, n, radius, camera, o.Size, o.Repeats, reference));
  }

  PrintSummary(savrFirst, savr, ideal, frames, o.PointQueryPass != 0, savrMiB);
  PrintResampled(rows, savr);
  return EXIT_SUCCESS;
}

// Convergence report: error against wall-clock time for three ways of refining the same rays.
//
//   savr_convergence [--scene wavelet|head|particles|FILE.vti|FILE.vtu|FILE.vthb|FILE.nii[.gz]]
//                    [--size 256] [--step S]
//                    [--frames 64] [--reference-factor 256] [--tf tf.json]
//                    [--opacity "v:a,v:a,..."] [--color "v:r:g:b,..."] [--unit U]
//                    [--csv out.csv] [--plot out.png] [--title TEXT] [--check 1]
//
// With --check 1 the program fails unless SAVR matches ideal sampling at every power of two of
// frames (to 1e-5 RMSE) and ends below frame averaging's error.
// A file scene renders its first one-component point array (else its first cell array): an
// image, an unstructured grid or an AMR hierarchy, each through the mapper's own sampler. The
// scene "particles" is a clustered cloud of 200,000 particles (SAVRParticleScenes.h) drawn as
// the mapper draws particles by default (a Gaussian of the automatic radius, normalized).
// Methods, all on the rays of one camera, at base step S (default: the smallest spacing, the
// typical cell size of an unstructured grid, the finest level's spacing of an AMR hierarchy):
// - SAVR: frame K samples every ray at one new offset, keeps all samples, re-blends them all;
// - frame averaging: frame K is a jittered single pass at step S, and the image is the mean of
//   the K passes (image-space progressive rendering, Usher et al.'s Eq. 2);
// - ideal sampling: one pass at step S / K (the image SAVR equals at powers of two), timed alone.
// Error is measured on premultiplied RGBA in [0, 1] against a reference integrated in double
// precision, with the transfer function evaluated exactly, at step S / reference-factor:
// RMSE, PSNR (20 log10 1/RMSE) and the largest absolute error, per frame, with cumulative time;
// and the RMSE against a second reference, the engine's pre-integrated blend at the same fine
// step.
// The transfer-function JSON file is {"color": [[v, r, g, b], ...], "opacity": [[v, a], ...],
// "unitDistance": u}.

#include "SAVRArguments.h"
#include "SAVRBenchmarkSupport.h"
#include "SAVRParticleScenes.h"

#include "reference/ReferenceIntegrator.h"
#include "frame/FrameLoop.h"
#include "frame/OffsetSequence.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContextScene.h"
#include "vtkContextView.h"
#include "vtkDoubleArray.h"
#include "vtkMatrix4x4.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkTable.h"
#include "vtkWindowToImageFilter.h"
#include "vtk_jsoncpp.h"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace
{
struct Options
{
  std::string Scene = "wavelet";
  int Size = 256;
  double Step = 0.0;
  int Frames = 64;
  int ReferenceFactor = 256;
  std::string TransferFunctionFile;
  std::string Opacity;
  std::string Color;
  double Unit = 0.0;
  std::string Csv;
  std::string Plot;
  std::string Title;
  bool Check = false;
  bool PreIntegration = false;
};

struct Row
{
  std::string Method;
  int Frames;
  double Seconds;
  double Rmse;
  double Psnr;
  double MaxError;
  double RmseSecond; // against the pre-integrated reference
};

double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::vector<std::vector<double>> ParseList(const std::string& text, std::size_t width)
{
  std::vector<std::vector<double>> points;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ','))
  {
    std::vector<double> point;
    std::stringstream fields(item);
    std::string field;
    while (std::getline(fields, field, ':'))
    {
      point.push_back(std::atof(field.c_str()));
    }
    if (point.size() == width)
    {
      points.push_back(point);
    }
  }
  return points;
}

bool LoadTransferFunctionFile(const std::string& file, vtkVolumeProperty* property)
{
  std::ifstream in(file);
  Json::Value root;
  Json::CharReaderBuilder builder;
  std::string errors;
  if (!in || !Json::parseFromStream(builder, in, &root, &errors))
  {
    std::fprintf(stderr, "cannot read %s: %s\n", file.c_str(), errors.c_str());
    return false;
  }
  vtkNew<vtkColorTransferFunction> color;
  for (const Json::Value& p : root["color"])
  {
    color->AddRGBPoint(p[0].asDouble(), p[1].asDouble(), p[2].asDouble(), p[3].asDouble());
  }
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const Json::Value& p : root["opacity"])
  {
    opacity->AddPoint(p[0].asDouble(), p[1].asDouble());
  }
  if (color->GetSize() == 0 || opacity->GetSize() == 0)
  {
    std::fprintf(stderr, "%s needs \"color\" and \"opacity\" points\n", file.c_str());
    return false;
  }
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  if (root.isMember("unitDistance"))
  {
    property->SetScalarOpacityUnitDistance(root["unitDistance"].asDouble());
  }
  return true;
}

vtkSmartPointer<vtkDataObject> LoadScene(const std::string& scene)
{
  if (scene == "wavelet")
  {
    return savr_scenes::Wavelet();
  }
  if (scene == "head")
  {
    return savr_scenes::Head();
  }
  if (scene == "particles")
  {
    return savr_scenes::ClusteredCloud(200000, 40);
  }
  std::string error;
  vtkSmartPointer<vtkDataObject> data = savr_scenes::ReadDataFile(scene, error);
  if (!data)
  {
    std::fprintf(stderr, "%s (or use the scene wavelet, head or particles)\n", error.c_str());
  }
  return data;
}

void Measure(Row& row, const std::vector<float>& image, const std::vector<float>& reference,
  const std::vector<float>& second)
{
  row.RmseSecond = savr_scenes::ErrorAgainst(image, second).Rmse;
  const savr_scenes::ImageError error = savr_scenes::ErrorAgainst(image, reference);
  row.Rmse = error.Rmse;
  row.Psnr = row.Rmse > 0.0 ? 20.0 * std::log10(1.0 / row.Rmse) : INFINITY;
  row.MaxError = error.Max;
}

void WritePlot(const std::vector<Row>& rows, const Options& options)
{
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(900, 600);
  view->GetRenderer()->SetBackground(1, 1, 1);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  chart->SetTitle(options.Title.empty() ? "Error against time" : options.Title);
  const char* methods[] = { "SAVR", "frame averaging", "ideal sampling" };
  const unsigned char colors[3][3] = { { 200, 40, 40 }, { 40, 90, 200 }, { 30, 150, 60 } };
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (int m = 0; m < 3; ++m)
  {
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> time;
    time->SetName("seconds");
    vtkNew<vtkDoubleArray> error;
    error->SetName(methods[m]);
    for (const Row& row : rows)
    {
      if (row.Method == methods[m] && row.Rmse > 0.0)
      {
        time->InsertNextValue(row.Seconds);
        error->InsertNextValue(row.Rmse);
      }
    }
    table->AddColumn(time);
    table->AddColumn(error);
    tables.push_back(table);
    vtkPlot* line = chart->AddPlot(vtkChart::LINE);
    line->SetInputData(table, 0, 1);
    line->SetColor(colors[m][0], colors[m][1], colors[m][2], 255);
    line->SetWidth(2.5);
  }
  vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
  x->SetTitle("wall-clock seconds (cumulative; ideal sampling: one pass)");
  x->SetLogScale(true);
  vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
  y->SetTitle("RMSE of premultiplied RGBA");
  y->SetLogScale(true);
  view->GetRenderWindow()->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(view->GetRenderWindow());
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(options.Plot.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
}
// The transfer function: the scene's default, a JSON file, or points on the command line.
bool SetUpProperty(const Options& options, vtkVolumeProperty* property)
{
  if (options.Scene == "head")
  {
    savr_scenes::HeadProperty(property);
  }
  else if (options.Scene == "particles")
  {
    savr_scenes::CloudProperty(property);
  }
  else
  {
    savr_scenes::WaveletProperty(property);
  }
  if (!options.TransferFunctionFile.empty() &&
      !LoadTransferFunctionFile(options.TransferFunctionFile, property))
  {
    return false;
  }
  if (!options.Opacity.empty())
  {
    vtkNew<vtkPiecewiseFunction> opacity;
    for (const auto& p : ParseList(options.Opacity, 2))
    {
      opacity->AddPoint(p[0], p[1]);
    }
    property->SetScalarOpacity(opacity);
  }
  if (!options.Color.empty())
  {
    vtkNew<vtkColorTransferFunction> color;
    for (const auto& p : ParseList(options.Color, 4))
    {
      color->AddRGBPoint(p[0], p[1], p[2], p[3]);
    }
    property->SetColor(color);
  }
  if (options.Unit > 0.0)
  {
    property->SetScalarOpacityUnitDistance(options.Unit);
  }
  return true;
}

// SAVR equals ideal sampling at every power of two of frames, and ends below frame averaging.
bool Check(const std::vector<Row>& rows)
{
  bool ok = true;
  double savrLast = 0.0;
  double averagingLast = 0.0;
  for (const Row& row : rows)
  {
    if (row.Method == "SAVR")
      savrLast = row.Rmse;
    if (row.Method == "frame averaging")
      averagingLast = row.Rmse;
    if (row.Method != "ideal sampling")
      continue;
    for (const Row& savr : rows)
    {
      if (savr.Method == "SAVR" && savr.Frames == row.Frames &&
          std::abs(savr.Rmse - row.Rmse) > 1e-5)
      {
        std::printf("FAILED: SAVR after %d frames differs from ideal sampling\n", row.Frames);
        ok = false;
      }
    }
  }
  if (!(savrLast < averagingLast))
  {
    std::printf("FAILED: SAVR ends at %g, frame averaging at %g\n", savrLast, averagingLast);
    ok = false;
  }
  std::printf("%s\n", ok ? "check passed" : "check failed");
  return ok;
}

// Reads the command line into `options`; false, with the program's exit code, when it should
// end.
bool ParseOptions(int argc, char* argv[], Options& options, int& exitCode)
{
  int check = 0;
  int preIntegration = 0;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_convergence: error against wall-clock time for SAVR, frame averaging and ideal "
    "sampling\nof the same rays, against a reference integrated in double precision.");
  arguments.Option("--scene", &options.Scene,
    "wavelet, head, particles, or a .vti, .vtu, .vthb, .nii or .nii.gz file (wavelet).");
  arguments.Option("--size", &options.Size, "Image width and height in pixels (256).");
  arguments.Option("--step", &options.Step,
    "Base step (0: the smallest spacing, typical cell size or finest AMR spacing).");
  arguments.Option("--frames", &options.Frames, "Frames to accumulate (64).");
  arguments.Option(
    "--reference-factor", &options.ReferenceFactor, "Reference step = step / factor (256).");
  arguments.Option("--tf", &options.TransferFunctionFile,
    "Transfer function JSON: {\"color\": [[v, r, g, b], ...], \"opacity\": [[v, a], ...], "
    "\"unitDistance\": u}.");
  arguments.Option("--opacity", &options.Opacity, "Opacity points \"v:a,v:a,...\".");
  arguments.Option("--color", &options.Color, "Colour points \"v:r:g:b,...\".");
  arguments.Option("--unit", &options.Unit, "Scalar opacity unit distance (0: the scene's).");
  arguments.Option("--csv", &options.Csv, "Write every frame's errors to this CSV file.");
  arguments.Option("--plot", &options.Plot, "Write the error-against-time plot to this PNG.");
  arguments.Option("--title", &options.Title, "The plot's title.");
  arguments.Option("--check", &check,
    "1: fail unless SAVR equals ideal sampling at powers of two and ends below frame "
    "averaging.");
  arguments.Option("--pre-integration", &preIntegration,
    "1: every method blends pre-integrated segments instead of point samples.");
  if (!arguments.Parse())
  {
    exitCode = arguments.ExitCode();
    return false;
  }
  options.Check = check == 1;
  options.PreIntegration = preIntegration == 1;
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
  if (options.Size < 1 || options.Frames < 1 || options.ReferenceFactor < 1)
  {
    std::fprintf(stderr, "--size, --frames and --reference-factor must be positive\n");
    return EXIT_FAILURE;
  }

  vtkSmartPointer<vtkDataObject> data = LoadScene(options.Scene);
  if (!data)
  {
    return EXIT_FAILURE;
  }

  vtkNew<vtkVolumeProperty> property;
  if (!SetUpProperty(options, property))
  {
    return EXIT_FAILURE;
  }

  // The sampler and a camera framing the data, as the tests use.
  double spacing = 1.0;
  std::string error;
  std::shared_ptr<const savr::Sampler> sampler = savr_benchmarks::SamplerFor(data, spacing, error);
  if (!sampler)
  {
    std::fprintf(stderr, "cannot sample %s: %s\n", options.Scene.c_str(), error.c_str());
    return EXIT_FAILURE;
  }
  savr_scenes::Scene framing(data, options.Size, options.Size);
  if (options.Scene == "head")
  {
    savr_scenes::FaceTheHead(framing.Renderer);
  }
  const savr::View view =
    savr_benchmarks::ViewOf(framing.Renderer->GetActiveCamera(), options.Size, options.Size);
  const double step = options.Step > 0.0 ? options.Step : spacing;

  // Transfer-function tables for the engine.
  savr::FrameSettings settings;
  settings.SampleDistance = step;
  settings.MaximumFrames = options.Frames;
  settings.MemoryBudget = std::size_t(8) << 30;
  // The integral itself: rays stop where less than 1e-6 of the light comes through (the mapper
  // stops them at 1/512, which adds at most that per channel).
  settings.Termination = 1e-6;
  // Stored as the mapper stores them: with fractional bits for features narrower than a level.
  settings.FineCodes =
    savr_benchmarks::NeedsFineCodes(savr::SampleEncoding::ForSampler(*sampler), property);
  const savr::BlendMode mode =
    options.PreIntegration ? savr::BlendMode::PreIntegrated : savr::BlendMode::Composite;
  savr::FrameLoop loop;
  loop.Reset(view, sampler, settings);
  savr::TransferFunctionTable table;
  savr_benchmarks::BuildTable(loop.Encoding(), property, table);

  std::printf("scene %s, %dx%d pixels, base step %g, %d frames, reference step %g\n",
    options.Scene.c_str(), options.Size, options.Size, step, options.Frames,
    step / options.ReferenceFactor);
  double t = Now();
  const std::vector<float> reference =
    savr_benchmarks::Reference(view, *sampler, property, step / options.ReferenceFactor);
  std::printf("reference computed in %.1f s\n", Now() - t);
  // The second reference: the engine's pre-integrated blend of its own samples at the same fine
  // step (stored precision, pre-integrated segments).
  savr::FrameLoop fine;
  fine.Reset(view, sampler, settings);
  fine.RenderSinglePass(table, savr::BlendMode::PreIntegrated, step / options.ReferenceFactor, 0.0);
  const std::vector<float> second = fine.Image();
  std::printf(
    "RMSE between the two references: %.3e\n", savr_scenes::ErrorAgainst(second, reference).Rmse);

  std::vector<Row> rows;
  // SAVR.
  double total = 0.0;
  for (int k = 1; k <= options.Frames; ++k)
  {
    t = Now();
    loop.AccumulateFrame(table, mode);
    total += Now() - t;
    Row row{ "SAVR", k, total, 0, 0, 0, 0 };
    Measure(row, loop.Image(), reference, second);
    rows.push_back(row);
  }
  // Frame averaging: the mean of jittered single passes at the base step.
  savr::FrameLoop passes;
  passes.Reset(view, sampler, settings);
  std::vector<double> sum(reference.size(), 0.0);
  std::vector<float> mean(reference.size(), 0.0f);
  total = 0.0;
  for (int k = 1; k <= options.Frames; ++k)
  {
    t = Now();
    passes.RenderSinglePass(table, mode, step, savr::RadicalInverse2(k - 1));
    const std::vector<float>& image = passes.Image();
    for (std::size_t i = 0; i < image.size(); ++i)
    {
      sum[i] += image[i];
      mean[i] = static_cast<float>(sum[i] / k);
    }
    total += Now() - t;
    Row row{ "frame averaging", k, total, 0, 0, 0, 0 };
    Measure(row, mean, reference, second);
    rows.push_back(row);
  }
  // Ideal sampling: one pass at step / K, timed alone.
  for (int k = 1; k <= options.Frames; k *= 2)
  {
    t = Now();
    passes.RenderSinglePass(table, mode, step / k, 0.0);
    Row row{ "ideal sampling", k, Now() - t, 0, 0, 0, 0 };
    Measure(row, passes.Image(), reference, second);
    rows.push_back(row);
  }

  std::printf(
    "\n%-16s %7s %12s %12s %9s %12s\n", "method", "frames", "seconds", "RMSE", "PSNR", "max error");
  for (const Row& row : rows)
  {
    if ((row.Frames & (row.Frames - 1)) == 0)
    {
      std::printf("%-16s %7d %12.4f %12.3e %9.2f %12.3e %14.3e\n", row.Method.c_str(), row.Frames,
        row.Seconds, row.Rmse, row.Psnr, row.MaxError, row.RmseSecond);
    }
  }
  if (!options.Csv.empty())
  {
    std::ofstream csv(options.Csv);
    csv << "method,frames,seconds,rmse,psnr,max_error,rmse_vs_preintegrated_reference\n";
    for (const Row& row : rows)
    {
      csv << row.Method << "," << row.Frames << "," << row.Seconds << "," << row.Rmse << ","
          << row.Psnr << "," << row.MaxError << "," << row.RmseSecond << "\n";
    }
    std::printf("wrote %s\n", options.Csv.c_str());
  }
  if (!options.Plot.empty())
  {
    WritePlot(rows, options);
    std::printf("wrote %s\n", options.Plot.c_str());
  }
  if (options.Check)
  {
    return Check(rows) ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}

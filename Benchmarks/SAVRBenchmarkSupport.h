#pragma once
// What the benchmarks share: timing, medians, the double-precision reference image of a volume
// property's transfer functions, the engine's view of a VTK camera, and samplers for any input.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkSAVRAMRSampler.h"
#include "vtkSAVRImageSampler.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRUnstructuredSampler.h"

#include "frame/FrameLoop.h"
#include "reference/ReferenceIntegrator.h"
#include "sampler/Sampler.h"
#include "blend/TransferFunctionTable.h"
#include "frame/View.h"

#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkMatrix4x4.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPolyData.h"
#include "vtkUniformGrid.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace savr_benchmarks
{

inline double Seconds(const std::function<void()>& work)
{
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

/// RGB of the window against a reference's premultiplied RGB (over black).
inline savr_scenes::ImageError WindowError(
  vtkRenderWindow* window, const std::vector<float>& reference)
{
  return savr_scenes::ErrorAgainst(
    savr_scenes::FloatRGBA(savr_scenes::Capture(window)), reference, false);
}

/// The engine's view of `camera` for a window of width x height pixels.
inline savr::View ViewOf(vtkCamera* camera, int width, int height)
{
  vtkMatrix4x4* worldToNDC =
    camera->GetCompositeProjectionTransformMatrix(static_cast<double>(width) / height, -1, 1);
  savr::View view;
  view.Width = width;
  view.Height = height;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      view.NDCToWorld(r, c) = worldToNDC->GetElement(r, c);
    }
  }
  view.NDCToWorld = view.NDCToWorld.inverse().eval();
  return view;
}

/// A sampler of the first one-component array (points first, then cells; the ghost-type array
/// excepted) of an image, an unstructured grid, an AMR hierarchy or particles (the points of a
/// vtkPolyData), and the data's typical cell edge (half the particles' radius) in `spacing`;
/// null, with the reason in `error`, when there is none.
inline std::shared_ptr<const savr::Sampler> SamplerFor(
  vtkDataObject* data, double& spacing, std::string& error)
{
  auto* amr = vtkOverlappingAMR::SafeDownCast(data);
  bool cells = false;
  vtkDataArray* array = savr_scenes::FirstScalarArray(data, cells);
  if (!array)
  {
    error = "no one-component array";
    return nullptr;
  }
  if (auto* image = vtkImageData::SafeDownCast(data))
  {
    vtkNew<vtkSAVRImageSampler> adaptor;
    if (!adaptor->Build(image, array, cells, nullptr, VTK_LINEAR_INTERPOLATION))
    {
      error = adaptor->GetErrorMessage();
      return nullptr;
    }
    const double* h = image->GetSpacing();
    spacing = std::min({ std::abs(h[0]), std::abs(h[1]), std::abs(h[2]) });
    return adaptor->GetSampler();
  }
  if (auto* particles = vtkPolyData::SafeDownCast(data))
  {
    // As the mapper draws them by default: a Gaussian of the automatic radius, normalized.
    vtkNew<vtkSAVRParticleSampler> adaptor;
    if (!adaptor->Build(particles, array, 0.0, static_cast<vtkDataArray*>(nullptr),
          vtkSAVRParticleSampler::GAUSSIAN, true, nullptr))
    {
      error = adaptor->GetErrorMessage();
      return nullptr;
    }
    spacing = 0.5 * adaptor->GetTypicalRadius();
    return adaptor->GetSampler();
  }
  if (auto* grid = vtkUnstructuredGrid::SafeDownCast(data))
  {
    vtkNew<vtkSAVRUnstructuredSampler> adaptor;
    if (!adaptor->Build(grid, array, cells, nullptr))
    {
      error = adaptor->GetErrorMessage();
      return nullptr;
    }
    spacing = adaptor->GetTypicalCellSize();
    return adaptor->GetSampler();
  }
  if (amr)
  {
    vtkNew<vtkSAVRAMRSampler> adaptor;
    if (!adaptor->Build(amr,
          cells ? VTK_SCALAR_MODE_USE_CELL_FIELD_DATA : VTK_SCALAR_MODE_USE_POINT_FIELD_DATA,
          VTK_GET_ARRAY_BY_NAME, 0, array->GetName(), nullptr, VTK_LINEAR_INTERPOLATION))
    {
      error = adaptor->GetErrorMessage();
      return nullptr;
    }
    spacing = adaptor->GetFinestSpacing();
    return adaptor->GetSampler();
  }
  error = std::string("unsupported data type ") + data->GetClassName();
  return nullptr;
}

// The double-precision reference at `step`, with the transfer function taken from a table fine
// enough to be exact for piecewise-linear functions between its points (2^20 entries, linear
// interpolation).
inline std::vector<float> Reference(
  const savr::View& view, const savr::Sampler& sampler, vtkVolumeProperty* property, double step)
{
  const auto range = sampler.ValueRange();
  const int n = 1 << 20;
  auto rgb = std::make_shared<std::vector<double>>(3 * n);
  auto alpha = std::make_shared<std::vector<double>>(n);
  const double lo = range[0];
  const double hi = range[1] > range[0] ? range[1] : range[0] + 1.0;
  property->GetRGBTransferFunction(0)->GetTable(lo, hi, n, rgb->data());
  property->GetScalarOpacity(0)->GetTable(lo, hi, n, alpha->data());
  // Position of a value in the table: entry k and the weight of entry k + 1.
  const auto locate = [=](double v, int& k, double& w)
  {
    const double f = std::min(std::max((v - lo) / (hi - lo) * (n - 1), 0.0), n - 1.0);
    k = std::min(static_cast<int>(f), n - 2);
    w = f - k;
  };
  savr::ReferenceTransferFunction tf;
  tf.Color = [=](double v)
  {
    int k;
    double w;
    locate(v, k, w);
    const double* c = rgb->data() + 3 * k;
    return Eigen::Vector3d(
      c[0] + w * (c[3] - c[0]), c[1] + w * (c[4] - c[1]), c[2] + w * (c[5] - c[2]));
  };
  tf.Opacity = [=](double v)
  {
    int k;
    double w;
    locate(v, k, w);
    return (*alpha)[k] + w * ((*alpha)[k + 1] - (*alpha)[k]);
  };
  tf.UnitDistance = property->GetScalarOpacityUnitDistance(0);
  return savr::ReferenceImage(view, sampler, tf, step);
}

/// Whether `property`'s functions (component 0, RGB colour) have features narrower than one
/// code of `encoding`: the rule the mapper stores samples with fractional bits by.
inline bool NeedsFineCodes(const savr::SampleEncoding& encoding, vtkVolumeProperty* property)
{
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);
  vtkColorTransferFunction* color = property->GetRGBTransferFunction(0);
  std::vector<double> nodes;
  double node[6];
  for (int i = 0; i < opacity->GetSize(); ++i)
  {
    opacity->GetNodeValue(i, node);
    nodes.push_back(node[0]);
  }
  for (int i = 0; i < color->GetSize(); ++i)
  {
    color->GetNodeValue(i, node);
    nodes.push_back(node[0]);
  }
  return encoding.HasFeaturesBetweenCodes(
    nodes.data(), nodes.size(), [&](double v) { return opacity->GetValue(v); },
    [&](double v, double rgb[3]) { color->GetColor(v, rgb); });
}

/// The engine's transfer-function table of `property` (component 0) for `encoding`.
inline void BuildTable(const savr::SampleEncoding& encoding, vtkVolumeProperty* property,
  savr::TransferFunctionTable& table)
{
  std::vector<double> rgb(3 * encoding.Levels);
  std::vector<double> alpha(encoding.Levels);
  const double lo = encoding.Decode(0);
  const double hi = encoding.Decode(encoding.Levels - 1);
  property->GetRGBTransferFunction(0)->GetTable(lo, hi, encoding.Levels, rgb.data());
  property->GetScalarOpacity(0)->GetTable(lo, hi, encoding.Levels, alpha.data());
  table.Build(encoding, rgb.data(), alpha.data(), property->GetScalarOpacityUnitDistance(0));
}

} // namespace savr_benchmarks

#include "SAVRParticleScenes.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkSPHCubicKernel.h"
#include "vtkSPHInterpolator.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace savr_scenes
{
namespace
{
// Uniform in (0, 1] from 24 bits of a Mersenne twister, whose sequence the standard fixes (the
// standard distributions' are not).
class Uniform
{
public:
  explicit Uniform(unsigned seed)
    : Engine(seed)
  {
  }
  double operator()() { return ((this->Engine() >> 8) + 1) * (1.0 / 16777216.0); }

private:
  std::mt19937 Engine;
};

struct Cluster
{
  double Center[3];
  double Scale;
  double Brightness;
};
} // namespace

vtkSmartPointer<vtkPolyData> ClusteredCloud(long long points, int clusters, unsigned seed)
{
  Uniform random(seed);
  std::vector<Cluster> centres(std::max(clusters, 1));
  for (Cluster& c : centres)
  {
    for (double& x : c.Center)
    {
      x = -50.0 + 100.0 * random();
    }
    c.Scale = 1.5 * std::pow(8.0 / 1.5, random());
    c.Brightness = 0.4 + 0.6 * random();
  }
  vtkNew<vtkPoints> positions;
  positions->SetDataTypeToFloat();
  positions->SetNumberOfPoints(points);
  vtkNew<vtkFloatArray> values;
  values->SetName("value");
  values->SetNumberOfTuples(points);
  constexpr double Pi = 3.14159265358979323846;
  for (long long i = 0; i < points; ++i)
  {
    const Cluster& c = centres[i % static_cast<long long>(centres.size())];
    const double d = std::min(c.Scale * (1.0 / std::sqrt(random()) - 1.0), 6.0 * c.Scale);
    const double z = 2.0 * random() - 1.0;
    const double phi = 2.0 * Pi * random();
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    positions->SetPoint(i, c.Center[0] + d * rho * std::cos(phi),
      c.Center[1] + d * rho * std::sin(phi), c.Center[2] + d * z);
    values->SetValue(i, static_cast<float>(c.Brightness * std::exp(-d / c.Scale)));
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(positions);
  cloud->GetPointData()->SetScalars(values);
  return cloud;
}

void CloudProperty(vtkVolumeProperty* property)
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.1, 0.1, 0.6);
  color->AddRGBPoint(0.25, 0.45, 0.2, 0.8);
  color->AddRGBPoint(0.55, 0.95, 0.5, 0.15);
  color->AddRGBPoint(1.0, 1.0, 1.0, 0.85);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.1, 0.0);
  opacity->AddPoint(0.3, 0.05);
  opacity->AddPoint(0.6, 0.3);
  opacity->AddPoint(1.0, 0.8);
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(1.0);
}

vtkSmartPointer<vtkImageData> ResampleCubic(
  vtkPolyData* cloud, const double bounds[6], int points, double radius)
{
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(points, points, points);
  grid->SetOrigin(bounds[0], bounds[2], bounds[4]);
  grid->SetSpacing((bounds[1] - bounds[0]) / (points - 1), (bounds[3] - bounds[2]) / (points - 1),
    (bounds[5] - bounds[4]) / (points - 1));
  vtkNew<vtkSPHCubicKernel> kernel;
  kernel->SetSpatialStep(radius);
  kernel->SetDimension(3);
  vtkNew<vtkSPHInterpolator> interpolator;
  interpolator->SetInputData(grid);
  interpolator->SetSourceData(cloud);
  interpolator->SetKernel(kernel);
  interpolator->ShepardNormalizationOn();
  interpolator->SetNullPointsStrategyToNullValue();
  interpolator->SetNullValue(0.0);
  interpolator->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(interpolator->GetOutput());
  if (vtkDataArray* scalars = cloud->GetPointData()->GetScalars())
  {
    image->GetPointData()->SetActiveScalars(scalars->GetName());
  }
  return image;
}

} // namespace savr_scenes

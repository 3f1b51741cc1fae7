#include "vtkSAVRParticleSampler.h"

#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSAVRVTKVersions.h"
#include "vtkUnstructuredGrid.h"

#include "particles/ParticleSampler.h"

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkSAVRParticleSampler);

vtkSAVRParticleSampler::vtkSAVRParticleSampler() = default;
vtkSAVRParticleSampler::~vtkSAVRParticleSampler() = default;

bool vtkSAVRParticleSampler::Build(vtkPointSet* points, vtkDataArray* scalars, double radius,
  vtkDataArray* radii, int kernel, bool normalized, vtkMatrix4x4* volumeMatrix)
{
  this->Sampler.reset();
  this->ErrorMessage.clear();
  this->SkippedParticles = 0;
  this->TypicalRadius = 0.0;
  const vtkIdType count = points && points->GetPoints() ? points->GetNumberOfPoints() : 0;
  if (count == 0)
  {
    this->ErrorMessage = "the particles have no points";
    return false;
  }
  // Without scalars, summed kernels are the particles' density (each particle's value 1); a
  // normalized mean of ones would be 1 wherever there are particles, which says nothing.
  if (!scalars && normalized)
  {
    this->ErrorMessage = "the particles need one single-component point scalar per point, or "
                         "ParticleNormalized off to draw their density";
    return false;
  }
  if (scalars && (scalars->GetNumberOfTuples() != count || scalars->GetNumberOfComponents() != 1))
  {
    this->ErrorMessage = "the particles need one single-component point scalar per point";
    return false;
  }
  if (radii && (radii->GetNumberOfTuples() != count || radii->GetNumberOfComponents() != 1))
  {
    this->ErrorMessage = "the radius array '" +
                         std::string(radii->GetName() ? radii->GetName() : "") + "' has " +
                         std::to_string(radii->GetNumberOfTuples()) + " tuples of " +
                         std::to_string(radii->GetNumberOfComponents()) +
                         " component(s), not one value per point (" + std::to_string(count) + ")";
    return false;
  }
  if (kernel < GAUSSIAN || kernel > SPH_QUINTIC)
  {
    this->ErrorMessage = "unknown particle kernel " + std::to_string(kernel);
    return false;
  }
  // World positions, and the volume's mean scale for the radii.
  double scale = 1.0;
  if (volumeMatrix)
  {
    scale = std::cbrt(std::abs(volumeMatrix->Determinant()));
  }
  std::vector<double> positions(3 * static_cast<std::size_t>(count));
  std::vector<double> values(static_cast<std::size_t>(count));
  for (vtkIdType i = 0; i < count; ++i)
  {
    double p[4] = { 0, 0, 0, 1 };
    points->GetPoint(i, p);
    if (volumeMatrix)
    {
      volumeMatrix->MultiplyPoint(p, p);
    }
    std::copy(p, p + 3, positions.begin() + 3 * i);
    values[i] = scalars ? scalars->GetComponent(i, 0) : 1.0;
  }
  std::vector<double> radiusValues;
  if (radii)
  {
    radiusValues.resize(static_cast<std::size_t>(count));
    for (vtkIdType i = 0; i < count; ++i)
    {
      radiusValues[i] = radii->GetComponent(i, 0) * scale;
    }
  }
  radius = (radius > 0.0 ? radius : AutomaticRadius(points)) * scale;
  savr::ParticleDescription description;
  description.Points = positions.data();
  description.Values = values.data();
  description.NumberOfPoints = static_cast<std::size_t>(count);
  description.Radius = radius;
  description.Radii = radii ? radiusValues.data() : nullptr;
  description.Kernel = kernel == SPH_CUBIC     ? savr::ParticleKernel::SPHCubic
                       : kernel == SPH_QUINTIC ? savr::ParticleKernel::SPHQuintic
                                               : savr::ParticleKernel::Gaussian;
  description.Normalized = normalized;
  std::size_t skipped = 0;
  std::string error;
  auto sampler = savr::MakeParticleSampler(description, error, &skipped);
  this->SkippedParticles = static_cast<vtkIdType>(skipped);
  if (!sampler)
  {
    this->ErrorMessage = error;
    return false;
  }
  if (radii)
  {
    std::vector<double> sorted = radiusValues;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    this->TypicalRadius = sorted[sorted.size() / 2];
  }
  else
  {
    this->TypicalRadius = radius;
  }
  this->Sampler = sampler;
  return true;
}

namespace
{
// The box of the finite positions; false when there is none.
bool FiniteBox(vtkPointSet* points, double lo[3], double hi[3])
{
  bool any = false;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = any ? std::min(lo[a], p[a]) : p[a];
      hi[a] = any ? std::max(hi[a], p[a]) : p[a];
    }
    any = true;
  }
  return any;
}

// The point array of radii named `name`, or null (no name, or the points have none by it).
vtkDataArray* RadiusArray(vtkPointSet* points, const char* name)
{
  return points && name && *name ? points->GetPointData()->GetArray(name) : nullptr;
}
} // namespace

bool vtkSAVRParticleSampler::Build(vtkPointSet* points, vtkDataArray* scalars, double radius,
  const char* radiiName, int kernel, bool normalized, vtkMatrix4x4* volumeMatrix)
{
  vtkDataArray* radii = RadiusArray(points, radiiName);
  if (radiiName && *radiiName && !radii)
  {
    this->Sampler.reset();
    this->ErrorMessage =
      std::string("the particles have no point array '") + radiiName + "' for their radii";
    return false;
  }
  return this->Build(points, scalars, radius, radii, kernel, normalized, volumeMatrix);
}

double vtkSAVRParticleSampler::AutomaticRadius(vtkPointSet* points)
{
  double lo[3];
  double hi[3];
  if (!points || !FiniteBox(points, lo, hi))
  {
    return 1.0;
  }
  double volume = 1.0;
  int dimensions = 0;
  for (int a = 0; a < 3; ++a)
  {
    if (hi[a] > lo[a])
    {
      volume *= hi[a] - lo[a];
      ++dimensions;
    }
  }
  return dimensions > 0
           ? std::pow(volume / static_cast<double>(points->GetNumberOfPoints()), 1.0 / dimensions)
           : 1.0;
}

vtkPointSet* vtkSAVRParticleSampler::Particles(vtkDataObject* input)
{
  if (auto* polyData = vtkPolyData::SafeDownCast(input))
  {
    return polyData;
  }
  auto* grid = vtkUnstructuredGrid::SafeDownCast(input);
  if (!grid || grid->GetNumberOfPoints() == 0)
  {
    return nullptr;
  }
  for (const unsigned char type : vtkSAVRVTKVersions::DistinctCellTypes(grid))
  {
    if (type != VTK_VERTEX && type != VTK_POLY_VERTEX)
    {
      return nullptr;
    }
  }
  return grid;
}

void vtkSAVRParticleSampler::SupportBounds(
  vtkPointSet* points, double radius, const char* radiiName, int kernel, double bounds[6])
{
  vtkDataArray* radii = RadiusArray(points, radiiName);
  double lo[3];
  double hi[3];
  if (!points || !FiniteBox(points, lo, hi))
  {
    vtkMath::UninitializeBounds(bounds);
    return;
  }
  double reach = radius > 0.0 ? radius : AutomaticRadius(points);
  if (radii && radii->GetNumberOfTuples() == points->GetNumberOfPoints())
  {
    reach = 0.0;
    for (vtkIdType i = 0; i < radii->GetNumberOfTuples(); ++i)
    {
      const double r = radii->GetComponent(i, 0);
      reach = std::isfinite(r) ? std::max(reach, r) : reach;
    }
  }
  reach *= kernel == SPH_CUBIC ? 2.0 : 3.0;
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = lo[a] - reach;
    bounds[2 * a + 1] = hi[a] + reach;
  }
}

void vtkSAVRParticleSampler::GetFieldRange(double range[2]) const
{
  range[0] = range[1] = 0.0;
  if (this->Sampler)
  {
    const std::array<double, 2> field = this->Sampler->ValueRange();
    range[0] = field[0];
    range[1] = field[1];
  }
}

void vtkSAVRParticleSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sampler: " << (this->Sampler ? "built" : "none") << "\n";
  os << indent << "ErrorMessage: " << this->ErrorMessage << "\n";
  os << indent << "TypicalRadius: " << this->TypicalRadius << "\n";
}

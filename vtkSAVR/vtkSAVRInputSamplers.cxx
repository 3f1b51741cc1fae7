#include "vtkSAVRInputSamplers.h"

#include "vtkSAVRAMRSampler.h"
#include "vtkSAVRImageSampler.h"
#include "vtkSAVRInputChecks.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRUnstructuredSampler.h"

#include "vtkImageData.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointSet.h"
#include "vtkRectilinearGrid.h"
#include "vtkStructuredGrid.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>

namespace
{
// The fewest steps along a mesh's diagonal in its first frame, and once refined.
constexpr double kMeshStepsAlongDiagonal = 16.0;
constexpr double kMeshRefinedStepsAlongDiagonal = 128.0;
}

vtkSAVRInputSamplers::vtkSAVRInputSamplers() = default;

vtkSAVRInputSamplers::~vtkSAVRInputSamplers() = default;

bool vtkSAVRInputSamplers::IsMesh(vtkDataObject* input)
{
  return (vtkUnstructuredGrid::SafeDownCast(input) && !vtkSAVRParticleSampler::Particles(input)) ||
         vtkStructuredGrid::SafeDownCast(input) || vtkRectilinearGrid::SafeDownCast(input);
}

bool vtkSAVRInputSamplers::Supported(vtkDataObject* input)
{
  return vtkImageData::SafeDownCast(input) || vtkOverlappingAMR::SafeDownCast(input) ||
         IsMesh(input) || vtkSAVRParticleSampler::Particles(input);
}

int vtkSAVRInputSamplers::GetNumberOfImageComponents() const
{
  return this->Image->GetNumberOfComponents();
}

vtkSAVRInputSamplers::Result vtkSAVRInputSamplers::Build(
  vtkDataObject* input, const Request& request)
{
  Result result;
  if (auto* image = vtkImageData::SafeDownCast(input))
  {
    if (this->Image->Build(image, request.Scalars, request.CellData, request.VolumeMatrix,
          request.Interpolation, request.IndependentComponents))
    {
      result.Sampler = this->Image->GetSampler();
      // The smallest voxel edge sets the default step.
      result.SmallestSpacing = this->Image->GetSmallestSpacing();
      result.DefaultStep = result.SmallestSpacing;
    }
    else
    {
      result.Error = this->Image->GetErrorMessage();
    }
  }
  else if (vtkPointSet* particles = vtkSAVRParticleSampler::Particles(input))
  {
    // (Without scalars VTK reports the cell data it last looked in: no scalars is no cell data.)
    if (request.CellData && request.Scalars)
    {
      result.Error = "particles need point scalars, not cell scalars";
    }
    else if (this->Particles->Build(particles, request.Scalars, request.ParticleRadius,
               request.ParticleRadiusArrayName, request.ParticleKernel, request.ParticleNormalized,
               request.VolumeMatrix))
    {
      result.Sampler = this->Particles->GetSampler();
      // Two samples per radius; refinement goes to a quarter of that.
      result.SmallestSpacing = 0.5 * this->Particles->GetTypicalRadius();
      result.DefaultStep = result.SmallestSpacing;
      if (this->Particles->GetNumberOfSkippedParticles() > 0)
      {
        result.Warnings.push_back(std::to_string(this->Particles->GetNumberOfSkippedParticles()) +
                                  " particles are left out: their position or value is not finite");
      }
    }
    else
    {
      result.Error = this->Particles->GetErrorMessage();
    }
  }
  else if (IsMesh(input))
  {
    auto* mesh = vtkDataSet::SafeDownCast(input);
    if (this->Unstructured->Build(mesh, request.Scalars, request.CellData, request.VolumeMatrix))
    {
      result.Sampler = this->Unstructured->GetSampler();
      // A typical cell sets the step and refinement goes to a quarter of it; but a mesh of few
      // large cells starts at no more than a 16th of its diagonal and refines to a 128th, so
      // that its silhouettes come out clean (a ray's sampled length through the mesh is its
      // chord to within a step).
      const double cell = this->Unstructured->GetTypicalCellSize();
      const double diagonal = this->Unstructured->GetDiagonal();
      result.SmallestSpacing = cell;
      result.DefaultStep = cell;
      result.FinestStep = 0.25 * cell;
      if (diagonal > 0.0)
      {
        result.DefaultStep = std::min(cell, diagonal / kMeshStepsAlongDiagonal);
        result.FinestStep = std::min(result.FinestStep, diagonal / kMeshRefinedStepsAlongDiagonal);
      }
      if (this->Unstructured->GetNumberOfSkippedCells() > 0)
      {
        result.Warnings.push_back(
          std::to_string(this->Unstructured->GetNumberOfSkippedCells()) +
          " cells are left out: only tetrahedra, hexahedra, voxels, wedges and pyramids with "
          "finite points are rendered");
      }
    }
    else
    {
      result.Error = this->Unstructured->GetErrorMessage();
    }
  }
  else if (this->AMR->Build(vtkOverlappingAMR::SafeDownCast(input), request.ScalarMode,
             request.ArrayAccessMode, request.ArrayId, request.ArrayName, request.VolumeMatrix,
             request.Interpolation, request.VectorMode, request.VectorComponent))
  {
    // A frame samples at the coarsest level's spacing; refinement reaches the finest level's.
    result.Sampler = this->AMR->GetSampler();
    result.SmallestSpacing = this->AMR->GetFinestSpacing();
    result.DefaultStep = this->AMR->GetCoarsestSpacing();
  }
  else
  {
    result.Error = this->AMR->GetErrorMessage();
  }
  if (result.Error.empty())
  {
    result.Error = vtkSAVRInputChecks::ScalarRangeProblem(request.Scalars, IsMesh(input));
  }
  if (!result.Error.empty())
  {
    result.Sampler.reset();
  }
  if (result.FinestStep <= 0.0)
  {
    result.FinestStep = 0.25 * result.SmallestSpacing;
  }
  return result;
}

#include "vtkSAVRAMRSampler.h"

#include "amr/AMRSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRVectorSelection.h"

#include "vtkAMRBox.h"
#include "vtkAbstractMapper.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkSAVRAMRSampler);

vtkSAVRAMRSampler::vtkSAVRAMRSampler() = default;
vtkSAVRAMRSampler::~vtkSAVRAMRSampler() = default;

namespace
{
// Length in world units of the vector (x, y, z) of data space, mapped by m (linear part).
double WorldLength(vtkMatrix4x4* m, const double v[3])
{
  double w[3] = { v[0], v[1], v[2] };
  if (m)
  {
    for (int r = 0; r < 3; ++r)
    {
      w[r] = m->GetElement(r, 0) * v[0] + m->GetElement(r, 1) * v[1] + m->GetElement(r, 2) * v[2];
    }
  }
  return std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
}
// Which scalars of each block to sample (vtkAbstractMapper::GetScalars' arguments).
struct ScalarSelection
{
  int Mode;
  int AccessMode;
  int Id;
  const char* Name;
  int VectorMode;      // how an array of several components is drawn (vtkSAVRVectorSelection)
  int VectorComponent; // the component drawn by COMPONENT
};

// Each level's spacing, the finest spacing and the coarsest level's, in world units, and the
// bounds of level 0, from the metadata of every block, held here or not, so that every process
// of a parallel run clips rays alike and refines to the same step.
void DescribeLevels(vtkOverlappingAMR* amr, vtkMatrix4x4* volumeMatrix,
  savr::AMRDescription& description, double& coarsest, double& finest)
{
  const unsigned int levels = amr->GetNumberOfLevels();
  for (unsigned int level = 0; level < levels; ++level)
  {
    double h[3];
    amr->GetSpacing(level, h);
    description.Spacing.emplace_back(h[0], h[1], h[2]);
  }
  coarsest = 0.0;
  finest = 0.0;
  for (unsigned int level = 0; level < levels; ++level)
  {
    const Eigen::Vector3d& h = description.Spacing[level];
    if (amr->GetNumberOfDataSets(level) == 0)
    {
      continue;
    }
    const double edge[3][3] = { { h[0], 0, 0 }, { 0, h[1], 0 }, { 0, 0, h[2] } };
    for (const double* e : edge)
    {
      const double length = WorldLength(volumeMatrix, e);
      finest = finest > 0.0 ? std::min(finest, length) : length;
      if (level == 0)
      {
        coarsest = coarsest > 0.0 ? std::min(coarsest, length) : length;
      }
    }
    for (unsigned int id = 0; level == 0 && id < amr->GetNumberOfDataSets(0); ++id)
    {
      const vtkAMRBox& box = amr->GetAMRBox(0, id);
      for (int a = 0; a < 3 && !box.IsInvalid(); ++a)
      {
        const double lo = description.Origin[a] + static_cast<double>(box.GetLoCorner()[a]) * h[a];
        const double hi =
          description.Origin[a] + static_cast<double>(box.GetHiCorner()[a] + 1) * h[a];
        const bool first = description.BoundsMin[a] > description.BoundsMax[a];
        description.BoundsMin[a] = first ? lo : std::min(description.BoundsMin[a], lo);
        description.BoundsMax[a] = first ? hi : std::max(description.BoundsMax[a], hi);
      }
    }
  }
}

// The blocks held here, with their scalars (the same type and association in every block),
// into `description`; false, with the reason in `error`, when a block cannot be sampled.
bool DescribeBlocks(vtkOverlappingAMR* amr, const ScalarSelection& selection,
  savr::AMRDescription& description, int& cellFlagSeen, int& typeSeen,
  std::vector<vtkSmartPointer<vtkDataArray>>& selected, std::string& error)
{
  const unsigned int levels = amr->GetNumberOfLevels();
  const double* origin = amr->GetOrigin();
  for (unsigned int level = 0; level < levels; ++level)
  {
    const Eigen::Vector3d& h = description.Spacing[level];
    for (unsigned int id = 0; id < amr->GetNumberOfDataSets(level); ++id)
    {
      vtkUniformGrid* grid = amr->GetDataSet(level, id);
      if (!grid)
      {
        continue; // held by another process
      }
      std::ostringstream where;
      where << "block " << id << " of level " << level;
      int cellFlag = 0;
      vtkDataArray* scalars = vtkAbstractMapper::GetScalars(
        grid, selection.Mode, selection.AccessMode, selection.Id, selection.Name, cellFlag);
      if (!scalars)
      {
        error = where.str() + " has no scalars to render (check the scalar mode and "
                              "array name)";
        return false;
      }
      if (scalars->GetNumberOfComponents() != 1)
      {
        vtkSmartPointer<vtkDataArray> one =
          vtkSAVRVectorSelection::Select(scalars, selection.VectorMode, selection.VectorComponent);
        if (one->GetNumberOfComponents() != 1)
        {
          error = where.str() + "'s scalars have " +
                  std::to_string(scalars->GetNumberOfComponents()) +
                  " components: draw their magnitude or one of them (the mapper's VectorMode)";
          return false;
        }
        selected.push_back(one);
        scalars = one;
      }
      if ((cellFlagSeen >= 0 && cellFlag != cellFlagSeen) ||
          (typeSeen >= 0 && scalars->GetDataType() != typeSeen))
      {
        error = where.str() + "'s scalars differ from the other blocks' in type or "
                              "association (point or cell)";
        return false;
      }
      cellFlagSeen = cellFlag;
      typeSeen = scalars->GetDataType();
      const vtkAMRBox& box = amr->GetAMRBox(level, id);
      int dims[3];
      grid->GetDimensions(dims);
      const double* gridOrigin = grid->GetOrigin();
      savr::AMRBlockDescription block;
      block.Level = static_cast<int>(level);
      for (int a = 0; a < 3; ++a)
      {
        if (dims[a] < 2 || box.GetHiCorner()[a] < box.GetLoCorner()[a])
        {
          error = where.str() + " is flat; only 3D hierarchies are supported";
          return false;
        }
        block.Lo[a] = box.GetLoCorner()[a];
        block.Hi[a] = box.GetHiCorner()[a];
        block.ArrayLo[a] = static_cast<int>(std::lround((gridOrigin[a] - origin[a]) / h[a]));
        block.ArrayCells[a] = dims[a] - 1;
      }
      const vtkIdType expected =
        cellFlag == 1 ? grid->GetNumberOfCells() : grid->GetNumberOfPoints();
      if (scalars->GetNumberOfTuples() < expected)
      {
        error = where.str() + "'s scalar array is shorter than the block";
        return false;
      }
      block.Data = scalars->GetVoidPointer(0);
      if (auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
            grid->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName())))
      {
        if (ghosts->GetNumberOfTuples() >= grid->GetNumberOfCells())
        {
          block.CellGhosts = ghosts->GetPointer(0);
        }
      }
      description.Blocks.push_back(block);
    }
  }
  return true;
}
} // namespace

bool vtkSAVRAMRSampler::Build(vtkOverlappingAMR* amr, int scalarMode, int arrayAccessMode,
  int arrayId, const char* arrayName, vtkMatrix4x4* volumeMatrix, int interpolationType,
  int vectorMode, int vectorComponent)
{
  this->Sampler.reset();
  this->ErrorMessage.clear();
  if (!amr || !amr->GetAMRInfo() || amr->GetNumberOfLevels() == 0)
  {
    this->ErrorMessage = "the AMR input has no levels";
    return false;
  }
  savr::AMRDescription description;
  const double* origin = amr->GetOrigin();
  description.Origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
  this->CoarsestSpacing = 0.0;
  this->FinestSpacing = 0.0;
  DescribeLevels(amr, volumeMatrix, description, this->CoarsestSpacing, this->FinestSpacing);
  int cellFlagSeen = -1;
  int typeSeen = -1;
  const ScalarSelection selection{ scalarMode, arrayAccessMode, arrayId, arrayName, vectorMode,
    vectorComponent };
  std::vector<vtkSmartPointer<vtkDataArray>> selected;
  if (!DescribeBlocks(
        amr, selection, description, cellFlagSeen, typeSeen, selected, this->ErrorMessage))
  {
    return false;
  }
  if (description.Blocks.empty())
  {
    this->ErrorMessage = "the AMR input holds no blocks";
    return false;
  }
  if (!vtkSAVRConversions::ToScalarType(typeSeen, description.Type))
  {
    this->ErrorMessage = "AMR scalars of this type are not supported";
    return false;
  }
  description.CellData = cellFlagSeen == 1;
  if (volumeMatrix)
  {
    description.WorldToData = Eigen::Affine3d(vtkSAVRConversions::ToEigen(volumeMatrix)).inverse();
  }
  description.Interpolation = interpolationType == VTK_NEAREST_INTERPOLATION
                                ? savr::Interpolation::Nearest
                                : savr::Interpolation::Linear;
  std::string error;
  this->Sampler = savr::MakeAMRSampler(description, error);
  this->Selected = std::move(selected); // what the blocks of vector arrays sample
  if (!this->Sampler)
  {
    this->ErrorMessage = error;
    return false;
  }
  if (this->CoarsestSpacing <= 0.0)
  {
    this->CoarsestSpacing = this->FinestSpacing;
  }
  return true;
}

void vtkSAVRAMRSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sampler: " << (this->Sampler ? "built" : "none") << "\n";
  os << indent << "ErrorMessage: " << this->ErrorMessage << "\n";
}

#include "vtkSAVRAMRSampler.h"

#include "amr/AMRSampler.h"
#include "vtkSAVRConversions.h"

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
} // namespace

bool vtkSAVRAMRSampler::Build(vtkOverlappingAMR* amr, int scalarMode, int arrayAccessMode,
  int arrayId, const char* arrayName, vtkMatrix4x4* volumeMatrix, int interpolationType)
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
  const unsigned int levels = amr->GetNumberOfLevels();
  for (unsigned int level = 0; level < levels; ++level)
  {
    double h[3];
    amr->GetSpacing(level, h);
    description.Spacing.emplace_back(h[0], h[1], h[2]);
  }
  int cellFlagSeen = -1;
  int typeSeen = -1;
  // Spacings and bounds from the metadata of every block, held here or not, so that every
  // process of a parallel run clips rays alike and refines to the same step.
  this->CoarsestSpacing = 0.0;
  this->FinestSpacing = 0.0;
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
      this->FinestSpacing =
        this->FinestSpacing > 0.0 ? std::min(this->FinestSpacing, length) : length;
      if (level == 0)
      {
        this->CoarsestSpacing =
          this->CoarsestSpacing > 0.0 ? std::min(this->CoarsestSpacing, length) : length;
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
        grid, scalarMode, arrayAccessMode, arrayId, arrayName, cellFlag);
      if (!scalars)
      {
        this->ErrorMessage = where.str() + " has no scalars to render (check the scalar mode and "
                                           "array name)";
        return false;
      }
      if (scalars->GetNumberOfComponents() != 1)
      {
        this->ErrorMessage = where.str() + ": only single-component scalars are supported";
        return false;
      }
      if ((cellFlagSeen >= 0 && cellFlag != cellFlagSeen) ||
          (typeSeen >= 0 && scalars->GetDataType() != typeSeen))
      {
        this->ErrorMessage = where.str() + "'s scalars differ from the other blocks' in type or "
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
          this->ErrorMessage = where.str() + " is flat; only 3D hierarchies are supported";
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
        this->ErrorMessage = where.str() + "'s scalar array is shorter than the block";
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

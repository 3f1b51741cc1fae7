#include "vtkSAVRUnstructuredSampler.h"

#include "mesh/UnstructuredDescription.h"

#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkIdList.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkStructuredGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkSAVRUnstructuredSampler);

namespace
{
// The mesh in the form the engine reads, kept alive with the sampler that refers to it.
struct Mesh
{
  std::vector<double> Points;
  std::vector<std::int64_t> Offsets;
  std::vector<std::int64_t> Connectivity;
  std::vector<std::uint8_t> Types;
  std::vector<float> Values;
  std::shared_ptr<const savr::Sampler> Sampler;
};

// The cells of a structured or rectilinear grid (hexahedra or voxels in VTK's point order), or of
// any other data set, as offsets, connectivity and types. A blanked cell of a structured grid
// becomes an empty cell: it keeps its index (cell data stays aligned) and is not drawn.
void ListCells(vtkDataSet* grid, Mesh& mesh, vtkIdType& hidden)
{
  const vtkIdType nCells = grid->GetNumberOfCells();
  auto* structured = vtkStructuredGrid::SafeDownCast(grid);
  mesh.Offsets.assign(1, 0);
  mesh.Offsets.reserve(static_cast<std::size_t>(nCells) + 1);
  mesh.Connectivity.reserve(8 * static_cast<std::size_t>(nCells));
  mesh.Types.resize(static_cast<std::size_t>(nCells));
  hidden = 0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < nCells; ++c)
  {
    if (structured && !structured->IsCellVisible(c))
    {
      mesh.Types[static_cast<std::size_t>(c)] = VTK_EMPTY_CELL;
      mesh.Offsets.push_back(static_cast<std::int64_t>(mesh.Connectivity.size()));
      ++hidden;
      continue;
    }
    mesh.Types[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(grid->GetCellType(c));
    grid->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      mesh.Connectivity.push_back(static_cast<std::int64_t>(ids->GetId(k)));
    }
    mesh.Offsets.push_back(static_cast<std::int64_t>(mesh.Connectivity.size()));
  }
}

void CopyIds(vtkDataArray* ids, std::vector<std::int64_t>& out)
{
  out.resize(static_cast<std::size_t>(ids->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < ids->GetNumberOfTuples(); ++i)
  {
    out[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(ids->GetTuple1(i));
  }
}
} // namespace

vtkSAVRUnstructuredSampler::vtkSAVRUnstructuredSampler() = default;
vtkSAVRUnstructuredSampler::~vtkSAVRUnstructuredSampler() = default;

bool vtkSAVRUnstructuredSampler::Build(
  vtkDataSet* grid, vtkDataArray* scalars, bool cellData, vtkMatrix4x4* volumeMatrix)
{
  this->Sampler.reset();
  this->ErrorMessage.clear();
  this->SkippedCells = 0;
  this->TypicalCellSize = 0.0;
  this->Diagonal = 0.0;
  if (!grid || grid->GetNumberOfCells() == 0 || grid->GetNumberOfPoints() == 0)
  {
    this->ErrorMessage = "the unstructured grid has no cells";
    return false;
  }
  if (!scalars)
  {
    this->ErrorMessage =
      "the input has no scalars to render (check the scalar mode and array name)";
    return false;
  }
  if (scalars->GetNumberOfComponents() != 1)
  {
    this->ErrorMessage = "only single-component scalars are supported";
    return false;
  }
  const vtkIdType expected = cellData ? grid->GetNumberOfCells() : grid->GetNumberOfPoints();
  if (scalars->GetNumberOfTuples() < expected)
  {
    this->ErrorMessage = "the scalar array is shorter than the grid";
    return false;
  }
  auto mesh = std::make_shared<Mesh>();
  vtkIdType hidden = 0;
  if (auto* unstructured = vtkUnstructuredGrid::SafeDownCast(grid))
  {
    vtkCellArray* cells = unstructured->GetCells();
    vtkUnsignedCharArray* types = unstructured->GetCellTypesArray();
    if (!cells || !types || types->GetNumberOfTuples() < grid->GetNumberOfCells())
    {
      this->ErrorMessage = "the unstructured grid has no cell types";
      return false;
    }
    CopyIds(cells->GetOffsetsArray(), mesh->Offsets);
    CopyIds(cells->GetConnectivityArray(), mesh->Connectivity);
    mesh->Types.assign(types->GetPointer(0), types->GetPointer(0) + grid->GetNumberOfCells());
  }
  else
  {
    ListCells(grid, *mesh, hidden);
  }

  const vtkIdType nPoints = grid->GetNumberOfPoints();
  mesh->Points.resize(3 * static_cast<std::size_t>(nPoints));
  double lower[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
  double upper[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (vtkIdType i = 0; i < nPoints; ++i)
  {
    double p[4] = { 0, 0, 0, 1 };
    grid->GetPoint(i, p);
    if (volumeMatrix)
    {
      volumeMatrix->MultiplyPoint(p, p);
      if (p[3] != 1.0 && p[3] != 0.0)
      {
        p[0] /= p[3];
        p[1] /= p[3];
        p[2] /= p[3];
      }
    }
    std::copy(p, p + 3, mesh->Points.begin() + 3 * i);
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))
    {
      for (int a = 0; a < 3; ++a)
      {
        lower[a] = std::min(lower[a], p[a]);
        upper[a] = std::max(upper[a], p[a]);
      }
    }
  }
  if (lower[0] <= upper[0])
  {
    this->Diagonal = std::sqrt((upper[0] - lower[0]) * (upper[0] - lower[0]) +
                               (upper[1] - lower[1]) * (upper[1] - lower[1]) +
                               (upper[2] - lower[2]) * (upper[2] - lower[2]));
  }
  mesh->Values.resize(static_cast<std::size_t>(expected));
  for (vtkIdType i = 0; i < expected; ++i)
  {
    mesh->Values[static_cast<std::size_t>(i)] = static_cast<float>(scalars->GetTuple1(i));
  }

  // Typical cell size: the median of the cells' longest bounding-box edges.
  std::vector<double> sizes;
  const vtkIdType nCells = grid->GetNumberOfCells();
  const vtkIdType stride = std::max<vtkIdType>(1, nCells / 4096);
  for (vtkIdType c = 0; c < nCells; c += stride)
  {
    double lo[3] = { VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, VTK_DOUBLE_MAX };
    double hi[3] = { -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (std::int64_t k = mesh->Offsets[c]; k < mesh->Offsets[c + 1]; ++k)
    {
      const std::int64_t id = mesh->Connectivity[static_cast<std::size_t>(k)];
      if (id < 0 || id >= nPoints)
      {
        continue;
      }
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], mesh->Points[3 * id + a]);
        hi[a] = std::max(hi[a], mesh->Points[3 * id + a]);
      }
    }
    const double edge = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
    if (std::isfinite(edge) && edge > 0.0)
    {
      sizes.push_back(edge);
    }
  }
  if (sizes.empty())
  {
    this->ErrorMessage = "every cell of the unstructured grid is degenerate";
    return false;
  }
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  this->TypicalCellSize = sizes[sizes.size() / 2];

  savr::UnstructuredDescription description;
  description.Points = mesh->Points.data();
  description.NumberOfPoints = static_cast<std::size_t>(nPoints);
  description.Offsets = mesh->Offsets.data();
  description.Connectivity = mesh->Connectivity.data();
  description.Types = mesh->Types.data();
  description.NumberOfCells = static_cast<std::size_t>(nCells);
  description.Values = mesh->Values.data();
  description.CellData = cellData;
  std::string error;
  std::size_t skipped = 0;
  mesh->Sampler = savr::MakeUnstructuredSampler(description, error, &skipped);
  // Blanked cells are left out on purpose.
  this->SkippedCells = static_cast<vtkIdType>(skipped) - hidden;
  if (!mesh->Sampler)
  {
    this->ErrorMessage = error;
    return false;
  }
  // The sampler shares the mesh's lifetime.
  this->Sampler = std::shared_ptr<const savr::Sampler>(mesh, mesh->Sampler.get());
  return true;
}

void vtkSAVRUnstructuredSampler::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Sampler: " << (this->Sampler ? "built" : "none") << "\n";
  os << indent << "SkippedCells: " << this->SkippedCells << "\n";
  os << indent << "ErrorMessage: " << this->ErrorMessage << "\n";
}

#pragma once
// A mesh of linear cells (tetrahedra, hexahedra, voxels, wedges and pyramids) as the caller
// holds it, and the factory of its sampler (UnstructuredSampler.h), which samples it natively:
// each cell interpolates with its own shape functions, and rays walk from cell to cell across
// shared faces.

#include "sampler/Sampler.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace savr
{

/// Describes a mesh held by someone else, who keeps it alive as long as the sampler. Cells are
/// `Connectivity[Offsets[c] .. Offsets[c + 1])` with VTK's type codes and vertex orderings:
/// 10 tetrahedron, 11 voxel, 12 hexahedron, 13 wedge, 14 pyramid. Cells of any other type, and
/// cells with a non-finite point, are skipped.
struct UnstructuredDescription
{
  const double* Points = nullptr; // 3 per point, world coordinates
  std::size_t NumberOfPoints = 0;
  const std::int64_t* Offsets = nullptr; // NumberOfCells + 1 entries into Connectivity
  const std::int64_t* Connectivity = nullptr;
  const std::uint8_t* Types = nullptr; // VTK cell type per cell
  std::size_t NumberOfCells = 0;
  const float* Values = nullptr; // one per point, or one per cell when CellData
  bool CellData = false;
};

/// Builds a sampler for the mesh, or returns nullptr and explains why in `error`. When given,
/// `skippedCells` receives the number of cells that the sampler ignores (unsupported types,
/// non-finite points).
std::shared_ptr<const Sampler> MakeUnstructuredSampler(
  const UnstructuredDescription& mesh, std::string& error, std::size_t* skippedCells = nullptr);

} // namespace savr

#pragma once
// A sampler over an unstructured mesh of linear cells (tetrahedra, hexahedra, voxels, wedges and
// pyramids), sampled natively: each cell interpolates with its own shape functions, and rays walk
// from cell to cell across shared faces.

#include "Sampler.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace savr
{

/// Describes a mesh held by someone else, who keeps it alive as long as the sampler. Cells are
/// `connectivity[offsets[c] .. offsets[c + 1])` with VTK's type codes and vertex orderings:
/// 10 tetrahedron, 11 voxel, 12 hexahedron, 13 wedge, 14 pyramid. Cells of any other type, and
/// cells with a non-finite point, are skipped.
struct UnstructuredDescription
{
  const double* points = nullptr; // 3 per point, world coordinates
  std::size_t numberOfPoints = 0;
  const std::int64_t* offsets = nullptr; // numberOfCells + 1 entries into connectivity
  const std::int64_t* connectivity = nullptr;
  const std::uint8_t* types = nullptr; // VTK cell type per cell
  std::size_t numberOfCells = 0;
  const float* values = nullptr; // one per point, or one per cell when cellData
  bool cellData = false;
};

/// Builds a sampler for the mesh, or returns nullptr and explains why in `error`. When given,
/// `skippedCells` receives the number of cells that the sampler ignores (unsupported types,
/// non-finite points).
std::shared_ptr<const Sampler> MakeUnstructuredSampler(
  const UnstructuredDescription& mesh, std::string& error, std::size_t* skippedCells = nullptr);

} // namespace savr

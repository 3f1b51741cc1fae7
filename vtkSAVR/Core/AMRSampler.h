#pragma once
// A sampler over a block-structured AMR hierarchy (overlapping levels of regular blocks), sampled
// where the data lives: no resampling to a uniform grid.

#include "GridSampler.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace savr
{

/// One block of an AMR level. Indices are global at the block's level: cell (i, j, k) of level L
/// spans origin + (i, j, k) * spacing[L] to origin + (i + 1, j + 1, k + 1) * spacing[L].
struct AMRBlockDescription
{
  int level = 0;
  /// The cells this block is responsible for (inclusive): its AMR box, without ghost layers.
  std::array<int, 3> lo = { 0, 0, 0 };
  std::array<int, 3> hi = { 0, 0, 0 };
  /// The block's array: `arrayCells` cells from global cell `arrayLo` (ghost layers included), its
  /// values x fastest, one per cell (cell data) or per point (point data, arrayCells + 1 along
  /// each axis). Shared, never copied.
  const void* data = nullptr;
  std::array<int, 3> arrayLo = { 0, 0, 0 };
  std::array<int, 3> arrayCells = { 0, 0, 0 };
  /// Optional: one VTK ghost-type byte per cell of the array. Cells flagged hidden (32) and not
  /// covered by a finer block are holes: sampling there gives NaN.
  const std::uint8_t* cellGhosts = nullptr;
};

struct AMRDescription
{
  ScalarType type = ScalarType::Float32;
  bool cellData = true;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> spacing; // per level
  /// Maps world coordinates to the hierarchy's coordinates (the inverse of the volume's matrix).
  Eigen::Affine3d worldToData = Eigen::Affine3d::Identity();
  Interpolation interpolation = Interpolation::Linear;
  std::vector<AMRBlockDescription> blocks;
};

/// Builds the sampler, with its block index, or returns nullptr and explains why in `error`.
///
/// A point is sampled on the finest level whose block contains it. Linear interpolation is
/// trilinear between the eight nearest values of that level: values outside the block are read
/// from the neighbouring block of the same level, or, where that level has no block, interpolated
/// on the next coarser level at the value's position. So there are no seams between blocks of a
/// level, and a fine level blends into the coarse one across its boundary.
std::shared_ptr<const Sampler> MakeAMRSampler(const AMRDescription& amr, std::string& error);

} // namespace savr

#pragma once
// A sampler over a block-structured AMR hierarchy (overlapping levels of regular blocks), sampled
// where the data lives: no resampling to a uniform grid.

#include "image/GridSampler.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace savr
{

/// One block of an AMR level. Indices are global at the block's level: cell (i, j, k) of level L
/// spans Origin + (i, j, k) * Spacing[L] to Origin + (i + 1, j + 1, k + 1) * Spacing[L].
struct AMRBlockDescription
{
  int Level = 0;
  /// The cells this block is responsible for (inclusive): its AMR box, without ghost layers.
  std::array<int, 3> Lo = { 0, 0, 0 };
  std::array<int, 3> Hi = { 0, 0, 0 };
  /// The block's array: `ArrayCells` cells from global cell `ArrayLo` (ghost layers included), its
  /// values x fastest, one per cell (cell data) or per point (point data, ArrayCells + 1 along
  /// each axis). Shared, never copied.
  const void* Data = nullptr;
  std::array<int, 3> ArrayLo = { 0, 0, 0 };
  std::array<int, 3> ArrayCells = { 0, 0, 0 };
  /// Optional: one VTK ghost-type byte per cell of the array. Cells flagged hidden (32) and not
  /// covered by a finer block are holes: sampling there gives NaN.
  const std::uint8_t* CellGhosts = nullptr;
};

struct AMRDescription
{
  ScalarType Type = ScalarType::Float32;
  bool CellData = true;
  Eigen::Vector3d Origin = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> Spacing; // per level
  /// Maps world coordinates to the hierarchy's coordinates (the inverse of the volume's matrix).
  Eigen::Affine3d WorldToData = Eigen::Affine3d::Identity();
  savr::Interpolation Interpolation = savr::Interpolation::Linear;
  std::vector<AMRBlockDescription> Blocks;
  /// The whole hierarchy's level-0 box, in its coordinates, when Blocks are only some of its
  /// blocks (the others held by other processes): rays are clipped to it, so that every
  /// process's rays enter where one process's would and take the same samples. Left empty
  /// (min above max), the box of the level-0 blocks given.
  Eigen::Vector3d BoundsMin = Eigen::Vector3d::Constant(1.0);
  Eigen::Vector3d BoundsMax = Eigen::Vector3d::Constant(-1.0);
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

#pragma once
// A sampler over a regular grid of scalars held by someone else (shared, never copied).

#include "sampler/Sampler.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <string>

namespace savr
{

enum class Interpolation
{
  Nearest,
  Linear
};

enum class ScalarType
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

/// Describes a grid of `Dims` points (point data) or `Dims - 1` cells (cell data) whose values
/// are `Data[i + Dims.x * (j + Dims.y * k)]` (one component, or component 0 of `Components`).
struct GridDescription
{
  const void* Data = nullptr;
  ScalarType Type = ScalarType::Float32;
  int Components = 1;
  std::array<int, 3> Dims = { 0, 0, 0 }; // points along each axis
  bool CellData = false;
  /// Maps world coordinates to continuous point-index coordinates (i, j, k).
  Eigen::Affine3d WorldToIndex = Eigen::Affine3d::Identity();
  savr::Interpolation Interpolation = savr::Interpolation::Linear;
  /// Let linear interpolation take eight samples at a time where the CPU can (AVX2); the
  /// results are the same either way (tests compare the two).
  bool Vectorize = true;
};

/// Builds a sampler for the description, or returns nullptr and explains why in `error`.
std::shared_ptr<const Sampler> MakeGridSampler(const GridDescription& grid, std::string& error);

} // namespace savr

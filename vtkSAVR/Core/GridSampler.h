#pragma once
// A sampler over a regular grid of scalars held by someone else (shared, never copied).

#include "Sampler.h"

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

/// Describes a grid of `dims` points (point data) or `dims - 1` cells (cell data) whose values
/// are `data[i + dims.x * (j + dims.y * k)]` (one component, or component 0 of `components`).
struct GridDescription
{
  const void* data = nullptr;
  ScalarType type = ScalarType::Float32;
  int components = 1;
  std::array<int, 3> dims = { 0, 0, 0 }; // points along each axis
  bool cellData = false;
  /// Maps world coordinates to continuous point-index coordinates (i, j, k).
  Eigen::Affine3d worldToIndex = Eigen::Affine3d::Identity();
  Interpolation interpolation = Interpolation::Linear;
  /// Let linear interpolation take eight samples at a time where the CPU can (AVX2); the
  /// results are the same either way (tests compare the two).
  bool vectorize = true;
};

/// Builds a sampler for the description, or returns nullptr and explains why in `error`.
std::shared_ptr<const Sampler> MakeGridSampler(const GridDescription& grid, std::string& error);

} // namespace savr

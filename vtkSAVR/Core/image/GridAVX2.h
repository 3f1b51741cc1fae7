#pragma once
// The grid sampler's trilinear interpolation, eight samples at a time with AVX2 where the CPU
// has it (chosen at run time: detail::HaveAVX2). Every lane computes exactly what the scalar path
// computes (the same double-precision positions, the same float operations in the same order, no
// fused multiply-add), so that images do not depend on which path took a sample.

#include "encoding/EncodeAVX2.h"

#include <cstddef>
#include <cstdint>

namespace savr
{
namespace detail
{

enum class GridValueType
{
  UInt8,
  UInt16,
  Float32
};

/// What the kernel needs of a grid sampler (value-grid coordinates, as GridSamplerT keeps them).
struct GridArrays
{
  const void* Values = nullptr;
  std::size_t Bytes = 0; // of the whole array, at most 2^31 - 1
  GridValueType Type = GridValueType::UInt8;
  int Step[3] = { 0, 0, 0 };      // array elements between neighbours along each axis
  int Neighbour[3] = { 0, 0, 0 }; // Step, or 0 along an axis with a single value
  int LastCell[3] = { 0, 0, 0 };  // largest lower cell corner
  double MaxValueIndex[3] = { 0.0, 0.0, 0.0 };
  double CellShift = 0.0;
  const float* BlockConstant = nullptr; // per block of cells: its one value, or NaN
  int BlockShift = 3;                   // log2 of the cells per block edge
  bool AnyConstant = false;             // whether any block has one value
  int Blocks[2] = { 1, 1 };             // blocks along x and y
  int NumberOfBlocks = 0;               // at least 4
};

/// What the gradient kernel needs of a GradientGrid (points, not array elements).
struct GradientArrays
{
  const std::int16_t* Codes = nullptr;   // 3 per point, padded (GradientGrid::CodeData)
  const std::uint32_t* Packed = nullptr; // or 1 word per point (GradientGrid::PackedData)
  const std::int32_t* ZeroBlocks = nullptr;
  int Step[3] = { 0, 0, 0 };      // points between neighbours along each axis
  int Neighbour[3] = { 0, 0, 0 }; // Step, or 0 along an axis with a single value
  float ToWorld[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
};

/// How far (in cells along every axis, so in steps of the fastest axis) a ray can move from a
/// point in a block whose skip distance is `distance` (Sampler::SkipDistances) and stay in
/// skipped blocks: the rings of skipped blocks around it, less a cell and a half, since the
/// point may lie at its block's far edge and the cell it lies in counts whole; 0 when there are
/// no such rings.
inline double SkipReach(int distance, int blockShift)
{
  return distance > 1 ? static_cast<double>((distance - 1) << blockShift) - 1.5 : 0.0;
}

/// Linear samples at o + (t0 + i dt) d (index coordinates) for i in [first, last], eight at a
/// time (the last group masked); NaN in blocks that `skipped` (may be null; one flag per block)
/// flags, passing over as many samples at once as its distances (SkipReach) allow. The positions
/// must lie inside the grid (as GridSamplerT::SampleRay's [first, last]). Returns last + 1.
int SampleLinearAVX2(const GridArrays& kernel, const double o[3], const double d[3], double t0,
  double dt, int first, int last, float* out, const std::uint8_t* skipped);

/// World gradients (3 floats per sample, gradients + 3 i) at the samples SampleLinearAVX2 takes
/// for the same arguments, eight at a time: the same bits as GradientGrid::Interpolate. The
/// grid's points times 6 bytes must fit 31 bits. AVX2 only.
void SampleGradientsAVX2(const GridArrays& kernel, const GradientArrays& gradient,
  const double o[3], const double d[3], double t0, double dt, int first, int last,
  float* gradients);

/// SampleLinearAVX2's values (without skipped blocks) and, for the same samples, EncodeNormal of
/// SampleGradientsAVX2's gradients, for i in [first, last]: the same bits as those two kernels
/// then EncodeNormalsAVX2, from one look at each group's cells, each normal encoded while in
/// registers. AVX2 only.
void SampleValuesAndNormalsAVX2(const GridArrays& kernel, const GradientArrays& gradient,
  const double o[3], const double d[3], double t0, double dt, int first, int last, float* out,
  std::uint16_t* normals);

} // namespace detail
} // namespace savr

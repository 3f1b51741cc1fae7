#pragma once
// What the files that implement FrameLoop share: its tiles, the per-thread buffers, how work
// runs over the tiles, and what a tile's blending pass is given.

#include "blend/StoredAVX2.h"
#include "frame/FrameLoop.h"
#include "frame/TilePaths.h"

#include <algorithm>
#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

namespace savr
{

struct FrameLoop::Buffers
{
  std::vector<float> Values;
  std::vector<float> Gradients;
  std::vector<std::uint16_t> SecondCodes;
  std::vector<std::uint16_t> Normals;
  std::vector<double> U;
  std::vector<int> Order;
  std::vector<const double*> Tables;
  std::vector<std::uint32_t> Codes;
  std::vector<float> ComponentGradients;    // each component's, with their gradient opacity
  std::vector<SampleAttributes> Attributes; // a single pass's chunk: normal and magnitude codes
  std::vector<PathPiece> Path;              // a ray's path as it is traced
  std::size_t Sampled = 0;                  // samples the tile at hand took
  // A tile's stores while its rays' rows are laid out anew: its first frame, sampled here
  // with whole rows of one slot, and the stores a resumption lays out (FrameLoop::SampleTile,
  // FrameLoop::ResumeRays).
  RayStores Relaid;
  std::vector<char> Flags; // per ray of the tile at hand
};

struct FrameLoop::Scratch
{
  tbb::enumerable_thread_specific<Buffers> Local;
};

template <typename Code>
struct FrameLoop::StoredRows
{
  Code* Codes = nullptr;
  std::uint16_t* Normals = nullptr;             // when shading
  std::uint8_t* Magnitudes = nullptr;           // with gradient opacity
  std::uint64_t* ComponentNormals = nullptr;    // when shading independent components
  std::uint32_t* ComponentMagnitudes = nullptr; // with independent components' gradient opacity
  std::uint16_t* SecondCodes = nullptr;         // when the sampler has second codes
  int Capacity = 1;                             // slots per row

  static StoredRows Of(
    RayStores& stores, std::size_t firstRow, const Attributes& attributes, bool secondCodes)
  {
    StoredRows rows;
    rows.Codes = stores.Codes.template Row<Code>(firstRow);
    rows.Capacity = stores.Codes.SlotCapacity();
    rows.Normals =
      attributes.Normals ? stores.Normals.template Row<std::uint16_t>(firstRow) : nullptr;
    rows.Magnitudes =
      attributes.Magnitudes ? stores.Magnitudes.template Row<std::uint8_t>(firstRow) : nullptr;
    rows.ComponentNormals = attributes.ComponentNormals
                              ? stores.ComponentNormals.template Row<std::uint64_t>(firstRow)
                              : nullptr;
    rows.ComponentMagnitudes = attributes.ComponentMagnitudes
                                 ? stores.ComponentMagnitudes.template Row<std::uint32_t>(firstRow)
                                 : nullptr;
    rows.SecondCodes =
      secondCodes ? stores.SecondCodes.template Row<std::uint16_t>(firstRow) : nullptr;
    return rows;
  }

  /// Rows `first` on: the same rows, shifted.
  StoredRows From(int first) const
  {
    const std::size_t k = static_cast<std::size_t>(first) * this->Capacity;
    StoredRows rows = *this;
    rows.Codes += k;
    rows.Normals = rows.Normals ? rows.Normals + k : nullptr;
    rows.Magnitudes = rows.Magnitudes ? rows.Magnitudes + k : nullptr;
    rows.ComponentNormals = rows.ComponentNormals ? rows.ComponentNormals + k : nullptr;
    rows.ComponentMagnitudes = rows.ComponentMagnitudes ? rows.ComponentMagnitudes + k : nullptr;
    rows.SecondCodes = rows.SecondCodes ? rows.SecondCodes + k : nullptr;
    return rows;
  }

  /// The first `frames` frames of `ray` in these rows, the slots' offsets `u` in `order`: up
  /// to its horizon, where the ray ends for the blends.
  RayLayout<Code> Layout(
    const RayInfo& ray, int frames, const double* u, const int* order, double dt) const
  {
    RayLayout<Code> layout;
    layout.Codes = this->Codes;
    layout.Normals = this->Normals;
    layout.Magnitudes = this->Magnitudes;
    layout.ComponentNormals = this->ComponentNormals;
    layout.ComponentMagnitudes = this->ComponentMagnitudes;
    layout.SecondCodes = this->SecondCodes;
    layout.SamplesPerFrame = ray.Horizon;
    layout.FirstRow = ray.Front;
    layout.Capacity = this->Capacity;
    layout.Frames = frames;
    layout.U = u;
    layout.Order = order;
    layout.Dt = dt;
    layout.Length =
      ray.Horizon < ray.SamplesPerFrame ? std::min(ray.Length, ray.Horizon * dt) : ray.Length;
    return layout;
  }
};

template <typename Body>
std::size_t FrameLoop::ForEachTile(
  Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles)
{
  return this->Schedule.ForEach(
    [&](Tile& tile) { body(tile, this->ThreadScratch->Local.local()); }, first, seconds, tiles);
}

// What the blending pass of every tile of a frame shares (FrameLoop::TilePasses, BlendTile).
template <typename Code>
struct FrameLoop::TileBlend
{
  const TransferFunctionTable& TF;
  BlendMode Mode;
  int Frames;
  Attributes Attrs;
  bool HasSecondCodes;
  // Plain composite: each sorted offset's interval table, and whether rays are composited four
  // at a time (AVX2; every offset has a table and the rays are unlit).
  const std::vector<const double*>& SortedTables;
  bool Plain;
  bool GroupsOfFour;
  const detail::RowScan<Code>& Scan;
  float* Pixels;
};

} // namespace savr

#pragma once
// A ray's rows in a tile's stores, as pointers into each store the view fills, and the layout
// the blends read them by.

#include "blend/BlendTypes.h"
#include "encoding/StoredAttributes.h"
#include "frame/RayStores.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace savr
{

template <typename Code>
struct StoredRows
{
  Code* Codes = nullptr;
  std::uint16_t* Normals = nullptr;             // when shading
  std::uint8_t* Magnitudes = nullptr;           // with gradient opacity
  std::uint64_t* ComponentNormals = nullptr;    // when shading independent components
  std::uint32_t* ComponentMagnitudes = nullptr; // with independent components' gradient opacity
  std::uint16_t* SecondCodes = nullptr;         // when the sampler has second codes
  int Capacity = 1;                             // slots per row

  static StoredRows Of(
    RayStores& stores, std::size_t firstRow, const StoredAttributes& attributes, bool secondCodes)
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

} // namespace savr

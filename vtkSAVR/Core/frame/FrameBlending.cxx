// The blending pass of a frame: each ray of a tile blended from its stored frames in depth
// order, through the composite's fast paths where the blend allows them (per-code interval
// tables, four rays at a time with AVX2), else through the blends of Integrator.h.

#include "frame/FrameLoop.h"

#include "blend/PlainComposite.h"
#include "frame/FrameLoopTiles.h"

#include <algorithm>
#include <cstdint>

namespace savr
{

void FrameLoop::PrepareBlend(const TransferFunctionTable& tf, int frames)
{
  if (this->Offsets.Frames() != frames)
  {
    this->Offsets.Resize(frames);
  }
  const double gap = OffsetSequence::SmallestGap(frames) * this->Settings.SampleDistance;
  this->Alphas.Prepare(tf, gap, 2.0 * gap);
}

bool FrameLoop::PlainIntervalTables(const TransferFunctionTable& tf, BlendMode mode, int frames,
  const Attributes& attributes, std::vector<const double*>& sortedTables)
{
  sortedTables.assign(frames, nullptr);
  // Composite without gradient opacity or second codes, lit or not: each interior interval
  // has its table. Independent components shaded light each component with its own coefficients:
  // not plain.
  const bool plain = this->Settings.FastPaths && mode == BlendMode::Composite &&
                     !attributes.GradientOpacity && !this->Source->HasSecondCode() &&
                     !tf.HasComponentTerms() && !(attributes.Shading && tf.HasComponentLevels());
  if (!plain)
  {
    return false;
  }
  this->Tables.Intervals(tf, this->Offsets, frames, this->Settings.SampleDistance, sortedTables);
  return true;
}

template <typename Code>
void FrameLoop::BlendTile(Tile& tile, Buffers& buffers, const TileBlend<Code>& b) const
{
  const int frames = b.Frames;
  const double dt = this->Settings.SampleDistance;
  const double termination = this->Settings.StopTransmittance();
  const OffsetSequence& offsets = this->Offsets;
  // Room for four rays' offsets: plain rays are composited four at a time. A ray's order of
  // frames and its ranks' tables depend only on its shift (OffsetSequence::Rotate): those of
  // every shift are made once here, not per ray.
  const std::size_t square = static_cast<std::size_t>(frames) * frames;
  buffers.U.resize(4 * static_cast<std::size_t>(frames));
  buffers.Order.resize(square);
  buffers.Tables.resize(square);
  for (int shift = 0; shift < frames; ++shift)
  {
    const std::size_t at = static_cast<std::size_t>(shift) * frames;
    offsets.Order(shift, buffers.Order.data() + at);
    if (b.Plain)
    {
      // Rank s is the offset SortedTables[s + shift] stands for, rotated.
      for (int s = 0; s < frames; ++s)
      {
        buffers.Tables[at + s] =
          b.SortedTables[s + shift < frames ? s + shift : s + shift - frames];
      }
    }
  }
  RayLayout<Code> group[4];
  const double* const* groupTables[4] = { nullptr, nullptr, nullptr, nullptr };
  int groupPixels[4] = { 0, 0, 0, 0 };
  int pending = 0;
  const auto compositeOne = [&](const RayLayout<Code>& layout, const double* const* tables)
  {
    return detail::PlainComposite<Code>(
      layout, b.TF, this->Alphas, tables, &b.Scan, termination, b.Attrs.Shading)
      .Blend();
  };
  const auto tablesOf = [&](int g) { return groupTables[g]; };
  const auto put = [&](const Pixel& p, int pixel)
  { std::copy(p.data(), p.data() + 4, b.Pixels + 4 * static_cast<std::size_t>(pixel)); };
  for (const RayInfo& ray : tile.Rays)
  {
    if (b.Plain && ray.KeepsNoRows())
    {
      // A third of the head's rays: the zero pixel PlainComposite would give, without its
      // set-up.
      put(Pixel::Zero(), ray.Pixel);
      continue;
    }
    double* const u = buffers.U.data() + static_cast<std::size_t>(pending) * frames;
    const std::size_t shifted =
      static_cast<std::size_t>(offsets.RotatedOffsets(ray.Rotation, u)) * frames;
    const int* const order = buffers.Order.data() + shifted;
    const double* const* const tables = buffers.Tables.data() + shifted;
    const StoredRows<Code> rows =
      StoredRows<Code>::Of(tile.Stores, ray.FirstRow, b.Attrs, b.HasSecondCodes);
    const RayLayout<Code> layout = rows.Layout(ray, frames, u, order, dt);
    if (!b.Plain)
    {
      put(BlendRay(layout, b.TF, this->Alphas, b.Mode, termination, b.Attrs.Shading,
            b.Attrs.GradientOpacity, b.Attrs.Isos),
        ray.Pixel);
      continue;
    }
    if (b.GroupsOfFour)
    {
      group[pending] = layout;
      groupTables[pending] = tables;
      groupPixels[pending] = ray.Pixel;
      if (++pending == 4)
      {
        detail::CompositeFour(
          group, tablesOf, &b.Scan, b.TF, this->Alphas, termination, b.Pixels, groupPixels);
        pending = 0;
      }
      continue;
    }
    put(compositeOne(layout, tables), ray.Pixel);
  }
  for (int g = 0; g < pending; ++g)
  {
    put(compositeOne(group[g], tablesOf(g)), groupPixels[g]);
  }
}

// The code widths FrameLoop::TilePasses runs.
template void FrameLoop::BlendTile<std::uint8_t>(
  Tile&, Buffers&, const TileBlend<std::uint8_t>&) const;
template void FrameLoop::BlendTile<std::uint16_t>(
  Tile&, Buffers&, const TileBlend<std::uint16_t>&) const;

} // namespace savr

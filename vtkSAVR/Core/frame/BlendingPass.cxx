// The blending pass of a frame (see BlendingPass.h).

#include "frame/BlendingPass.h"

#include "blend/PlainComposite.h"
#include "frame/PassScratch.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace savr
{

void BlendingPass::Prepare(const TransferFunctionTable& tf, int frames)
{
  if (this->State.Offsets.Frames() != frames)
  {
    this->State.Offsets.Resize(frames);
  }
  const double gap = OffsetSequence::SmallestGap(frames) * this->State.Settings.SampleDistance;
  this->Alphas.Prepare(tf, gap, 2.0 * gap);
}

bool BlendingPass::PlainIntervalTables(const TransferFunctionTable& tf, BlendMode mode, int frames,
  const StoredAttributes& attributes, std::vector<const double*>& sortedTables)
{
  sortedTables.assign(frames, nullptr);
  // Composite without gradient opacity or second codes, lit or not: each interior interval
  // has its table. Independent components shaded light each component with its own coefficients:
  // not plain.
  const bool plain = this->State.Settings.FastPaths && mode == BlendMode::Composite &&
                     !attributes.GradientOpacity && !this->State.Source->HasSecondCode() &&
                     !tf.HasComponentTerms() && !(attributes.Shading && tf.HasComponentLevels());
  if (!plain)
  {
    return false;
  }
  this->Tables.Intervals(
    tf, this->State.Offsets, frames, this->State.Settings.SampleDistance, sortedTables);
  return true;
}

template <typename Code>
void BlendingPass::BlendTile(Tile& tile, ThreadBuffers& buffers, const TileBlend<Code>& b) const
{
  const int frames = b.Frames;
  const double dt = this->State.Settings.SampleDistance;
  const double termination = this->State.Settings.StopTransmittance();
  const OffsetSequence& offsets = this->State.Offsets;
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

template <typename Code>
void BlendingPass::BlendWindows(const TransferFunctionTable& tf, BlendMode mode,
  const DepthWindow* windows, int count, int frames, const std::vector<std::size_t>* tiles)
{
  // (The error estimate may have left the offsets and the opacity cache at another count.)
  this->Prepare(tf, frames);
  const double dt = this->State.Settings.SampleDistance;
  const OffsetSequence& offsets = this->State.Offsets;
  // All three interior interval lengths tabulated: the walk of a part is not the plain blend's.
  const double gap = OffsetSequence::SmallestGap(frames) * dt;
  this->WindowAlphas.Prepare(tf, gap, 2.0 * gap, 1.5 * gap);
  const AlphaCache& alphas = this->WindowAlphas;
  const double termination = this->State.Settings.StopTransmittance();
  const View& view = this->State.CurrentViewData;
  const StoredAttributes attributes = this->State.CurrentAttributes();
  const bool hasSecondCodes = this->State.Source->HasSecondCode();
  this->State.ForEachTile(
    [&](Tile& tile, ThreadBuffers& buffers)
    {
      buffers.U.resize(static_cast<std::size_t>(frames));
      buffers.Order.resize(static_cast<std::size_t>(frames));
      double* const u = buffers.U.data();
      int* const order = buffers.Order.data();
      for (const RayInfo& ray : tile.Rays)
      {
        const int px = ray.Pixel % view.Width;
        const int py = ray.Pixel / view.Width;
        const Ray r = view.PixelRay(px, py);
        // Distance from the ray's entry point to window depth z (the near plane is depth 0).
        const auto distance = [&](float z)
        {
          if (z >= 1.0f)
          {
            return std::numeric_limits<double>::infinity();
          }
          const Eigen::Vector3d p = view.Unproject(view.NDCX(px), view.NDCY(py), 2.0 * z - 1.0);
          return (z > 0.0f ? (p - r.Origin).dot(r.Direction) : 0.0) - ray.TEnter;
        };
        const std::size_t i = static_cast<std::size_t>(ray.Pixel);
        bool rotated = false;
        for (int w = 0; w < count; ++w)
        {
          const DepthWindow& window = windows[w];
          float* const target = window.Image + 4 * i;
          const RayWindow part = window.Near[i] < window.Far[i]
                                   ? RayWindow{ distance(window.Near[i]), distance(window.Far[i]) }
                                   : RayWindow{};
          if (!(part.End > part.Begin) || part.End <= 0.0 || part.Begin >= ray.Length)
          {
            std::fill(target, target + 4, 0.0f);
            continue;
          }
          if (part.Begin <= 0.0 && part.End >= ray.Length)
          {
            // The whole ray: the image's pixel.
            std::copy(
              this->State.Pixels.data() + 4 * i, this->State.Pixels.data() + 4 * i + 4, target);
            continue;
          }
          if (!rotated)
          {
            offsets.Rotate(ray.Rotation, u, order);
            rotated = true;
          }
          const RayLayout<Code> layout =
            StoredRows<Code>::Of(tile.Stores, ray.FirstRow, attributes, hasSecondCodes)
              .Layout(ray, frames, u, order, dt);
          const Pixel p = BlendWindow(layout, part, tf, alphas, mode, termination,
            attributes.Shading, attributes.GradientOpacity);
          std::copy(p.data(), p.data() + 4, target);
        }
      }
    },
    0, 0.0, tiles);
}

// The code widths the frame loop runs.
template void BlendingPass::BlendTile<std::uint8_t>(
  Tile&, ThreadBuffers&, const TileBlend<std::uint8_t>&) const;
template void BlendingPass::BlendTile<std::uint16_t>(
  Tile&, ThreadBuffers&, const TileBlend<std::uint16_t>&) const;
template void BlendingPass::BlendWindows<std::uint8_t>(const TransferFunctionTable&, BlendMode,
  const DepthWindow*, int, int, const std::vector<std::size_t>*);
template void BlendingPass::BlendWindows<std::uint16_t>(const TransferFunctionTable&, BlendMode,
  const DepthWindow*, int, int, const std::vector<std::size_t>*);

} // namespace savr

// Blends of the stored samples over parts of the rays bounded by window depths: how the image
// composites with translucent layers drawn between those depths.

#include "frame/FrameLoop.h"

#include "frame/FrameLoopTiles.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace savr
{

bool FrameLoop::CanBlendDepthWindows(BlendMode mode) const
{
  return WindowedBlend(mode) && !this->ShowingSinglePass && this->FrameLimitCount > 0 &&
         this->FrameCount > 0 && !this->Tiles.empty();
}

void FrameLoop::BlendDepthWindows(
  const TransferFunctionTable& tf, BlendMode mode, const DepthWindow* windows, int count)
{
  if (!this->CanBlendDepthWindows(mode) || count <= 0)
  {
    return;
  }
  // Each tile's own frames, the frames its pixels hold.
  for (const TileGroup& group : this->Schedule.Groups([](const Tile& tile) { return tile.Frames; }))
  {
    const std::vector<std::size_t>* tiles = group.second.empty() ? nullptr : &group.second;
    if (this->Encoder.Bytes == 1)
    {
      this->BlendWindowTiles<std::uint8_t>(tf, mode, windows, count, group.first, tiles);
    }
    else
    {
      this->BlendWindowTiles<std::uint16_t>(tf, mode, windows, count, group.first, tiles);
    }
  }
}

template <typename Code>
void FrameLoop::BlendWindowTiles(const TransferFunctionTable& tf, BlendMode mode,
  const DepthWindow* windows, int count, int frames, const std::vector<std::size_t>* tiles)
{
  // (The error estimate may have left the offsets and the opacity cache at another count.)
  this->PrepareBlend(tf, frames);
  const double dt = this->Settings.SampleDistance;
  const OffsetSequence& offsets = this->Offsets;
  // All three interior interval lengths tabulated: the walk of a part is not the plain blend's.
  const double gap = OffsetSequence::SmallestGap(frames) * dt;
  this->WindowAlphas.Prepare(tf, gap, 2.0 * gap, 1.5 * gap);
  const AlphaCache& alphas = this->WindowAlphas;
  const double termination = this->Settings.StopTransmittance();
  const View& view = this->CurrentViewData;
  const Attributes attributes = this->CurrentAttributes();
  const bool hasSecondCodes = this->Source->HasSecondCode();
  this->ForEachTile(
    [&](Tile& tile, Buffers& buffers)
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
            std::copy(this->Pixels.data() + 4 * i, this->Pixels.data() + 4 * i + 4, target);
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

} // namespace savr

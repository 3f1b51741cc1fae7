// A tile's stores: laid out per ray, grown as frames accumulate, and laid out anew where the
// rows a ray keeps change.

#include "frame/RayStores.h"

#include <algorithm>
#include <utility>

namespace savr
{

std::size_t StoreLayout::BytesPerSample() const
{
  return static_cast<std::size_t>(this->CodeBytes) + (this->Normals ? 2 : 0) +
         (this->ComponentNormals ? 8 : 0) + (this->Magnitudes ? 1 : 0) +
         (this->ComponentMagnitudes ? 4 : 0) + (this->SecondCodes ? 2 : 0);
}

template <typename Other, typename F>
void RayStores::EachStore(Other& other, F&& f)
{
  f(this->Codes, other.Codes);
  f(this->Normals, other.Normals);
  f(this->Magnitudes, other.Magnitudes);
  f(this->ComponentNormals, other.ComponentNormals);
  f(this->ComponentMagnitudes, other.ComponentMagnitudes);
  f(this->SecondCodes, other.SecondCodes);
}

void RayStores::Lay(const StoreLayout& layout, std::size_t rows, int capacity, bool reuse)
{
  const auto set = [&](SampleStore& store, bool used, int bytes)
  {
    if (reuse)
    {
      store.Lay(used ? rows : 0, bytes, capacity);
      return;
    }
    store.Reset(used ? rows : 0, bytes);
    if (capacity > 0)
    {
      store.Grow(capacity, 0);
    }
  };
  set(this->Codes, true, layout.CodeBytes);
  set(this->Normals, layout.Normals, 2);
  set(this->ComponentNormals, layout.ComponentNormals, 8);
  set(this->Magnitudes, layout.Magnitudes, 1);
  set(this->ComponentMagnitudes, layout.ComponentMagnitudes, 4);
  set(this->SecondCodes, layout.SecondCodes, 2);
}

void RayStores::Free()
{
  this->Codes.Reset(0, 1);
  this->Normals.Reset(0, 1);
  this->Magnitudes.Reset(0, 1);
  this->ComponentNormals.Reset(0, 8);
  this->ComponentMagnitudes.Reset(0, 4);
  this->SecondCodes.Reset(0, 1);
}

void RayStores::Grow(int capacity, int frames)
{
  this->Codes.Grow(capacity, frames);
  this->Normals.Grow(capacity, frames);
  this->Magnitudes.Grow(capacity, frames);
  this->ComponentNormals.Grow(capacity, frames);
  this->ComponentMagnitudes.Grow(capacity, frames);
  this->SecondCodes.Grow(capacity, frames);
}

std::size_t RayStores::MemoryInUse() const
{
  return this->Codes.MemoryInUse() + this->Normals.MemoryInUse() + this->Magnitudes.MemoryInUse() +
         this->ComponentNormals.MemoryInUse() + this->ComponentMagnitudes.MemoryInUse() +
         this->SecondCodes.MemoryInUse();
}

void RayStores::KeepRows(
  std::vector<RayInfo>& rays, const RayStores& sampled, const StoreLayout& layout, int capacity)
{
  // Rows start past the largest front, so that every ray's row 0 has a row number.
  std::size_t pad = 0;
  std::size_t kept = 0;
  for (const RayInfo& ray : rays)
  {
    pad = std::max(pad, static_cast<std::size_t>(ray.Front));
    kept += static_cast<std::size_t>(ray.Horizon - ray.Front);
  }
  this->Lay(layout, pad + kept, capacity);
  std::size_t next = pad;
  for (RayInfo& ray : rays)
  {
    const std::size_t count = static_cast<std::size_t>(ray.Horizon - ray.Front);
    this->EachStore(sampled,
      [&](SampleStore& to, const SampleStore& from)
      {
        if (to.RowCount() > 0)
        {
          to.CopyRows(from, ray.FirstRow + ray.Front, next, count, 1);
        }
      });
    ray.FirstRow = next - static_cast<std::size_t>(ray.Front);
    next += count;
  }
}

void RayStores::RelayWholeRays(std::vector<RayInfo>& rays, const std::vector<char>& whole,
  RayStores& scratch, const StoreLayout& layout, int capacity)
{
  std::size_t pad = 0;
  std::size_t rows = 0;
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    const RayInfo& ray = rays[i];
    pad = whole[i] ? pad : std::max(pad, static_cast<std::size_t>(ray.Front));
    rows += static_cast<std::size_t>(whole[i] ? ray.SamplesPerFrame : ray.Horizon - ray.Front);
  }
  scratch.Lay(layout, pad + rows, capacity);
  std::size_t next = pad;
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    RayInfo& ray = rays[i];
    if (whole[i])
    {
      ray.Front = 0;
      ray.Back = ray.SamplesPerFrame;
      ray.FirstRow = next;
      next += static_cast<std::size_t>(ray.SamplesPerFrame);
      continue;
    }
    const std::size_t count = static_cast<std::size_t>(ray.Horizon - ray.Front);
    scratch.EachStore(*this,
      [&](SampleStore& to, SampleStore& from)
      {
        if (to.RowCount() > 0)
        {
          to.CopyRows(from, ray.FirstRow + ray.Front, next, count, capacity);
        }
      });
    ray.FirstRow = next - static_cast<std::size_t>(ray.Front);
    next += count;
  }
  this->EachStore(scratch, [](SampleStore& a, SampleStore& b) { std::swap(a, b); });
  scratch.Lay(layout, 0, 0); // the old stores go
}

int RayStores::NextCapacity(int capacity, int limit)
{
  return std::min(std::max(4, 4 * capacity), limit);
}

std::size_t RayStores::PeakSlots(int limit)
{
  std::size_t peak = 0;
  for (int capacity = 0; capacity < limit;)
  {
    const int next = NextCapacity(capacity, limit);
    peak = std::max<std::size_t>(peak, static_cast<std::size_t>(capacity) + next);
    capacity = next;
  }
  return peak;
}

} // namespace savr

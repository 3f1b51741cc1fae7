#include "OffsetSequence.h"

#include <algorithm>
#include <numeric>

namespace savr
{

double RadicalInverse2(std::uint32_t k)
{
  k = (k << 16) | (k >> 16);
  k = ((k & 0x00ff00ffu) << 8) | ((k & 0xff00ff00u) >> 8);
  k = ((k & 0x0f0f0f0fu) << 4) | ((k & 0xf0f0f0f0u) >> 4);
  k = ((k & 0x33333333u) << 2) | ((k & 0xccccccccu) >> 2);
  k = ((k & 0x55555555u) << 1) | ((k & 0xaaaaaaaau) >> 1);
  return k * 0x1p-32;
}

double PixelRotation(int x, int y)
{
  // A 32-bit integer hash of the pixel: well mixed, and exactly representable as a double.
  std::uint32_t h =
    static_cast<std::uint32_t>(x) * 0x8da6b343u ^ static_cast<std::uint32_t>(y) * 0xd8163841u;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h * 0x1p-32;
}

double PixelPhase(int x, int y)
{
  std::uint32_t h =
    static_cast<std::uint32_t>(x) * 0x9e3779b1u ^ static_cast<std::uint32_t>(y) * 0x85ebca77u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return static_cast<double>(h >> 16) + PixelRotation(x, y);
}

void OffsetSequence::Resize(int frames)
{
  this->Base.resize(frames);
  for (int k = 0; k < frames; ++k)
  {
    this->Base[k] = RadicalInverse2(static_cast<std::uint32_t>(k));
  }
  this->Sorted.resize(frames);
  std::iota(this->Sorted.begin(), this->Sorted.end(), 0);
  std::sort(this->Sorted.begin(), this->Sorted.end(),
    [this](int a, int b) { return this->Base[a] < this->Base[b]; });
}

double OffsetSequence::SmallestGap(int frames)
{
  double gap = 1.0;
  for (int k = 1; k < frames; k *= 2)
  {
    gap *= 0.5;
  }
  return gap;
}

int OffsetSequence::Rotate(double rotation, double* u, int* order) const
{
  const int frames = this->Frames();
  for (int k = 0; k < frames; ++k)
  {
    u[k] = RotatedOffset(this->Base[k], rotation);
  }
  // Rotation is a cyclic shift of the sorted order: the offsets that wrap past 1 come first.
  int firstWrapped = frames;
  for (int s = 0; s < frames; ++s)
  {
    if (this->Base[this->Sorted[s]] + rotation >= 1.0)
    {
      firstWrapped = s;
      break;
    }
  }
  int out = 0;
  for (int s = firstWrapped; s < frames; ++s)
  {
    order[out++] = this->Sorted[s];
  }
  for (int s = 0; s < firstWrapped; ++s)
  {
    order[out++] = this->Sorted[s];
  }
  return firstWrapped % std::max(frames, 1);
}

} // namespace savr

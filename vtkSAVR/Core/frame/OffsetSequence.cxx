#include "frame/OffsetSequence.h"

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

namespace
{
// A well-mixed 32-bit hash of a pixel: two multipliers for the coordinates, then three
// xor-shifts with two multiplications between them.
struct PixelHash
{
  std::uint32_t X, Y, M1, M2;
  int S1, S2, S3;

  std::uint32_t operator()(int x, int y) const
  {
    std::uint32_t h =
      static_cast<std::uint32_t>(x) * this->X ^ static_cast<std::uint32_t>(y) * this->Y;
    h ^= h >> this->S1;
    h *= this->M1;
    h ^= h >> this->S2;
    h *= this->M2;
    h ^= h >> this->S3;
    return h;
  }
};

constexpr PixelHash kRotationHash{ 0x8da6b343u, 0xd8163841u, 0x7feb352du, 0x846ca68bu, 16, 15, 16 };
constexpr PixelHash kPhaseHash{ 0x9e3779b1u, 0x85ebca77u, 0x2c1b3c6du, 0x297a2d39u, 15, 12, 15 };
} // namespace

double PixelRotation(int x, int y)
{
  // Exactly representable as a double.
  return kRotationHash(x, y) * 0x1p-32;
}

double PixelPhase(int x, int y)
{
  return static_cast<double>(kPhaseHash(x, y) >> 16) + PixelRotation(x, y);
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
  const int shift = this->RotatedOffsets(rotation, u);
  this->Order(shift, order);
  return shift;
}

int OffsetSequence::RotatedOffsets(double rotation, double* u) const
{
  const int frames = this->Frames();
  for (int k = 0; k < frames; ++k)
  {
    u[k] = RotatedOffset(this->Base[k], rotation);
  }
  // Rotation is a cyclic shift of the sorted order: the offsets that wrap past 1 (the last in
  // sorted order) come first. Counted without a branch on the rotation.
  int unwrapped = 0;
  for (int s = 0; s < frames; ++s)
  {
    unwrapped += static_cast<int>(this->Base[this->Sorted[s]] + rotation < 1.0);
  }
  return unwrapped < frames ? unwrapped : 0;
}

void OffsetSequence::Order(int shift, int* order) const
{
  const int frames = this->Frames();
  for (int s = 0; s < frames; ++s)
  {
    const int from = s + shift;
    order[s] = this->Sorted[from < frames ? from : from - frames];
  }
}

} // namespace savr

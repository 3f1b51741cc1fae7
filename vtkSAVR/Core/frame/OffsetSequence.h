#pragma once
// Where each frame samples inside the base step: the base-2 radical inverse (van der Corput) of
// the frame index, rotated per pixel by a constant (Cranley-Patterson). After 2^m frames the union
// of offsets is the regular grid {i / 2^m} shifted by the rotation.

#include <cstdint>
#include <vector>

namespace savr
{

/// Base-2 radical inverse of k: bits of k mirrored around the binary point.
double RadicalInverse2(std::uint32_t k);

/// A per-pixel rotation in [0, 1), a fixed function of the pixel (never of time or thread).
double PixelRotation(int x, int y);

/// PixelRotation(x, y) plus a whole number in [0, 2^16) of its own, also a fixed function of the
/// pixel: in units of a length L, the pixel's phase along its ray. In units of a step s it is
/// rotated by frac(PixelPhase * L / s): PixelRotation when s = L, and spread over [0, 1) for a
/// coarser s as well.
double PixelPhase(int x, int y);

/// Offsets of frames [0, frames) and their ascending order.
class OffsetSequence
{
public:
  explicit OffsetSequence(int frames = 0) { this->Resize(frames); }

  void Resize(int frames);
  int Frames() const { return static_cast<int>(this->Base.size()); }

  /// Offset of frame k without rotation.
  double Offset(int k) const { return this->Base[k]; }

  /// Frame index of the p-th smallest offset without rotation.
  int SortedFrame(int p) const { return this->Sorted[p]; }

  /// Rotated offsets `u[k]` of every frame and the frame indices `order` sorted by them.
  /// Returns the shift: order[s] is SortedFrame((s + shift) % Frames()).
  int Rotate(double rotation, double* u, int* order) const;

  /// Rotate in two parts, for callers that keep the orders of every shift: the rotated offsets
  /// `u[k]`, and the shift.
  int RotatedOffsets(double rotation, double* u) const;
  /// The frame indices sorted by their offsets rotated with this shift.
  void Order(int shift, int* order) const;

  /// The gaps between consecutive offsets of this many frames take at most two values: the
  /// smaller is 1 / 2^ceil(log2(frames)), the larger twice that.
  static double SmallestGap(int frames);

private:
  std::vector<double> Base;
  std::vector<int> Sorted; // frame indices by ascending base offset
};

/// Offset of frame k rotated by `rotation`, in [0, 1).
inline double RotatedOffset(double base, double rotation)
{
  // Without a branch: the rotation is random per pixel, so a branch on it is mispredicted half
  // the time. u lies in [0, 2), so its whole part is 0 or 1 (and u - 0.0 is u, bit for bit).
  const double u = base + rotation;
  return u - static_cast<double>(static_cast<int>(u));
}

} // namespace savr

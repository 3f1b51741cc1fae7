#pragma once
// The codes a stored sample's attributes take: a gradient's direction as a 16-bit octahedral
// normal, its length as an 8-bit magnitude, and the 128-bit word they travel in to the blends,
// with a second code or independent components' own codes.

#include <Eigen/Core>

#include <cstdint>

namespace savr
{

/// Quantization steps per octahedral coordinate of a normal code: codes below
/// kNormalSteps * kNormalSteps are directions.
constexpr int kNormalSteps = 255;
/// Stored for samples whose gradient is zero or undefined.
constexpr std::uint16_t kNoNormal = 0xFFFF;
/// In a sample's normal field: its independent components have normals of their own
/// (ComponentNormalOf). No direction has this code (EncodeNormal's codes end at 0xFE00).
constexpr std::uint16_t kComponentNormals = 0xFFFE;

/// A sample's stored attributes travel together in one 128-bit word: the normal code in bits 0
/// to 15 (or kComponentNormals); in bits 16 to 31 the gradient-magnitude code (one component,
/// low 8 bits) or the second code (several components); in bits 32 to 63 the gradient-magnitude
/// codes of independent components, a byte each (ComponentMagnitudeOf); in bits 64 to 127 their
/// normal codes, 16 bits each (ComponentNormalOf).
using SampleAttributes = unsigned __int128;

inline std::uint16_t NormalOf(SampleAttributes attributes)
{
  return static_cast<std::uint16_t>(attributes & 0xFFFFu);
}
inline std::uint32_t MagnitudeOf(SampleAttributes attributes)
{
  return static_cast<std::uint32_t>((attributes >> 16) & 0xFFu);
}
inline std::uint32_t SecondCodeOf(SampleAttributes attributes)
{
  return static_cast<std::uint32_t>((attributes >> 16) & 0xFFFFu);
}
inline std::uint32_t ComponentMagnitudeOf(SampleAttributes attributes, int component)
{
  return static_cast<std::uint32_t>((attributes >> (32 + 8 * component)) & 0xFFu);
}
/// The word of four components' magnitude codes (their bytes in component order) as attributes.
inline SampleAttributes WithComponentMagnitudes(std::uint32_t codes)
{
  return static_cast<SampleAttributes>(codes) << 32;
}
inline std::uint16_t ComponentNormalOf(SampleAttributes attributes, int component)
{
  return static_cast<std::uint16_t>((attributes >> (64 + 16 * component)) & 0xFFFFu);
}
/// Four components' normal codes (16 bits each, component 0 lowest) as attributes, with the
/// normal field saying so.
inline SampleAttributes WithComponentNormals(std::uint64_t codes)
{
  return (static_cast<SampleAttributes>(codes) << 64) | kComponentNormals;
}

/// 8-bit code of the gradient's length: `scale` codes per scalar unit per world unit, clamped.
std::uint8_t EncodeMagnitude(const float gradient[3], double scale);

/// Octahedral code of the direction of `gradient` (world space), or kNoNormal.
std::uint16_t EncodeNormal(const float gradient[3]);
/// The unit normal of a code (undefined for kNoNormal).
Eigen::Vector3f DecodeNormal(std::uint16_t code);

} // namespace savr

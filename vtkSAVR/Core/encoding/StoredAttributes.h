#pragma once
// What a frame stores with each sample besides its code: a normal for shading, a gradient
// magnitude for gradient opacity, or each component's own for independent components; the
// tables the blends read them with; and how a gradient becomes those codes.

#include "encoding/AttributeCodes.h"

#include <array>
#include <cstdint>

namespace savr
{

class ShadingTable;
class GradientOpacityTable;
struct IsoSurfaces;

/// What a frame stores with each sample besides its code, the tables the blends read it with,
/// and how a gradient becomes those attributes.
struct StoredAttributes
{
  bool Normals = false;    // shading: store and use normals
  bool Magnitudes = false; // gradient opacity: store and use magnitudes
  double MagnitudeScale = 1.0;
  // Independent components shaded, gradient opacity: store and use each component's normal,
  // magnitude.
  bool ComponentNormals = false;
  bool ComponentMagnitudes = false;
  std::array<double, 4> ComponentScales = { 1.0, 1.0, 1.0, 1.0 };
  const ShadingTable* Shading = nullptr;
  const GradientOpacityTable* GradientOpacity = nullptr;
  const IsoSurfaces* Isos = nullptr;

  bool Any() const
  {
    return this->Normals || this->Magnitudes || this->ComponentNormals || this->ComponentMagnitudes;
  }
  bool AnyComponents() const { return this->ComponentNormals || this->ComponentMagnitudes; }
  SampleAttributes Encode(const float gradient[3]) const
  {
    return (this->Normals ? EncodeNormal(gradient) : kNoNormal) |
           (this->Magnitudes
               ? SampleAttributes(EncodeMagnitude(gradient, this->MagnitudeScale)) << 16
               : 0u);
  }
  // The magnitude codes of four components' gradients (12 floats, as
  // Sampler::ComponentGradientsAlongRay gives a sample's), component 0 in the lowest byte.
  std::uint32_t ComponentMagnitudeCodes(const float* gradients) const
  {
    std::uint32_t codes = 0;
    for (int c = 0; c < 4; ++c)
    {
      codes |=
        static_cast<std::uint32_t>(EncodeMagnitude(gradients + 3 * c, this->ComponentScales[c]))
        << (8 * c);
    }
    return codes;
  }
  // Their normal codes, component 0 in the lowest 16 bits.
  static std::uint64_t ComponentNormalCodes(const float* gradients)
  {
    std::uint64_t codes = 0;
    for (int c = 0; c < 4; ++c)
    {
      codes |= static_cast<std::uint64_t>(EncodeNormal(gradients + 3 * c)) << (16 * c);
    }
    return codes;
  }
  // A sample's attributes of its components (ComponentGradientsAlongRay's 12 floats), in
  // place of those of `single` that they replace.
  SampleAttributes WithComponents(SampleAttributes single, const float* gradients) const
  {
    if (this->ComponentNormals)
    {
      single = (single & ~SampleAttributes(0xFFFFu)) |
               WithComponentNormals(ComponentNormalCodes(gradients));
    }
    if (this->ComponentMagnitudes)
    {
      single |= WithComponentMagnitudes(this->ComponentMagnitudeCodes(gradients));
    }
    return single;
  }
};

} // namespace savr

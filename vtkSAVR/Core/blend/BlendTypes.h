#pragma once
// The types every blend shares: the blend modes, a pixel, the part of a ray a blend covers, the
// interval opacities tabulated per code, and where a stored ray's samples are.

#include "blend/Composite.h"
#include "blend/TransferFunctionTable.h"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <vector>

namespace savr
{

enum class BlendMode
{
  Composite,     // front-to-back emission-absorption
  Maximum,       // transfer function of the largest sample
  Minimum,       // transfer function of the smallest sample
  Average,       // transfer function of the length-weighted mean sample
  Additive,      // sum of interval opacities times colour, without attenuation
  PreIntegrated, // composite, each segment between consecutive samples pre-integrated
  Isosurface,    // surfaces where the value crosses iso values, composited front to back
  Slice, // the transfer function at the ray's crossing with a plane (FrameLoop::SetSlicePlane)
  AverageGrey, // VTK's GPU average intensity: opaque grey, the length-weighted mean of the
               // transfer function's opacity times the value normalized over the codes' range
  AdditiveGrey // VTK's GPU additive intensity: opaque grey, the integral over the ray of the
               // transfer function's opacity (per unit distance) times the normalized value
};

/// Isosurfaces for the Isosurface blend: the values, and each one's colour and opacity.
struct IsoSurfaces
{
  std::uint64_t Generation = 0; // changed by whoever changes the surfaces
  std::vector<double> Values;
  std::vector<Eigen::Array3d> Colors;
  std::vector<double> Opacities;
};

/// A part [Begin, End] of a ray, in distance from its entry point: a blend over it takes each
/// sample's interval where it overlaps the part, so that blends over adjacent parts composite to
/// the blend over both.
struct RayWindow
{
  double Begin = 0.0;
  double End = 0.0;
};

/// Transmittance below which a composite blend stops unless told otherwise (a frame loop stops
/// at FrameSettings::Termination).
constexpr double kNegligibleTransmittance = 1e-6;

/// Interval opacities tabulated for the (at most two) interior gap lengths of a ray, so that the
/// per-sample cost is a lookup; other intervals (ray ends) use IntervalAlpha. A third length
/// (`middleStep`, when positive) is looked up after the two.
class AlphaCache
{
public:
  void Prepare(const TransferFunctionTable& table, double smallStep, double largeStep,
    double middleStep = 0.0);

  double Alpha(const TransferFunctionTable& table, std::uint32_t code, double h) const
  {
    for (int i = 0; i < 3; ++i)
    {
      if (std::abs(h - this->Step[i]) <= 1e-9 * this->Step[i])
      {
        return this->Table[i][code];
      }
    }
    return table.IntervalAlpha(code, h);
  }

  /// The opacities of every code for the interval `h`, if tabulated (else null).
  const double* TableFor(double h) const
  {
    for (int i = 0; i < 3; ++i)
    {
      if (std::abs(h - this->Step[i]) <= 1e-9 * this->Step[i] && !this->Table[i].empty())
      {
        return this->Table[i].data();
      }
    }
    return nullptr;
  }

private:
  // Without a middle step the third is the second again (never reached: the second matches).
  double Step[3] = { 0.0, 0.0, 0.0 };
  std::uint64_t Generation = 0;
  std::vector<double> Table[3];
};

/// Where a ray's samples are and in which order to read them: sample (j, slot) lies at ray
/// distance (j + U[slot]) * Dt from the entry point and is valid while that is below `Length`.
/// Codes are stored slot-major: code(j, slot) = Codes[j * Capacity + slot]. Rows before
/// `FirstRow` are not read: every sample there is transparent to the blend, and the blends give
/// the bits they would give reading them.
template <typename Code>
struct RayLayout
{
  const Code* Codes = nullptr;
  const std::uint8_t* Magnitudes = nullptr; // gradient-magnitude codes as `Codes`, when needed
  int SamplesPerFrame = 0;
  int FirstRow = 0;
  int Capacity = 1;
  int Frames = 1;
  const double* U = nullptr;              // per slot
  const int* Order = nullptr;             // slots by ascending U
  const std::uint16_t* Normals = nullptr; // normal codes laid out as `Codes`, when shading
  const std::uint16_t* SecondCodes =
    nullptr; // second codes laid out as `Codes`, when the data has them
  // Independent components' normal codes (16 bits each, component 0 lowest) laid out as
  // `Codes`, when shading them.
  const std::uint64_t* ComponentNormals = nullptr;
  // Independent components' magnitude codes (a byte each, component 0 lowest) laid out as
  // `Codes`, with their gradient opacity.
  const std::uint32_t* ComponentMagnitudes = nullptr;
  double Dt = 1.0;
  double Length = 0.0;
};

} // namespace savr

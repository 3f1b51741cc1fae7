#pragma once
// Shading of stored samples: a gradient is stored as a 16-bit octahedral normal, and the
// lighting of every normal code is tabulated (diffuse and specular factors per colour channel)
// whenever the lights, the view or the coefficients change, so that editing them re-blends
// without resampling. Lighting follows VTK's volume mappers: the normal opposes the gradient,
// two-sided when asked (the normal turned to face the viewer, as the fixed-point mapper does),
// ambient from each light's ambient colour, diffuse and specular only where the normal faces the
// light, and ambient alone where there is no gradient.

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace savr
{

/// Stored for samples whose gradient is zero or undefined.
constexpr std::uint16_t kNoNormal = 0xFFFF;

/// A sample's stored attributes travel together: the normal code in the low 16 bits, the
/// gradient-magnitude code in the next 8.
inline std::uint16_t NormalOf(std::uint32_t attributes)
{
  return static_cast<std::uint16_t>(attributes & 0xFFFFu);
}
inline std::uint32_t MagnitudeOf(std::uint32_t attributes)
{
  return (attributes >> 16) & 0xFFu;
}

/// 8-bit code of the gradient's length: `scale` codes per scalar unit per world unit, clamped.
std::uint8_t EncodeMagnitude(const float gradient[3], double scale);

/// Octahedral code of the direction of `gradient` (world space), or kNoNormal.
std::uint16_t EncodeNormal(const float gradient[3]);
/// The unit normal of a code (undefined for kNoNormal).
Eigen::Vector3f DecodeNormal(std::uint16_t code);

struct Light
{
  Eigen::Vector3d Direction = Eigen::Vector3d::UnitZ(); // towards the light, unit length
  Eigen::Vector3d Ambient = Eigen::Vector3d::Zero();    // ambient colour
  Eigen::Vector3d Diffuse = Eigen::Vector3d::Ones();    // diffuse colour times intensity
  Eigen::Vector3d Specular = Eigen::Vector3d::Ones();   // specular colour times intensity
};

/// One set of vtkVolumeProperty's lighting coefficients (per component).
struct ShadingCoefficients
{
  double Ambient = 0.1;
  double Diffuse = 0.7;
  double Specular = 0.2;
  double SpecularPower = 10.0;
};

class ShadingTable
{
public:
  /// `toViewer` is the unit direction towards the camera (one for the whole image, as VTK's
  /// fixed-point mapper does). Coefficients as vtkVolumeProperty's.
  void Build(const std::vector<Light>& lights, const Eigen::Vector3d& toViewer, double ambient,
    double diffuse, double specular, double specularPower, bool twoSided = true)
  {
    this->Build(lights, toViewer,
      std::vector<ShadingCoefficients>{ { ambient, diffuse, specular, specularPower } }, twoSided);
  }
  /// The same, a table per set of coefficients: independent components each lit with their own
  /// (at most 4; none gives the defaults).
  void Build(const std::vector<Light>& lights, const Eigen::Vector3d& toViewer,
    const std::vector<ShadingCoefficients>& components, bool twoSided = true);

  /// Shaded colour of a sample of colour `rgb` with normal code `normal` (the first set).
  Eigen::Array3d Shade(const float* rgb, std::uint16_t normal) const
  {
    const float* d = &this->Factors[6 * normal];
    return Eigen::Array3d(rgb[0] * d[0] + d[3], rgb[1] * d[1] + d[4], rgb[2] * d[2] + d[5]);
  }

  /// The factors of a normal code: diffuse (ambient included) per channel, then specular; of
  /// the first set, or of set `component`.
  const float* FactorsOf(std::uint16_t normal) const { return &this->Factors[6 * normal]; }
  const float* FactorsOf(std::uint16_t normal, int component) const
  {
    return &this->Factors[6 * (static_cast<std::size_t>(component) * kCodes + normal)];
  }
  /// Sets of coefficients tabulated (1 to 4).
  int Components() const { return this->Sets; }

  /// Changes on every Build.
  std::uint64_t Generation() const { return this->Built; }

private:
  static constexpr std::size_t kCodes = 65536;
  std::uint64_t Built = 0;
  int Sets = 1;
  std::vector<float> Factors; // per set, per code: diffuse rgb (ambient included), specular rgb
};

} // namespace savr

namespace savr
{

class TransferFunctionTable;

/// Gradient opacity: a factor per gradient-magnitude code (256 codes over [0, 255 / Scale] in
/// scalar units per world unit) that multiplies a sample's scalar opacity before the opacity is
/// corrected for the interval, as VTK's mappers combine them.
class GradientOpacityTable
{
public:
  void Build(const double* factors, double scale);
  double Scale() const { return this->CodesPerUnit; }
  /// Opacity of an interval of length h of a sample with value code `code` and magnitude code
  /// `magnitude`.
  double IntervalAlpha(
    const TransferFunctionTable& tf, std::uint32_t code, std::uint32_t magnitude, double h) const;
  std::uint64_t Generation() const { return this->Built; }

private:
  double Factors[256] = {};
  double CodesPerUnit = 1.0;
  std::uint64_t Built = 0;
};

} // namespace savr

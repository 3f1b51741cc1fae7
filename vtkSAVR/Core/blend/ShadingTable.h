#pragma once
// Shading of stored samples: a gradient is stored as a 16-bit octahedral normal, and the
// lighting of every normal code is tabulated (diffuse and specular factors per colour channel)
// whenever the lights, the view or the coefficients change, so that editing them re-blends
// without resampling. Lighting follows VTK's volume mappers: the normal opposes the gradient,
// two-sided when asked (the normal turned to face the viewer, as the fixed-point mapper does),
// ambient from each light's ambient colour, diffuse and specular only where the normal faces the
// light, and ambient alone where there is no gradient.

#include "blend/Composite.h"
#include "encoding/AttributeCodes.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace savr
{

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
    return composite::Shaded(rgb, this->FactorsOf(normal));
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
/// corrected for the interval, as VTK's mappers combine them. Independent components have a set
/// of factors each, over a scale of their own, applied to their own magnitudes.
class GradientOpacityTable
{
public:
  static constexpr int kMostSets = 4;
  /// One set: the single component's.
  void Build(const double* factors, double scale) { this->Build(factors, &scale, 1); }
  /// `sets` sets (1 to 4) of 256 factors one after another, and each one's scale.
  void Build(const double* factors, const double* scales, int sets);
  double Scale(int set = 0) const { return this->CodesPerUnit[set]; }
  int Sets() const { return this->Count; }
  /// The factor of magnitude code `magnitude` in set `set`.
  double Factor(int set, std::uint32_t magnitude) const
  {
    return this->Factors[256 * set + (magnitude & 0xFFu)];
  }
  /// Opacity of an interval of length h of a sample with value code `code` and magnitude code
  /// `magnitude` (the first set).
  double IntervalAlpha(
    const TransferFunctionTable& tf, std::uint32_t code, std::uint32_t magnitude, double h) const;
  std::uint64_t Generation() const { return this->Built; }

private:
  double Factors[kMostSets * 256] = {};
  double CodesPerUnit[kMostSets] = { 1.0, 1.0, 1.0, 1.0 };
  int Count = 1;
  std::uint64_t Built = 0;
};

} // namespace savr

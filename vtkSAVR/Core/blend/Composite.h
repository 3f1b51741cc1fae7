#pragma once
// The front-to-back composite, defined once: the opacity of a sample's interval, the light it
// sends toward the viewer, and how it is laid behind what a pixel already holds. Every composite
// in the engine is written with these: the blends of Integrator.h (the definition the others are
// held to), the tabled fast paths of PlainComposite.h, the single pass and the reference
// integrator. The AVX2 composite (StoredAVX2.h) cannot call them; it and every other fast path
// are checked against the definition by TestCompositePaths.

#include <Eigen/Core>

#include <cmath>

namespace savr
{

/// Premultiplied RGBA of one pixel.
using Pixel = Eigen::Array4f;

/// The composite's steps, named as a reader asks for them: composite::Over, composite::
/// IntervalOpacity.
namespace composite
{

/// The opacity of an interval of length `h` through a medium of extinction `sigma`
/// (Beer-Lambert; expm1 keeps the small opacities of thin intervals exact).
inline double IntervalOpacity(double sigma, double h)
{
  return -std::expm1(-sigma * h);
}

/// The light a sample of colour `rgb` sends toward the viewer, from its normal's shading
/// factors `f` (ShadingTable::FactorsOf): the colour times the diffuse factor (ambient
/// included), plus the specular one. Computed in float, as the factors are stored.
inline Eigen::Array3d Shaded(const float* rgb, const float* f)
{
  return Eigen::Array3d(rgb[0] * f[0] + f[3], rgb[1] * f[1] + f[4], rgb[2] * f[2] + f[5]);
}

/// Shaded, for a tabulated sample: `entry` holds the opacity, then the colour times it, and the
/// light comes out times the opacity too.
inline Eigen::Array3d ShadedPremultiplied(const double* entry, const float* f)
{
  return Eigen::Array3d(entry[1] * f[0] + entry[0] * f[3], entry[2] * f[1] + entry[0] * f[4],
    entry[3] * f[2] + entry[0] * f[5]);
}

/// Lays a sample of opacity `a` and colour `colour` behind what a pixel holds: its colour so
/// far `C` and the transmittance `T` left in front of the sample.
inline void Over(Eigen::Array3d& C, double& T, double a, const Eigen::Array3d& colour)
{
  C += (T * a) * colour;
  T *= 1.0 - a;
}

/// Over, for a sample whose colour is already times its opacity `a` (a tabulated sample).
inline void OverPremultiplied(
  Eigen::Array3d& C, double& T, double a, const Eigen::Array3d& premultiplied)
{
  C += T * premultiplied;
  T *= 1.0 - a;
}

/// The pixel a composite leaves: its colour and the opacity, one minus the transmittance.
inline Pixel FrontToBack(const Eigen::Array3d& C, double T)
{
  Pixel p;
  p << static_cast<float>(C[0]), static_cast<float>(C[1]), static_cast<float>(C[2]),
    static_cast<float>(1.0 - T);
  return p;
}

} // namespace composite
} // namespace savr

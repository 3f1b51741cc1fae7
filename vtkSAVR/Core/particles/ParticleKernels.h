#pragma once
// The particles' kernels W(r, h) and what the sampler needs of them: cutoff, normalization,
// peak, and W'(r) / r for gradients (see ParticleKernel for their definitions).

#include <cmath>

namespace savr
{

/// The kernels W(r, h) of a particle of radius h, r the distance from it. Each is exactly 0 at
/// and beyond its cutoff and positive inside it.
enum class ParticleKernel
{
  /// exp(-r^2 / (2 h^2)) up to r = 3 h (where it is still exp(-4.5) = 0.011), 0 beyond: the
  /// Gaussian of radial basis function particle models, not normalized (its peak is 1).
  Gaussian,
  /// The cubic B-spline of SPH in 3D, as VTK's vtkSPHCubicKernel (h its SpatialStep): with
  /// q = r / h, (1 / (pi h^3)) (1/4 (2 - q)^3 - (1 - q)^3), the terms taken only while positive;
  /// cutoff 2 h; integrates to 1 over space.
  SPHCubic,
  /// The quintic spline of SPH in 3D, as VTK's vtkSPHQuinticKernel: (1 / (120 pi h^3))
  /// ((3 - q)^5 - 6 (2 - q)^5 + 15 (1 - q)^5), the terms taken only while positive; cutoff
  /// 3 h; integrates to 1 over space.
  SPHQuintic
};

namespace particles
{

constexpr double kPi = 3.14159265358979323846;

inline double CutoffFactor(ParticleKernel kernel)
{
  return kernel == ParticleKernel::SPHCubic ? 2.0 : 3.0;
}

// The kernel's normalization factor (its peak, for the Gaussian) and largest value.
inline double Normalization(ParticleKernel kernel, double h)
{
  switch (kernel)
  {
    case ParticleKernel::SPHCubic:
      return 1.0 / (kPi * h * h * h);
    case ParticleKernel::SPHQuintic:
      return 1.0 / (120.0 * kPi * h * h * h);
    default:
      return 1.0;
  }
}

inline double PeakValue(ParticleKernel kernel, double h)
{
  // Cubic at q = 0: 1/4 2^3 - 1 = 1; quintic: 3^5 - 6 2^5 + 15 = 66.
  return Normalization(kernel, h) * (kernel == ParticleKernel::SPHQuintic ? 66.0 : 1.0);
}

// Whether the kernel's constants and cutoff are finite and positive for radius h.
inline bool UsableRadius(ParticleKernel kernel, double h)
{
  if (!(h > 0.0) || !std::isfinite(h))
  {
    return false;
  }
  const double cutoff = CutoffFactor(kernel) * h;
  const double peak = PeakValue(kernel, h);
  const double inverseSquare = 1.0 / (h * h);
  return std::isfinite(cutoff) && std::isfinite(cutoff * cutoff) && peak > 0.0 &&
         std::isfinite(peak) && std::isfinite(inverseSquare) && inverseSquare > 0.0;
}

// W(r) and G(r) = W'(r) / r (finite at r = 0) of one particle, from r^2.
template <ParticleKernel K>
struct KernelOf;

template <>
struct KernelOf<ParticleKernel::Gaussian>
{
  explicit KernelOf(double h)
    : InverseTwoSquare(0.5 / (h * h))
  {
  }
  double Value(double r2) const { return std::exp(-r2 * this->InverseTwoSquare); }
  double Derivative(double r2, double value) const
  {
    (void)r2;
    return -2.0 * this->InverseTwoSquare * value;
  }
  double InverseTwoSquare;
};

// What the splines need of h: q = r / h, and the normalization.
template <ParticleKernel K>
struct Spline
{
  explicit Spline(double h)
    : InverseH(1.0 / h)
    , Norm(Normalization(K, h))
  {
  }
  double Q(double r2) const { return std::sqrt(r2) * this->InverseH; }
  double InverseH;
  double Norm;
};

template <>
struct KernelOf<ParticleKernel::SPHCubic> : Spline<ParticleKernel::SPHCubic>
{
  using Spline::Spline;
  double Value(double r2) const
  {
    const double q = this->Q(r2);
    const double a = 2.0 - q;
    const double b = q < 1.0 ? 1.0 - q : 0.0;
    return this->Norm * (0.25 * a * a * a - b * b * b);
  }
  double Derivative(double r2, double value) const
  {
    (void)value;
    const double q = this->Q(r2);
    const double scale = this->Norm * this->InverseH * this->InverseH;
    if (q < 1.0)
    {
      // dW/dq = -3/4 (2 - q)^2 + 3 (1 - q)^2 = -3 q + 9/4 q^2, divided by q in closed form.
      return scale * (-3.0 + 2.25 * q);
    }
    const double a = 2.0 - q;
    return scale * (-0.75 * a * a) / q;
  }
};

template <>
struct KernelOf<ParticleKernel::SPHQuintic> : Spline<ParticleKernel::SPHQuintic>
{
  using Spline::Spline;
  static double Fifth(double x) { return x > 0.0 ? x * x * x * x * x : 0.0; }
  static double Fourth(double x) { return x > 0.0 ? x * x * x * x : 0.0; }
  double Value(double r2) const
  {
    const double q = this->Q(r2);
    return this->Norm * (Fifth(3.0 - q) - 6.0 * Fifth(2.0 - q) + 15.0 * Fifth(1.0 - q));
  }
  double Derivative(double r2, double value) const
  {
    (void)value;
    const double q = this->Q(r2);
    const double scale = -5.0 * this->Norm * this->InverseH * this->InverseH;
    if (q < 1.0)
    {
      // (3 - q)^4 - 6 (2 - q)^4 + 15 (1 - q)^4 = 24 q - 24 q^3 + 10 q^4, divided by q.
      return scale * (24.0 - 24.0 * q * q + 10.0 * q * q * q);
    }
    return scale * (Fourth(3.0 - q) - 6.0 * Fourth(2.0 - q)) / q;
  }
};

/// W of a particle of radius h at squared distance r2 (inside its cutoff).
inline double KernelValue(ParticleKernel kernel, double h, double r2)
{
  switch (kernel)
  {
    case ParticleKernel::SPHCubic:
      return KernelOf<ParticleKernel::SPHCubic>(h).Value(r2);
    case ParticleKernel::SPHQuintic:
      return KernelOf<ParticleKernel::SPHQuintic>(h).Value(r2);
    default:
      return KernelOf<ParticleKernel::Gaussian>(h).Value(r2);
  }
}

} // namespace particles
} // namespace savr

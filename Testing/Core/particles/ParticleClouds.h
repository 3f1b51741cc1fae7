#pragma once
// Particle clouds for the particle sampler's tests, and the kernels written out again from their
// definitions (VTK's vtkSPHCubicKernel and vtkSPHQuinticKernel in 3D, the truncated Gaussian).

#include "particles/ParticleSampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace savr_test
{

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr savr::ParticleKernel kKernels[] = { savr::ParticleKernel::Gaussian,
  savr::ParticleKernel::SPHCubic, savr::ParticleKernel::SPHQuintic };

inline const char* Name(savr::ParticleKernel kernel)
{
  return kernel == savr::ParticleKernel::Gaussian
           ? "Gaussian"
           : (kernel == savr::ParticleKernel::SPHCubic ? "SPH cubic" : "SPH quintic");
}

inline double Cutoff(savr::ParticleKernel kernel)
{
  return kernel == savr::ParticleKernel::SPHCubic ? 2.0 : 3.0;
}

// The kernels as documented (VTK's vtkSPHCubicKernel and vtkSPHQuinticKernel in 3D).
inline double Kernel(savr::ParticleKernel kernel, double r, double h)
{
  const double q = r / h;
  if (q >= Cutoff(kernel))
  {
    return 0.0;
  }
  auto positive = [](double x, int power) { return x > 0.0 ? std::pow(x, power) : 0.0; };
  switch (kernel)
  {
    case savr::ParticleKernel::SPHCubic:
      return (0.25 * positive(2 - q, 3) - positive(1 - q, 3)) / (kPi * h * h * h);
    case savr::ParticleKernel::SPHQuintic:
      return (positive(3 - q, 5) - 6 * positive(2 - q, 5) + 15 * positive(1 - q, 5)) /
             (120 * kPi * h * h * h);
    default:
      return std::exp(-q * q / 2);
  }
}

struct Cloud
{
  std::vector<double> Points;
  std::vector<double> Values;
  std::vector<double> Radii;

  void Add(const Eigen::Vector3d& p, double value, double radius = 0.0)
  {
    this->Points.insert(this->Points.end(), { p.x(), p.y(), p.z() });
    this->Values.push_back(value);
    this->Radii.push_back(radius);
  }
  savr::ParticleDescription Description(
    savr::ParticleKernel kernel, bool normalized, double radius, bool perPoint = false) const
  {
    savr::ParticleDescription d;
    d.Points = this->Points.data();
    d.Values = this->Values.data();
    d.NumberOfPoints = this->Values.size();
    d.Radius = radius;
    d.Radii = perPoint ? this->Radii.data() : nullptr;
    d.Kernel = kernel;
    d.Normalized = normalized;
    return d;
  }
  std::shared_ptr<const savr::ParticleSampler> Sampler(
    savr::ParticleKernel kernel, bool normalized, double radius, bool perPoint = false) const
  {
    std::string error;
    auto sampler =
      savr::MakeParticleSampler(this->Description(kernel, normalized, radius, perPoint), error);
    EXPECT_TRUE(sampler) << error;
    return sampler;
  }
};

inline savr::Ray RayThrough(
  const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double back)
{
  savr::Ray ray;
  ray.Direction = direction.normalized();
  ray.Origin = point - back * ray.Direction;
  return ray;
}

inline Eigen::Vector3d RandomDirection(std::mt19937& random)
{
  std::normal_distribution<double> normal;
  return Eigen::Vector3d(normal(random), normal(random), normal(random)).normalized();
}

} // namespace savr_test

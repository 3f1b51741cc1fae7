#pragma once
// The line that a ray samples through an unstructured mesh, as the mesh's face and box tests
// use it.

#include <Eigen/Core>

namespace savr
{
namespace unstructured
{

inline double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The line o + t d, with what box tests need of it.
struct Line
{
  double O[3];
  double D[3];
  double Inverse[3];
  bool Parallel[3];

  Line(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->O[a] = origin[a];
      this->D[a] = direction[a];
      this->Parallel[a] = direction[a] == 0.0;
      this->Inverse[a] = this->Parallel[a] ? 0.0 : 1.0 / direction[a];
    }
  }
};

} // namespace unstructured
} // namespace savr

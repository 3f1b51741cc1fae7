#include "frame/View.h"

#include <array>
#include <cmath>
#include <limits>

namespace savr
{

void View::HullPixels(const Sampler& source, int pixels[4]) const
{
  std::array<Eigen::Vector3d, 8> corners;
  if (!source.HullCorners(corners))
  {
    return;
  }
  const Eigen::Matrix4d toNDC = this->NDCToWorld.inverse();
  if (!toNDC.allFinite())
  {
    return;
  }
  double lo[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double hi[2] = { -lo[0], -lo[1] };
  for (const Eigen::Vector3d& c : corners)
  {
    const Eigen::Vector4d p = toNDC * Eigen::Vector4d(c[0], c[1], c[2], 1.0);
    if (!(p[3] > 0.0) || !p.allFinite())
    {
      return; // a corner behind the eye: any pixel may see the data
    }
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], p[a] / p[3]);
      hi[a] = std::max(hi[a], p[a] / p[3]);
    }
  }
  // Pixel centre x + 0.5 is at NDC 2 (x + 0.5) / width - 1.
  const int size[2] = { this->Width, this->Height };
  for (int a = 0; a < 2; ++a)
  {
    const double first = std::floor(0.5 * (lo[a] + 1.0) * size[a] - 0.5) - 1.0;
    const double last = std::ceil(0.5 * (hi[a] + 1.0) * size[a] - 0.5) + 1.0;
    pixels[a] = static_cast<int>(std::min(std::max(first, 0.0), static_cast<double>(size[a])));
    pixels[2 + a] =
      static_cast<int>(std::min(std::max(last + 1.0, 0.0), static_cast<double>(size[a])));
  }
}

} // namespace savr

#include "CroppingSampler.h"

#include <algorithm>
#include <limits>

namespace savr
{

CroppingSampler::CroppingSampler(std::shared_ptr<const Sampler> inner,
  const Eigen::Affine3d& worldToData, const double planes[6], std::uint32_t regions)
  : Inner(std::move(inner))
  , WorldToData(worldToData)
  , Regions(regions)
{
  for (int a = 0; a < 3; ++a)
  {
    this->Planes[2 * a] = std::min(planes[2 * a], planes[2 * a + 1]);
    this->Planes[2 * a + 1] = std::max(planes[2 * a], planes[2 * a + 1]);
  }
}

void CroppingSampler::SampleRay(
  const Ray& ray, double t0, double dt, int count, float* out, const SkipMask* skip) const
{
  this->Inner->SampleRay(ray, t0, dt, count, out, skip);
  this->Crop(ray, t0, dt, count, out);
}

void CroppingSampler::SampleRayGradients(
  const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const
{
  this->Inner->SampleRayGradients(ray, t0, dt, count, out, gradients);
  this->Crop(ray, t0, dt, count, out);
  for (int i = 0; i < count; ++i)
  {
    if (out[i] != out[i])
    {
      std::fill(gradients + 3 * static_cast<std::size_t>(i),
        gradients + 3 * static_cast<std::size_t>(i) + 3, 0.0f);
    }
  }
}

void CroppingSampler::Crop(const Ray& ray, double t0, double dt, int count, float* out) const
{
  const Eigen::Vector3d o = this->WorldToData * ray.Origin;
  const Eigen::Vector3d d = this->WorldToData.linear() * ray.Direction;
  for (int i = 0; i < count; ++i)
  {
    if (out[i] != out[i])
    {
      continue;
    }
    const Eigen::Vector3d p = o + (t0 + i * dt) * d;
    int region = 0;
    int weight = 1;
    for (int a = 0; a < 3; ++a, weight *= 3)
    {
      region += weight * ((p[a] >= this->Planes[2 * a]) + (p[a] > this->Planes[2 * a + 1]));
    }
    if (!((this->Regions >> region) & 1u))
    {
      out[i] = std::numeric_limits<float>::quiet_NaN();
    }
  }
}

} // namespace savr

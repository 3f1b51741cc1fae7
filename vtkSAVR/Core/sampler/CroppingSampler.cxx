#include "sampler/CroppingSampler.h"

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

bool CroppingSampler::Restrict(const Ray& ray, double& t0, double& t1) const
{
  if (!this->Inner->Restrict(ray, t0, t1))
  {
    return false;
  }
  constexpr std::uint32_t kMiddleOnly = 1u << 13; // region x = y = z = 1
  if (this->Regions != kMiddleOnly)
  {
    return t0 < t1;
  }
  double enter = 0.0;
  double exit = 0.0;
  const Eigen::Vector3d lo(this->Planes[0], this->Planes[2], this->Planes[4]);
  const Eigen::Vector3d hi(this->Planes[1], this->Planes[3], this->Planes[5]);
  // An affine map keeps the ray's parameter: the box's interval in data coordinates is the
  // world ray's.
  if (!ClipToBox(this->WorldToData * ray.Origin, this->WorldToData.linear() * ray.Direction, lo, hi,
        enter, exit))
  {
    return false;
  }
  t0 = std::max(t0, enter);
  t1 = std::min(t1, exit);
  return t0 < t1;
}

void CroppingSampler::SampleRay(
  const Ray& ray, double t0, double dt, int count, float* out, const SkipMask* skip) const
{
  this->Inner->SampleRay(ray, t0, dt, count, out, skip);
  this->Crop(ray, t0, dt, count, out);
}

void CroppingSampler::SampleAlongPath(const Ray& ray, const PathPiece* path, std::size_t pieces,
  double traceStart, double t0, double dt, int count, float* out) const
{
  this->Inner->SampleAlongPath(ray, path, pieces, traceStart, t0, dt, count, out);
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

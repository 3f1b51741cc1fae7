#pragma once
// The rays of an image: one per pixel centre, from the near plane to the far plane or to the
// depth of opaque geometry already drawn.

#include "sampler/Sampler.h"

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <vector>

namespace savr
{

struct View
{
  int Width = 0;
  int Height = 0;
  /// Inverse of the world-to-normalized-device matrix (OpenGL convention, z in [-1, 1]).
  Eigen::Matrix4d NDCToWorld = Eigen::Matrix4d::Identity();
  /// Optional window-space depth in [0, 1] per pixel, rows from the bottom; empty means none.
  std::vector<float> Depth;
  /// Clipping planes (a, b, c, d) in world coordinates: points with a x + b y + c z + d >= 0
  /// are kept.
  std::vector<Eigen::Vector4d> ClippingPlanes;

private:
  // Set by Prepare: pixel (0, 0)'s homogeneous near and far points and the steps per pixel.
  Eigen::Vector4d Corner[2];
  Eigen::Vector4d StepX = Eigen::Vector4d::Zero();
  Eigen::Vector4d StepY = Eigen::Vector4d::Zero();
  bool Prepared = false;

public:
  /// Narrows [tEnter, tExit] of `ray` to the part every clipping plane keeps; false when
  /// nothing is left.
  bool Clip(const Ray& ray, double& tEnter, double& tExit) const
  {
    for (const Eigen::Vector4d& plane : this->ClippingPlanes)
    {
      const double start = plane.head<3>().dot(ray.Origin) + plane[3];
      const double rate = plane.head<3>().dot(ray.Direction);
      if (rate == 0.0)
      {
        if (start < 0.0)
        {
          return false;
        }
        continue;
      }
      const double t = -start / rate;
      if (rate > 0.0)
      {
        tEnter = std::max(tEnter, t);
      }
      else
      {
        tExit = std::min(tExit, t);
      }
    }
    return tExit > tEnter;
  }

  /// The ray through the centre of pixel (x, y), starting on the near plane; `tMax` is the
  /// distance to the far plane or to the depth buffer, whichever is nearer.
  Ray PixelRay(int x, int y, double& tMax) const
  {
    const Ray ray = this->NearPlaneRay(x, y, tMax);
    if (!this->Depth.empty())
    {
      const double z = this->Depth[static_cast<std::size_t>(y) * this->Width + x];
      if (z < 1.0)
      {
        const Eigen::Vector3d hit = this->Unproject(this->NDCX(x), this->NDCY(y), 2.0 * z - 1.0);
        tMax = std::min(tMax, (hit - ray.Origin).dot(ray.Direction));
      }
    }
    return ray;
  }

  /// The part [tEnter, tExit] of pixel (x, y)'s ray that a renderer samples: inside the data,
  /// in front of the near plane, before opaque geometry, kept by every clipping plane. False
  /// when nothing is left.
  bool Segment(const Sampler& data, int x, int y, Ray& ray, double& tEnter, double& tExit) const
  {
    double tMax = 0.0;
    ray = this->PixelRay(x, y, tMax);
    if (!data.Clip(ray, tEnter, tExit))
    {
      return false;
    }
    tEnter = std::max(tEnter, 0.0);
    tExit = std::min(tExit, tMax);
    return tExit > tEnter && this->Clip(ray, tEnter, tExit);
  }

  /// The ray through the centre of pixel (x, y), starting on the near plane.
  Ray PixelRay(int x, int y) const
  {
    double toFar = 0.0;
    return this->NearPlaneRay(x, y, toFar);
  }

  // Pixel (x, y)'s ray from the near plane, and the distance along it to the far plane.
  Ray NearPlaneRay(int x, int y, double& toFar) const
  {
    Eigen::Vector3d nearPoint;
    Eigen::Vector3d farPoint;
    this->PlanePoints(x, y, nearPoint, farPoint);
    const Eigen::Vector3d span = farPoint - nearPoint;
    toFar = span.norm();
    Ray ray;
    ray.Origin = nearPoint;
    ray.Direction = span * (1.0 / toFar); // one division, not three: this runs for every pixel
    return ray;
  }

  // Pixel (x, y)'s points on the near and far planes.
  void PlanePoints(int x, int y, Eigen::Vector3d& nearPoint, Eigen::Vector3d& farPoint) const
  {
    if (!this->Prepared)
    {
      nearPoint = this->Unproject(this->NDCX(x), this->NDCY(y), -1.0);
      farPoint = this->Unproject(this->NDCX(x), this->NDCY(y), 1.0);
      return;
    }
    const Eigen::Vector4d offset = this->StepX * x + this->StepY * y;
    const Eigen::Vector4d n = this->Corner[0] + offset;
    const Eigen::Vector4d f = this->Corner[1] + offset;
    nearPoint = n.head<3>() * (1.0 / n[3]);
    farPoint = f.head<3>() * (1.0 / f[3]);
  }

  double NDCX(int x) const { return 2.0 * (x + 0.5) / this->Width - 1.0; }
  double NDCY(int y) const { return 2.0 * (y + 0.5) / this->Height - 1.0; }

  /// Precomputes what PixelRay needs per pixel (call after setting NDCToWorld and the size;
  /// PixelRay works without it, only slower).
  void Prepare()
  {
    // The homogeneous points on the near and far planes are affine in the pixel's (x, y).
    const double sx = 2.0 / std::max(this->Width, 1);
    const double sy = 2.0 / std::max(this->Height, 1);
    for (int plane = 0; plane < 2; ++plane)
    {
      const double nz = plane == 0 ? -1.0 : 1.0;
      this->Corner[plane] =
        this->NDCToWorld * Eigen::Vector4d(0.5 * sx - 1.0, 0.5 * sy - 1.0, nz, 1.0);
    }
    this->StepX = this->NDCToWorld.col(0) * sx;
    this->StepY = this->NDCToWorld.col(1) * sy;
    this->Prepared = true;
  }

  /// Narrows the pixels [x0, y0] to [x1, y1) (`pixels`) to those whose rays can meet the data:
  /// around the image of the sampler's hull, when all of it lies in front of the eye (the image
  /// of a convex set then holds every point of it, and each of its points lies on the ray of the
  /// pixel centre it projects to). One pixel more on every side covers round-off.
  void HullPixels(const Sampler& source, int pixels[4]) const;

  Eigen::Vector3d Unproject(double nx, double ny, double nz) const
  {
    const Eigen::Vector4d p = this->NDCToWorld * Eigen::Vector4d(nx, ny, nz, 1.0);
    return p.head<3>() * (1.0 / p[3]); // one division, not three: this runs for every pixel
  }
};

} // namespace savr

#pragma once
// The part of the sampler interface that says where along a ray the data can hold anything:
// the segment inside the data's region (Clip, narrowed by Restrict, bounded by HullCorners),
// and the blocks a pass may skip because its transfer function makes them transparent
// (BlockRanges, SkipDistances, FirstUnskipped). Sampler implements it.

#include "sampler/Ray.h"

#include <array>
#include <cstdint>
#include <vector>

namespace savr
{

/// Blocks of the data that a pass may skip: SampleRay writes NaN for samples in blocks whose
/// flag is set, without reading the data. Indexed like Sampler::BlockRanges. A flag above 1
/// (from Sampler::SkipDistances) also promises that every block fewer rings away than it is
/// skipped too.
struct SkipMask
{
  const std::vector<std::uint8_t>* Skip = nullptr;
};

/// Where along a ray the data can hold anything (see above).
class RayIntervals
{
public:
  virtual ~RayIntervals() = default;

  /// Parameter interval [tEnter, tExit] of the infinite line `ray` inside the data's region.
  /// Returns false when the line misses it.
  virtual bool Clip(const Ray& ray, double& tEnter, double& tExit) const = 0;

  /// Narrows [t0, t1] (a segment Clip gave) to where samples can be other than NaN whatever the
  /// data holds (a cropping box), or returns false when nowhere on it. The frame loop keeps its
  /// sample lattice where Clip put it and drops only the whole steps outside, so narrowing
  /// changes no sample that is kept. The default narrows nothing.
  virtual bool Restrict(const Ray& ray, double& t0, double& t1) const
  {
    (void)ray;
    return t0 < t1;
  }

  /// Eight world points whose convex hull holds every segment Clip gives (the box Clip clips
  /// to), so that the rays of pixels outside the hull's image need no Clip at all; false when
  /// the sampler cannot say.
  virtual bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const
  {
    (void)corners;
    return false;
  }

  /// Turns a pass's skip flags (0 or 1 per block, as BlockRanges) into distances: a skipped
  /// block's flag becomes its distance in rings of blocks (every direction) to the nearest block
  /// that is not skipped, at most 255, so that SampleRay can pass over skipped space many blocks
  /// at a time. Samplers whose blocks have no such layout leave the flags as they are.
  virtual void SkipDistances(std::vector<std::uint8_t>& skip) const { (void)skip; }

  /// The first i in [0, count) whose sample SampleRay with `skip` could return other than NaN
  /// for lying in a skipped block (count when none): a pass whose transfer function makes NaN
  /// transparent may start sampling there. Every sample before it is NaN (in a skipped block, or
  /// outside the data). 0 by default.
  virtual int FirstUnskipped(
    const Ray& ray, double t0, double dt, int count, const SkipMask* skip) const
  {
    (void)ray;
    (void)t0;
    (void)dt;
    (void)count;
    (void)skip;
    return 0;
  }

  /// A ray parameter in [t0, t1] such that every point of the ray in [t0, it) lies in a block
  /// `skip` flags (or outside the data): the entry of the first block along the ray that is not
  /// skipped, found block by block rather than sample by sample; t1 when there is none. t0 by
  /// default.
  virtual double FirstUnskippedAt(const Ray& ray, double t0, double t1, const SkipMask* skip) const
  {
    (void)ray;
    (void)t1;
    (void)skip;
    return t0;
  }

  /// Smallest and largest finite value that sampling can return inside each block of the data
  /// (2 floats per block), or empty when the sampler has no blocks.
  virtual const std::vector<float>& BlockRanges() const
  {
    static const std::vector<float> none;
    return none;
  }
};

} // namespace savr

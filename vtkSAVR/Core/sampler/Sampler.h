#pragma once
// The sampler interface: the only thing the SAVR engine knows about the data. Sampling is
// here (values, gradients, second codes); where rays meet the data and what a pass may skip
// is RayIntervals.h, recording rays' paths PathCache.h.

#include "sampler/PathCache.h"
#include "sampler/Ray.h"
#include "sampler/RayIntervals.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace savr
{

/// What Sampler::SampleRaySecond gives where a sample has no second code (a component is NaN).
constexpr std::uint16_t kNoSecondCode = 0xFFFF;

/// Read-only view of a scalar field. Implementations must be safe to call from many threads at
/// once: they keep no mutable state (per-thread scratch belongs to the caller).
class Sampler
  : public RayIntervals
  , public PathCache
{
public:
  virtual ~Sampler() = default;

  /// Smallest and largest finite value of the field.
  virtual std::array<double, 2> ValueRange() const = 0;

  /// Bits of the data's integer type (8, 16, 32 or 64), or 0 when the data is continuous (float,
  /// double). Integral data whose range spans fewer than 2^16 values is stored exactly.
  virtual int ExactBits() const = 0;

  /// Whether SampleRay can return NaN inside the region (NaN or Inf in the data, holes).
  virtual bool MayReturnNaN() const = 0;

  /// out[i] = field at ray.At(t0 + i * dt) for i in [0, count); NaN where the point lies outside
  /// the data, and, when `skip` is given, where it lies in a skipped block.
  virtual void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip = nullptr) const = 0;

  /// One ray's piece for SampleRays: `Count` samples of `*R` from `T0` into `Out`.
  struct RayPiece
  {
    const Ray* R;
    double T0;
    int Count;
    float* Out;
  };
  /// The most rays a sampler handles together in SampleRays (more are taken this many at a time).
  static constexpr int kMostPieces = 4;
  /// SampleRay for several rays at once (`n` pieces, the same step `dt` > 0, no skip mask): the
  /// same values as one call each. Samplers that walk their data take the walks' steps in turn,
  /// so that one runs while the others wait on memory.
  virtual void SampleRays(const RayPiece* pieces, int n, double dt) const
  {
    for (int i = 0; i < n; ++i)
    {
      this->SampleRay(*pieces[i].R, pieces[i].T0, dt, pieces[i].Count, pieces[i].Out);
    }
  }

  /// PathCache::SampleAlongPath: by default, samples the data.
  void SampleAlongPath(const Ray& ray, const PathPiece* path, std::size_t pieces, double traceStart,
    double t0, double dt, int count, float* out) const override
  {
    (void)path;
    (void)pieces;
    (void)traceStart;
    this->SampleRay(ray, t0, dt, count, out);
  }

  /// The field's gradient in world space at ray.At(t); zero where it has none (outside the
  /// data, or for samplers without gradients: the default).
  virtual void GradientAt(const Ray& ray, double t, float gradient[3]) const
  {
    (void)ray;
    (void)t;
    gradient[0] = gradient[1] = gradient[2] = 0.0f;
  }

  /// Computes whatever gradients rest on (per-voxel gradients, say) if not done yet. The frame
  /// loop calls it, serially, before a frame or pass that needs gradients, so that the work is
  /// done once per data change, in parallel, and only while gradients are in use; samplers also
  /// prepare on their own at the first gradient asked for. The default prepares nothing.
  virtual void PrepareGradients() const {}

  /// Bytes that what PrepareGradients computes takes (or will take once prepared), for the
  /// memory budget; 0 for samplers that keep nothing for gradients (the default).
  virtual std::size_t GradientBytes() const { return 0; }

  /// Asks the sampler to keep nothing for its gradients and compute each where it is asked
  /// for, the same bits, slower: what the frame loop falls back to when the kept ones do not
  /// fit the memory budget. Returns whether GradientBytes() went down (false: it cannot, the
  /// default). Called serially, outside frames.
  virtual bool ComputeGradientsOnDemand() const { return false; }

  /// As SampleRay, and also the gradient at each sample (3 floats per sample in `gradients`;
  /// zero where the sample is NaN). The default samples, then asks GradientsAlongRay.
  virtual void SampleRayGradients(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const
  {
    this->SampleRay(ray, t0, dt, count, out);
    this->GradientsAlongRay(ray, t0, dt, 0, count - 1, out, gradients);
  }

  /// As SampleRayGradients, with each sample's gradient given as its normal's code (what
  /// EncodeNormal gives for it: kNoNormal where the value is NaN) in `normals`, for samplers that
  /// encode them faster than a separate pass over the gradients would. Returns false, having
  /// sampled nothing, where the sampler does not (the default).
  virtual bool SampleRayNormals(
    const Ray& ray, double t0, double dt, int count, float* out, std::uint16_t* normals) const
  {
    (void)ray;
    (void)t0;
    (void)dt;
    (void)count;
    (void)out;
    (void)normals;
    return false;
  }

  /// The gradients of samples [first, last] of SampleRay's samples at t0 + i dt, given the
  /// values it gave for them (`values`, indexed from sample 0): 3 floats per sample into
  /// `gradients` (also indexed from sample 0), zero where the value is NaN; the other samples'
  /// are not written. A pass that needs gradients at some samples only (those it sees) asks
  /// for them here, a run at a time. The default asks GradientAt for each sample.
  virtual void GradientsAlongRay(const Ray& ray, double t0, double dt, int first, int last,
    const float* values, float* gradients) const
  {
    for (int i = first; i <= last; ++i)
    {
      if (values[i] == values[i])
      {
        this->GradientAt(ray, t0 + i * dt, gradients + 3 * static_cast<std::size_t>(i));
      }
      else
      {
        std::fill(gradients + 3 * static_cast<std::size_t>(i),
          gradients + 3 * static_cast<std::size_t>(i) + 3, 0.0f);
      }
    }
  }

  /// Data of several components (ComponentSampler): each component's own gradient at samples
  /// [first, last], as GradientsAlongRay gives the field's: component c's of sample i at
  /// gradients[3 * (4 * i + c)], zero where the value is NaN or the component is absent (12
  /// floats per sample, indexed from sample 0). The default, for data of one component, gives
  /// zeros.
  virtual void ComponentGradientsAlongRay(const Ray& ray, double t0, double dt, int first, int last,
    const float* values, float* gradients) const
  {
    (void)ray;
    (void)t0;
    (void)dt;
    (void)values;
    if (first <= last)
    {
      std::fill(gradients + 12 * static_cast<std::size_t>(first),
        gradients + 12 * (static_cast<std::size_t>(last) + 1), 0.0f);
    }
  }

  /// Whether every sample also has a second 16-bit code that the blends read beside its value
  /// (data with three or four components keeps the third and fourth there, see
  /// ComponentSampler). False for single-valued data.
  virtual bool HasSecondCode() const { return false; }

  /// second[i] = the second code at ray.At(t0 + i * dt) for i in [0, count), kNoSecondCode
  /// where there is none. Samples whose value is NaN may have any second code.
  virtual void SampleRaySecond(
    const Ray& ray, double t0, double dt, int count, std::uint16_t* second) const
  {
    (void)ray;
    (void)t0;
    (void)dt;
    std::fill(second, second + count, kNoSecondCode);
  }
};

} // namespace savr

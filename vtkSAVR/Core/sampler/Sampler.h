#pragma once
// The sampler interface: the only thing the SAVR engine knows about the data.

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

/// A ray in world coordinates; `Direction` has unit length so ray parameters are world distances.
struct Ray
{
  Eigen::Vector3d Origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d Direction = Eigen::Vector3d::UnitZ();

  Eigen::Vector3d At(double t) const { return Origin + t * Direction; }
};

/// Parameter interval [tEnter, tExit] of the line o + t d inside the box [lo, hi] (slabs); false
/// when the line misses it or o or d is not finite.
inline bool ClipToBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
  const Eigen::Vector3d& hi, double& tEnter, double& tExit)
{
  if (!o.allFinite() || !d.allFinite())
  {
    return false;
  }
  tEnter = -std::numeric_limits<double>::infinity();
  tExit = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < lo[a] || o[a] > hi[a])
      {
        return false;
      }
      continue;
    }
    const double inverse = 1.0 / d[a]; // one division, not two: this runs for every pixel
    double t0 = (lo[a] - o[a]) * inverse;
    double t1 = (hi[a] - o[a]) * inverse;
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    tEnter = std::max(tEnter, t0);
    tExit = std::min(tExit, t1);
  }
  return tEnter < tExit;
}

/// Blocks of the data that a pass may skip: SampleRay writes NaN for samples in blocks whose
/// flag is set, without reading the data. Indexed like Sampler::BlockRanges. A flag above 1
/// (from Sampler::SkipDistances) also promises that every block fewer rings away than it is
/// skipped too.
struct SkipMask
{
  const std::vector<std::uint8_t>* Skip = nullptr;
};

/// What Sampler::SampleRaySecond gives where a sample has no second code (a component is NaN).
constexpr std::uint16_t kNoSecondCode = 0xFFFF;

/// One piece of what a ray crosses, as Sampler::TracePath records it for later samples of the
/// same ray: the piece ends `End` past the trace's start (world units), and holds the samples
/// after the previous piece's end up to its own. What `Value` and `Slope` hold is the sampler's.
struct PathPiece
{
  float End;
  float Value;
  float Slope;
};

/// Read-only view of a scalar field. Implementations must be safe to call from many threads at
/// once: they keep no mutable state (per-thread scratch belongs to the caller).
class Sampler
{
public:
  virtual ~Sampler() = default;

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

  /// Whether TracePath can record rays: samplers that find what a ray crosses by walking the
  /// data (unstructured meshes) let every later frame on the same ray skip the walk. False by
  /// default.
  virtual bool TracesPaths() const { return false; }

  /// Appends to `path` the pieces of what [t0, t1] of the ray crosses, so that SampleAlongPath
  /// gives samples in [t0, t1] without walking the data again. When `spacing` > 0, every sample
  /// that will be asked for lies at t0 + n spacing (n whole), and pieces that hold none may be
  /// left out. False, with `path` as it was, when more than `maxPieces` pieces would be needed
  /// or the sampler cannot trace.
  virtual bool TracePath(const Ray& ray, double t0, double t1, double spacing,
    std::size_t maxPieces, std::vector<PathPiece>& path) const
  {
    (void)ray;
    (void)t0;
    (void)t1;
    (void)spacing;
    (void)maxPieces;
    (void)path;
    return false;
  }

  /// As SampleRay, for samples at increasing parameters in [traceStart, t1] of TracePath's
  /// call (on its lattice, when it had one), from the `pieces` pieces that TracePath recorded
  /// for this ray from `traceStart`. The values equal SampleRay's up to rounding (a piece may
  /// give, say, a field linear along the ray in floats). The default samples the data.
  virtual void SampleAlongPath(const Ray& ray, const PathPiece* path, std::size_t pieces,
    double traceStart, double t0, double dt, int count, float* out) const
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

  /// Smallest and largest finite value that sampling can return inside each block of the data
  /// (2 floats per block), or empty when the sampler has no blocks.
  virtual const std::vector<float>& BlockRanges() const
  {
    static const std::vector<float> none;
    return none;
  }
};

} // namespace savr

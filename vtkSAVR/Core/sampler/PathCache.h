#pragma once
// The part of the sampler interface that records what a ray crosses, for samplers that find it
// by walking the data (unstructured meshes): the first frame traces each ray's path, later
// frames sample along it without walking again. Sampler implements it (by default, nothing is
// traced and SampleAlongPath samples the data).

#include "sampler/Ray.h"

#include <cstddef>
#include <vector>

namespace savr
{

/// One piece of what a ray crosses, as Sampler::TracePath records it for later samples of the
/// same ray: the piece ends `End` past the trace's start (world units), and holds the samples
/// after the previous piece's end up to its own. What `Value` and `Slope` hold is the sampler's.
struct PathPiece
{
  float End;
  float Value;
  float Slope;
};

/// Rays' paths recorded for later frames (see above).
class PathCache
{
public:
  virtual ~PathCache() = default;

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
  /// give, say, a field linear along the ray in floats).
  virtual void SampleAlongPath(const Ray& ray, const PathPiece* path, std::size_t pieces,
    double traceStart, double t0, double dt, int count, float* out) const = 0;
};

} // namespace savr

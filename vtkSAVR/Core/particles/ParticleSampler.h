#pragma once
// A sampler over particles: a field made of one kernel per point, either normalized (Shepard:
// the kernel-weighted mean of the values of the particles that reach a point) or summed (a
// density: the values times their kernels, added). A bounding-volume hierarchy over the
// particles' support spheres finds, once per piece of ray, the particles that reach it; each
// sample adds only those, and samples no particle reaches are NaN without any work.

#include "particles/ParticleKernels.h"
#include "sampler/Sampler.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace savr
{

/// Describes particles held by someone else; the sampler copies what it needs.
struct ParticleDescription
{
  const double* Points = nullptr; // 3 per point, world coordinates
  const double* Values = nullptr; // 1 per point
  std::size_t NumberOfPoints = 0;
  /// The kernels' h for every particle, unless `Radii` (1 per point) gives each its own.
  double Radius = 1.0;
  const double* Radii = nullptr;
  /// A weight w per point (a volume, such as mass / density as VTK's SPH kernels take), or 1
  /// for every point when null.
  const double* Weights = nullptr;
  ParticleKernel Kernel = ParticleKernel::Gaussian;
  /// The weighted mean of the values (Shepard): sum of w v W over sum of w W, when set; their
  /// weighted sum, sum of w v W (a density when v w is a mass), when not.
  bool Normalized = true;
};

class ParticleSampler final : public Sampler
{
public:
  /// What is kept of a particle: its weight w and w v. Particles at exactly the same place with
  /// the same radius are one, whose `ValueSum` and `Weight` add theirs, which leaves both fields
  /// exactly as they were (sum of w v W is ValueSum W; sum of w W is Weight W).
  struct Particle
  {
    double Position[3];
    double H;
    double ValueSum;
    double Weight;
  };
  /// A node of the hierarchy: the box (rounded outwards to float) of its particles' supports.
  struct Node
  {
    float Lo[3];
    float Hi[3];
  };

  /// Builds the index over `particles`, kept in their order, which should be spatially coherent
  /// (MakeParticleSampler sorts them by Morton code and merges coincident ones); `valueRange`
  /// is the values' extremes, the range of a normalized field.
  ParticleSampler(std::vector<Particle> particles, ParticleKernel kernel, bool normalized,
    std::array<double, 2> valueRange, std::size_t skipped);

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override;
  bool HullCorners(std::array<Eigen::Vector3d, 8>& corners) const override;
  std::array<double, 2> ValueRange() const override { return this->Range; }
  int ExactBits() const override { return 0; }
  // Wherever no particle reaches.
  bool MayReturnNaN() const override { return true; }
  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip = nullptr) const override;
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override;
  void SampleRayGradients(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const override;

  /// As SampleRay, and returns the number of kernel evaluations (particle and sample pairs
  /// looked at) it took: what tests of empty-space skipping count.
  std::uint64_t SampleRayCounted(const Ray& ray, double t0, double dt, int count, float* out) const;

  /// Particles kept, after coincident ones are merged.
  std::size_t ParticleCount() const { return this->Particles.size(); }
  /// Particles of the description left out (a non-finite position or value).
  std::size_t SkippedParticles() const { return this->Skipped; }
  /// Bytes the particles and their index take, for a memory budget.
  std::size_t IndexBytes() const
  {
    return this->Particles.capacity() * sizeof(Particle) + this->Nodes.capacity() * sizeof(Node);
  }
  ParticleKernel Kernel() const { return this->KernelType; }
  bool Normalized() const { return this->NormalizedField; }

private:
  // Samples [first, first + count) of the ray's lattice t0 + i dt (dt > 0) into out (and the
  // gradients, when given); returns the kernel evaluations.
  std::uint64_t SampleChunk(
    const Ray& ray, double t0, double dt, int first, int count, float* out, float* gradients) const;
  std::uint64_t Sample(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const;
  template <ParticleKernel K, bool Gradients>
  std::uint64_t Accumulate(const Ray& ray, double t0, double dt, int first, int count, double* sums,
    std::uint8_t* reached) const;
  // Calls visit(particle) for each particle of the leaves that meets(node) lets the traversal
  // reach, in the particles' order (children are visited left first).
  template <typename Meets, typename Visit>
  void ForEachParticle(const Meets& meets, const Visit& visit) const;
  void BuildHierarchy();
  std::array<double, 2> SummedRange() const;

  std::vector<Particle> Particles;
  // A complete binary tree in heap order (children of k at 2k + 1 and 2k + 2) over LeafCount
  // leaves (a power of two) of kLeafSize consecutive particles each; leaves past the particles
  // have empty boxes. Visiting children left first meets the particles in their order, which is
  // the order every sample adds them in.
  std::vector<Node> Nodes;
  std::size_t LeafCount = 0;
  ParticleKernel KernelType;
  bool NormalizedField;
  std::array<double, 2> Range;
  std::size_t Skipped;
  double BoxLo[3] = { 0, 0, 0 }; // of every support sphere
  double BoxHi[3] = { 0, 0, 0 };
  double Scale = 1.0; // size of the box and distance from the origin, for round-off margins
};

/// Builds a sampler for the particles, or returns nullptr and explains why in `error`.
/// Particles with a non-finite position or value, or a weight that is not finite and positive,
/// are skipped (counted in `skippedParticles` when given, and refused when none remain); a
/// radius that is not finite and positive is refused, naming the first. Exactly coincident
/// particles of the same radius are merged.
std::shared_ptr<const ParticleSampler> MakeParticleSampler(const ParticleDescription& particles,
  std::string& error, std::size_t* skippedParticles = nullptr);

} // namespace savr

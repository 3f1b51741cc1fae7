// The particle sampler: the order and merging of the particles, the hierarchy over their
// supports, the bound on a summed field, and the ray sampling that visits the particles reaching
// a piece of ray once and adds each to the samples it reaches (the kernels: ParticleKernels.h).
#include "particles/ParticleSampler.h"

#include "particles/ParticleKernels.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <string>
#include <tuple>

namespace savr
{
namespace
{

using namespace particles;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Particles per leaf of the hierarchy.
constexpr std::size_t kLeafSize = 8;
// Samples handled at a time: their sums live on the stack, so no scratch outlives a call.
constexpr int kChunk = 256;
// Supports are grown by this fraction in the index, so that round-off in the ray's geometry
// never hides a particle from a sample its exact distance test keeps.
constexpr double kSupportMargin = 1e-9;
// Cells per axis, at most, of the grid that bounds the summed field (see SummedRange).
constexpr int kRangeCells = 64;
// Cells a particle meets in that grid, on average, at most.
constexpr double kRangePairsPerParticle = 256.0;

float FloatBelow(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x)
  {
    f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  }
  return f;
}

float FloatAbove(double x)
{
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x)
  {
    f = std::nextafter(f, std::numeric_limits<float>::infinity());
  }
  return f;
}

// The particle's support grown by kSupportMargin.
double SupportRadius(ParticleKernel kernel, double h)
{
  return CutoffFactor(kernel) * h * (1.0 + kSupportMargin);
}

// A ray's segment [Lo, Hi] against boxes (slabs).
struct SegmentTest
{
  SegmentTest(const Ray& ray, double lo, double hi)
    : Lo(lo)
    , Hi(hi)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->O[a] = ray.Origin[a];
      this->Parallel[a] = ray.Direction[a] == 0.0;
      this->Inverse[a] = this->Parallel[a] ? 0.0 : 1.0 / ray.Direction[a];
    }
  }
  bool Hits(const ParticleSampler::Node& node) const
  {
    if (!(node.Lo[0] <= node.Hi[0]))
    {
      return false; // empty: the slabs of infinite bounds would not say so
    }
    double lo = this->Lo;
    double hi = this->Hi;
    for (int a = 0; a < 3; ++a)
    {
      if (this->Parallel[a])
      {
        if (!(this->O[a] >= node.Lo[a] && this->O[a] <= node.Hi[a]))
        {
          return false;
        }
        continue;
      }
      const double ta = (node.Lo[a] - this->O[a]) * this->Inverse[a];
      const double tb = (node.Hi[a] - this->O[a]) * this->Inverse[a];
      lo = std::max(lo, std::min(ta, tb));
      hi = std::min(hi, std::max(ta, tb));
    }
    return lo <= hi; // false for empty boxes (Lo above Hi), and for NaN
  }
  double O[3];
  double Inverse[3];
  bool Parallel[3];
  double Lo;
  double Hi;
};

bool BoxesOverlap(const ParticleSampler::Node& a, const ParticleSampler::Node& b)
{
  for (int k = 0; k < 3; ++k)
  {
    if (a.Hi[k] < b.Lo[k] || b.Hi[k] < a.Lo[k])
    {
      return false;
    }
  }
  return true;
}

ParticleSampler::Node EmptyNode()
{
  const float inf = std::numeric_limits<float>::infinity();
  return ParticleSampler::Node{ { inf, inf, inf }, { -inf, -inf, -inf } };
}

void Extend(ParticleSampler::Node& node, const ParticleSampler::Node& other)
{
  for (int a = 0; a < 3; ++a)
  {
    node.Lo[a] = std::min(node.Lo[a], other.Lo[a]);
    node.Hi[a] = std::max(node.Hi[a], other.Hi[a]);
  }
}

ParticleSampler::Node SupportBox(const ParticleSampler::Particle& p, ParticleKernel kernel)
{
  const double r = SupportRadius(kernel, p.H);
  ParticleSampler::Node node;
  for (int a = 0; a < 3; ++a)
  {
    node.Lo[a] = FloatBelow(p.Position[a] - r);
    node.Hi[a] = FloatAbove(p.Position[a] + r);
  }
  return node;
}

// Spreads the low 21 bits of x to every third bit.
std::uint64_t Spread(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

} // namespace

ParticleSampler::ParticleSampler(std::vector<Particle> particles, ParticleKernel kernel,
  bool normalized, std::array<double, 2> valueRange, std::size_t skipped)
  : Particles(std::move(particles))
  , KernelType(kernel)
  , NormalizedField(normalized)
  , Range(valueRange)
  , Skipped(skipped)
{
  this->BuildHierarchy();
  if (!normalized)
  {
    this->Range = this->SummedRange();
  }
}

void ParticleSampler::BuildHierarchy()
{
  const std::size_t n = this->Particles.size();
  const std::size_t leaves = (n + kLeafSize - 1) / kLeafSize;
  this->LeafCount = 1;
  while (this->LeafCount < leaves)
  {
    this->LeafCount *= 2;
  }
  this->Nodes.assign(2 * this->LeafCount - 1, EmptyNode());
  const std::size_t firstLeaf = this->LeafCount - 1;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves, 256),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t leaf = range.begin(); leaf != range.end(); ++leaf)
      {
        Node& node = this->Nodes[firstLeaf + leaf];
        for (std::size_t j = leaf * kLeafSize; j < std::min(n, (leaf + 1) * kLeafSize); ++j)
        {
          Extend(node, SupportBox(this->Particles[j], this->KernelType));
        }
      }
    });
  // Level by level upwards: the nodes of a level are [width - 1, 2 width - 1).
  for (std::size_t width = this->LeafCount / 2; width >= 1; width /= 2)
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(width - 1, 2 * width - 1, 1024),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t k = range.begin(); k != range.end(); ++k)
        {
          Node node = this->Nodes[2 * k + 1];
          Extend(node, this->Nodes[2 * k + 2]);
          this->Nodes[k] = node;
        }
      });
  }
  double extent = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    this->BoxLo[a] = this->Nodes[0].Lo[a];
    this->BoxHi[a] = this->Nodes[0].Hi[a];
    extent = std::max({ extent, this->BoxHi[a] - this->BoxLo[a], std::abs(this->BoxLo[a]),
      std::abs(this->BoxHi[a]) });
  }
  this->Scale = std::isfinite(extent) ? extent : std::numeric_limits<double>::max();
}

template <typename Meets, typename Visit>
void ParticleSampler::ForEachParticle(const Meets& meets, const Visit& visit) const
{
  const std::size_t firstLeaf = this->LeafCount - 1;
  const std::size_t n = this->Particles.size();
  std::size_t stack[64]; // the tree's depth is below 64
  int top = 0;
  stack[top++] = 0;
  while (top > 0)
  {
    const std::size_t k = stack[--top];
    if (!meets(this->Nodes[k]))
    {
      continue;
    }
    if (k < firstLeaf)
    {
      stack[top++] = 2 * k + 2;
      stack[top++] = 2 * k + 1;
      continue;
    }
    const std::size_t leaf = k - firstLeaf;
    for (std::size_t j = leaf * kLeafSize; j < std::min(n, (leaf + 1) * kLeafSize); ++j)
    {
      visit(this->Particles[j]);
    }
  }
}

// A grid of cells over the supports' box: in a cell, each particle whose support meets it adds
// at most |ValueSum| W(the particle's distance to the cell) (the kernels fall with distance), so
// the sums of those bounds, positive and negative parts apart, bound the field in the cell, and
// their extremes over the cells bound it everywhere. Cells are half the median support radius
// wide, or wider to keep within kRangeCells per axis and kRangePairsPerParticle. How loose: on
// 20000 uniform particles (h 0.2 to 0.5 in a box of 10, values in [-0.3, 0.7]) the upper bound was
// 2 to 3.3 times the largest sample of 8 million, the lower one 2.6 to 21 times the smallest (the
// negative part alone, without the positive values that offset it); it grows with the cells' width
// against h, and so with clouds whose extent is large against their particles' supports.
std::array<double, 2> ParticleSampler::SummedRange() const
{
  const std::size_t n = this->Particles.size();
  std::vector<double> supports(n);
  for (std::size_t j = 0; j < n; ++j)
  {
    supports[j] = CutoffFactor(this->KernelType) * this->Particles[j].H;
  }
  std::nth_element(supports.begin(), supports.begin() + n / 2, supports.end());
  double cell = 0.5 * supports[n / 2];
  for (int a = 0; a < 3; ++a)
  {
    cell = std::max(cell, (this->BoxHi[a] - this->BoxLo[a]) / kRangeCells);
  }
  // A particle meets (2 R / cell + 1)^3 cells on average: cells grow until that stays within
  // kRangePairsPerParticle on average, so that supports much larger than most cannot make the
  // bound cost more than sampling a few hundred samples per particle.
  double extent = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    extent = std::max(extent, this->BoxHi[a] - this->BoxLo[a]);
  }
  auto pairs = [&](double width)
  {
    double sum = 0.0;
    for (double support : supports)
    {
      const double across = 2.0 * support / width + 1.0;
      sum += across * across * across;
    }
    return sum;
  };
  while (cell < extent && pairs(cell) > kRangePairsPerParticle * static_cast<double>(n))
  {
    cell *= 2.0;
  }
  if (!std::isfinite(cell) || !(cell > 0.0))
  {
    return { -kInfinity, kInfinity }; // a box beyond double's range: nothing better to say
  }
  int dims[3];
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = std::max(1, static_cast<int>(std::ceil((this->BoxHi[a] - this->BoxLo[a]) / cell)));
  }
  std::vector<double> high(static_cast<std::size_t>(dims[1]) * dims[2], 0.0);
  std::vector<double> low(high.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, high.size()),
    [&](const tbb::blocked_range<std::size_t>& rows)
    {
      for (std::size_t row = rows.begin(); row != rows.end(); ++row)
      {
        for (int i = 0; i < dims[0]; ++i)
        {
          const int index[3] = { i, static_cast<int>(row % dims[1]),
            static_cast<int>(row / dims[1]) };
          double lo[3];
          double hi[3];
          Node box;
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = this->BoxLo[a] + index[a] * cell;
            hi[a] = this->BoxLo[a] + (index[a] + 1) * cell; // shared exactly with the next cell
            box.Lo[a] = FloatBelow(lo[a]);
            box.Hi[a] = FloatAbove(hi[a]);
          }
          double positive = 0.0;
          double negative = 0.0;
          this->ForEachParticle([&](const Node& node) { return BoxesOverlap(node, box); },
            [&](const Particle& p)
            {
              double distance2 = 0.0;
              for (int a = 0; a < 3; ++a)
              {
                const double gap = std::max({ lo[a] - p.Position[a], p.Position[a] - hi[a], 0.0 });
                distance2 += gap * gap;
              }
              const double support = CutoffFactor(this->KernelType) * p.H;
              if (distance2 < support * support)
              {
                const double w = KernelValue(this->KernelType, p.H, distance2);
                positive += std::max(p.ValueSum, 0.0) * w;
                negative += std::min(p.ValueSum, 0.0) * w;
              }
            });
          high[row] = std::max(high[row], positive);
          low[row] = std::min(low[row], negative);
        }
      }
    });
  const double top = *std::max_element(high.begin(), high.end());
  const double bottom = *std::min_element(low.begin(), low.end());
  // The samples' own sums round too: a relative margin far above theirs.
  return { bottom * (1.0 + 1e-9), top * (1.0 + 1e-9) };
}

bool ParticleSampler::Clip(const Ray& ray, double& tEnter, double& tExit) const
{
  return ClipToBox(ray.Origin, ray.Direction, Eigen::Map<const Eigen::Vector3d>(this->BoxLo),
    Eigen::Map<const Eigen::Vector3d>(this->BoxHi), tEnter, tExit);
}

bool ParticleSampler::HullCorners(std::array<Eigen::Vector3d, 8>& corners) const
{
  for (int c = 0; c < 8; ++c)
  {
    for (int a = 0; a < 3; ++a)
    {
      corners[c][a] = (c >> a) & 1 ? this->BoxHi[a] : this->BoxLo[a];
    }
  }
  return true;
}

void ParticleSampler::SampleRay(
  const Ray& ray, double t0, double dt, int count, float* out, const SkipMask* skip) const
{
  (void)skip; // no blocks
  this->Sample(ray, t0, dt, count, out, nullptr);
}

std::uint64_t ParticleSampler::SampleRayCounted(
  const Ray& ray, double t0, double dt, int count, float* out) const
{
  return this->Sample(ray, t0, dt, count, out, nullptr);
}

void ParticleSampler::SampleRayGradients(
  const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const
{
  this->Sample(ray, t0, dt, count, out, gradients);
}

void ParticleSampler::GradientAt(const Ray& ray, double t, float gradient[3]) const
{
  float value;
  this->Sample(ray, t, 1.0, 1, &value, gradient);
}

std::uint64_t ParticleSampler::Sample(
  const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const
{
  if (count <= 0)
  {
    return 0;
  }
  std::fill(out, out + count, std::numeric_limits<float>::quiet_NaN());
  if (gradients)
  {
    std::fill(gradients, gradients + 3 * static_cast<std::size_t>(count), 0.0f);
  }
  if (!std::isfinite(t0) || !std::isfinite(dt) || !ray.Origin.allFinite() ||
      !ray.Direction.allFinite())
  {
    return 0;
  }
  if (dt < 0.0)
  {
    // The same points on the reversed ray, at increasing parameters (negation is exact).
    const Ray reversed{ ray.Origin, -ray.Direction };
    return this->Sample(reversed, -t0, -dt, count, out, gradients);
  }
  if (dt == 0.0)
  {
    const std::uint64_t work = this->SampleChunk(ray, t0, 1.0, 0, 1, out, gradients);
    std::fill(out + 1, out + count, out[0]);
    for (int i = 1; gradients && i < count; ++i)
    {
      std::copy(gradients, gradients + 3, gradients + 3 * static_cast<std::size_t>(i));
    }
    return work;
  }
  std::uint64_t work = 0;
  for (int first = 0; first < count; first += kChunk)
  {
    work += this->SampleChunk(ray, t0, dt, first, std::min(kChunk, count - first), out, gradients);
  }
  return work;
}

std::uint64_t ParticleSampler::SampleChunk(
  const Ray& ray, double t0, double dt, int first, int count, float* out, float* gradients) const
{
  const int stride = gradients ? 8 : 2;
  double sums[8 * kChunk];
  std::uint8_t reached[kChunk];
  std::fill(sums, sums + stride * count, 0.0);
  std::fill(reached, reached + count, std::uint8_t(0));
  std::uint64_t work = 0;
  switch (this->KernelType)
  {
    case ParticleKernel::SPHCubic:
      work = gradients ? this->Accumulate<ParticleKernel::SPHCubic, true>(
                           ray, t0, dt, first, count, sums, reached)
                       : this->Accumulate<ParticleKernel::SPHCubic, false>(
                           ray, t0, dt, first, count, sums, reached);
      break;
    case ParticleKernel::SPHQuintic:
      work = gradients ? this->Accumulate<ParticleKernel::SPHQuintic, true>(
                           ray, t0, dt, first, count, sums, reached)
                       : this->Accumulate<ParticleKernel::SPHQuintic, false>(
                           ray, t0, dt, first, count, sums, reached);
      break;
    default:
      work = gradients ? this->Accumulate<ParticleKernel::Gaussian, true>(
                           ray, t0, dt, first, count, sums, reached)
                       : this->Accumulate<ParticleKernel::Gaussian, false>(
                           ray, t0, dt, first, count, sums, reached);
      break;
  }
  for (int i = 0; i < count; ++i)
  {
    if (!reached[i])
    {
      continue; // NaN, zero gradient: set by Sample
    }
    const double* s = sums + stride * i;
    const double value = this->NormalizedField ? (s[1] > 0.0 ? s[0] / s[1] : kNaN) : s[0];
    out[first + i] = static_cast<float>(value);
    if (gradients && value == value)
    {
      float* g = gradients + 3 * static_cast<std::size_t>(first + i);
      for (int a = 0; a < 3; ++a)
      {
        // Normalized: the quotient rule on (sum s W) / (sum m W).
        const double ga = this->NormalizedField ? (s[2 + a] - value * s[5 + a]) / s[1] : s[2 + a];
        g[a] = std::isfinite(ga) ? static_cast<float>(ga) : 0.0f;
      }
    }
  }
  return work;
}

// Visits the leaves that meet the chunk's segment left first, so that each sample adds its
// particles in their stored order whatever the chunk; a particle adds to the samples of its
// chord only, each kept by its own distance test, so that the piece of ray a call covers changes
// nothing but round-off in the samples' parameters.
template <ParticleKernel K, bool Gradients>
std::uint64_t ParticleSampler::Accumulate(const Ray& ray, double t0, double dt, int first,
  int count, double* sums, std::uint8_t* reached) const
{
  constexpr int stride = Gradients ? 8 : 2;
  const double tFirst = t0 + first * dt;
  const double tLast = t0 + (first + count - 1) * dt;
  const double pad = 1e-9 * (this->Scale + std::abs(tFirst) + std::abs(tLast));
  const SegmentTest segment(ray, tFirst - pad, tLast + pad);
  const Eigen::Vector3d& o = ray.Origin;
  const Eigen::Vector3d& d = ray.Direction;
  const double cutoff = CutoffFactor(K);
  std::uint64_t work = 0;
  this->ForEachParticle([&](const Node& node) { return segment.Hits(node); },
    [&](const Particle& p)
    {
      const Eigen::Vector3d q = Eigen::Vector3d(p.Position[0], p.Position[1], p.Position[2]) - o;
      const double b = q.dot(d);
      const Eigen::Vector3d across = q - b * d; // from the ray's closest point to the particle
      const double across2 = across.squaredNorm();
      const double support = cutoff * p.H;
      const double support2 = support * support;
      if (!(across2 < support2))
      {
        return;
      }
      // The chord's samples, one more each side: each sample's own test below decides.
      const double halfChord = std::sqrt(support2 - across2);
      const double lo = std::ceil((b - halfChord - t0) / dt) - 1.0;
      const double hi = std::floor((b + halfChord - t0) / dt) + 2.0;
      if (!(lo < first + count) || !(hi > first))
      {
        return; // also when round-off overflowed to NaN
      }
      const int begin = lo > first ? static_cast<int>(lo) : first;
      const int end = hi < first + count ? static_cast<int>(hi) : first + count;
      const KernelOf<K> kernel(p.H);
      work += static_cast<std::uint64_t>(end - begin);
      for (int i = begin; i < end; ++i)
      {
        const double s = t0 + i * dt - b;
        const double r2 = across2 + s * s;
        if (!(r2 < support2))
        {
          continue;
        }
        const double w = kernel.Value(r2);
        double* sum = sums + stride * (i - first);
        reached[i - first] = 1;
        sum[0] += p.ValueSum * w;
        sum[1] += p.Weight * w;
        if (Gradients)
        {
          // grad W = W'(r) / r (x - p), and x - p = s d - across.
          const double g = kernel.Derivative(r2, w);
          for (int a = 0; a < 3; ++a)
          {
            const double direction = s * d[a] - across[a];
            sum[2 + a] += p.ValueSum * g * direction;
            sum[5 + a] += p.Weight * g * direction;
          }
        }
      }
    });
  return work;
}

namespace
{

double RadiusOf(const ParticleDescription& particles, std::size_t i)
{
  return particles.Radii ? particles.Radii[i] : particles.Radius;
}

double WeightOf(const ParticleDescription& particles, std::size_t i)
{
  return particles.Weights ? particles.Weights[i] : 1.0;
}

// The particles `kept` (indices into the description) in Morton order of their centres (within
// the box [lo, hi] of the centres), ties broken by position, radius and index: a total order, so
// that the result does not depend on the sort's threads, and exactly coincident particles of the
// same radius end up side by side, in the order of their indices, and are merged.
std::vector<ParticleSampler::Particle> OrderAndMerge(const ParticleDescription& particles,
  const std::vector<std::uint32_t>& kept, const double lo[3], const double hi[3])
{
  struct Key
  {
    std::uint64_t Code;
    std::uint32_t Index;
  };
  std::vector<Key> keys(kept.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kept.size(), 4096),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t k = range.begin(); k != range.end(); ++k)
      {
        const double* x = particles.Points + 3 * static_cast<std::size_t>(kept[k]);
        std::uint64_t code = 0;
        for (int a = 0; a < 3; ++a)
        {
          const double extent = hi[a] - lo[a];
          const double unit = extent > 0.0 && std::isfinite(extent) ? (x[a] - lo[a]) / extent : 0.0;
          code |= Spread(static_cast<std::uint64_t>(unit * 2097151.0)) << a;
        }
        keys[k] = Key{ code, kept[k] };
      }
    });
  auto tie = [&](std::uint32_t i)
  {
    const double* x = particles.Points + 3 * static_cast<std::size_t>(i);
    return std::make_tuple(x[0], x[1], x[2], RadiusOf(particles, i));
  };
  tbb::parallel_sort(keys.begin(), keys.end(),
    [&](const Key& a, const Key& b)
    {
      if (a.Code != b.Code)
      {
        return a.Code < b.Code;
      }
      const auto ta = tie(a.Index);
      const auto tb = tie(b.Index);
      return ta < tb || (!(tb < ta) && a.Index < b.Index);
    });
  std::vector<ParticleSampler::Particle> merged;
  merged.reserve(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k)
  {
    const std::uint32_t i = keys[k].Index;
    const double* x = particles.Points + 3 * static_cast<std::size_t>(i);
    if (!merged.empty() && k > 0 && tie(keys[k - 1].Index) == tie(i))
    {
      merged.back().ValueSum += WeightOf(particles, i) * particles.Values[i];
      merged.back().Weight += WeightOf(particles, i);
      continue;
    }
    merged.push_back(ParticleSampler::Particle{ { x[0], x[1], x[2] }, RadiusOf(particles, i),
      WeightOf(particles, i) * particles.Values[i], WeightOf(particles, i) });
  }
  merged.shrink_to_fit();
  return merged;
}

} // namespace

std::shared_ptr<const ParticleSampler> MakeParticleSampler(
  const ParticleDescription& particles, std::string& error, std::size_t* skippedParticles)
{
  if (skippedParticles)
  {
    *skippedParticles = 0;
  }
  const std::size_t n = particles.NumberOfPoints;
  if (!particles.Points || n == 0)
  {
    error = "there are no particles";
    return nullptr;
  }
  if (!particles.Values)
  {
    error = "the particles have no values";
    return nullptr;
  }
  const ParticleKernel kernel = particles.Kernel;
  if (kernel != ParticleKernel::Gaussian && kernel != ParticleKernel::SPHCubic &&
      kernel != ParticleKernel::SPHQuintic)
  {
    error = "unknown particle kernel";
    return nullptr;
  }
  for (std::size_t i = 0; i < (particles.Radii ? n : 1); ++i)
  {
    if (!UsableRadius(kernel, RadiusOf(particles, i)))
    {
      error =
        (particles.Radii ? "the radius of particle " + std::to_string(i)
                         : std::string("the particles' radius")) +
        " is " + std::to_string(RadiusOf(particles, i)) +
        ": radii must be finite and positive, and the kernel's cutoff and normalization finite";
      return nullptr;
    }
  }
  try
  {
    // Kept: a finite position and value, a finite positive weight, and a finite support.
    std::vector<std::uint32_t> kept;
    double lo[3] = { kInfinity, kInfinity, kInfinity };
    double hi[3] = { -kInfinity, -kInfinity, -kInfinity };
    double valueLo = kInfinity;
    double valueHi = -kInfinity;
    if (n >= 0xffffffffu)
    {
      error = "too many particles (at most 2^32 - 2)";
      return nullptr;
    }
    kept.reserve(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      const double* x = particles.Points + 3 * i;
      const double v = particles.Values[i];
      const double r = SupportRadius(kernel, RadiusOf(particles, i));
      const double weight = WeightOf(particles, i);
      bool finite =
        std::isfinite(v) && std::isfinite(weight) && weight > 0.0 && std::isfinite(weight * v);
      for (int a = 0; a < 3; ++a)
      {
        finite = finite && std::isfinite(x[a]) && std::isfinite(std::abs(x[a]) + r);
      }
      if (!finite)
      {
        continue;
      }
      kept.push_back(static_cast<std::uint32_t>(i));
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], x[a]);
        hi[a] = std::max(hi[a], x[a]);
      }
      valueLo = std::min(valueLo, v);
      valueHi = std::max(valueHi, v);
    }
    const std::size_t skipped = n - kept.size();
    if (skippedParticles)
    {
      *skippedParticles = skipped;
    }
    if (kept.empty())
    {
      error = "no particle has a finite position and value and a positive weight (" +
              std::to_string(skipped) + " skipped)";
      return nullptr;
    }
    std::vector<ParticleSampler::Particle> merged = OrderAndMerge(particles, kept, lo, hi);
    kept = std::vector<std::uint32_t>();
    return std::make_shared<ParticleSampler>(std::move(merged), kernel, particles.Normalized,
      std::array<double, 2>{ valueLo, valueHi }, skipped);
  }
  catch (const std::bad_alloc&)
  {
    error = "not enough memory for the particles and their index";
    return nullptr;
  }
}

} // namespace savr

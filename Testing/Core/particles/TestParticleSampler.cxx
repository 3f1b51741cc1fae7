// The particle sampler against closed forms: kernels written out again from their definitions
// (ParticleClouds.h), a single particle's samples and line integral, a linear field through
// Shepard's mean, gradients against differences, bad input, and results that do not depend on
// threads or on how a ray is cut.
#include "particles/ParticleClouds.h"
#include "TestHelpers.h"

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <random>
#include <string>

using namespace savr_test;

// Shepard's mean of a linear field v = a + b.x is a + b.c, c the weighted centroid of the
// particles that reach x, so the error is b.(c - x). The test checks the sampler against that
// sum done here by brute force (float round-off of the values: 1e-6 relative), and the field
// against two bounds: always |b| times the distance to the farthest particle that reaches
// (c is a convex combination), and at the root mean square |b| delta, delta the jitter's
// half-width: c - x is the weighted mean of the jitters (each at most delta sqrt(3) long,
// independent, so their mean over the ten or more neighbours that reach is a few times
// smaller) plus the lattice's own offset, which the symmetric kernels keep near zero.
TEST(ParticleSampler, LinearFieldInsideAJitteredLattice)
{
  const double a = 2.0;
  const Eigen::Vector3d b(0.5, -0.3, 0.2);
  const double jitter = 0.25;
  std::mt19937 random(19);
  std::uniform_real_distribution<double> uniform(-jitter, jitter);
  Cloud cloud;
  const int n = 13;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const Eigen::Vector3d p = Eigen::Vector3d(i, j, k) + Eigen::Vector3d(uniform(random),
                                                               uniform(random), uniform(random));
        cloud.Add(p, a + b.dot(p));
      }
  for (savr::ParticleKernel kernel : kKernels)
  {
    SCOPED_TRACE(Name(kernel));
    const double h = kernel == savr::ParticleKernel::SPHCubic ? 1.3 : 1.0;
    const double support = Cutoff(kernel) * h;
    auto sampler = cloud.Sampler(kernel, true, h);
    ASSERT_TRUE(sampler);
    // The interior: every point at least one support from the cloud's border.
    const Eigen::Vector3d lo = Eigen::Vector3d::Constant(support + jitter);
    const Eigen::Vector3d hi = Eigen::Vector3d::Constant(n - 1 - support - jitter);
    double sumSquares = 0.0;
    int checked = 0;
    std::uniform_real_distribution<double> inside(0.0, 1.0);
    for (int r = 0; r < 40; ++r)
    {
      const Eigen::Vector3d centre = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(
                                            inside(random), inside(random), inside(random)));
      const savr::Ray ray = RayThrough(centre, RandomDirection(random), 10.0);
      const int count = 200;
      const double dt = 0.1;
      std::vector<float> out(count);
      sampler->SampleRay(ray, 0.0, dt, count, out.data());
      for (int i = 0; i < count; ++i)
      {
        const Eigen::Vector3d x = ray.At(i * dt);
        if ((x.array() < lo.array()).any() || (x.array() > hi.array()).any())
        {
          continue;
        }
        double weights = 0.0;
        double weighted = 0.0;
        double farthest = 0.0;
        for (std::size_t j = 0; j < cloud.Values.size(); ++j)
        {
          const Eigen::Vector3d p(
            cloud.Points[3 * j], cloud.Points[3 * j + 1], cloud.Points[3 * j + 2]);
          const double w = Kernel(kernel, (x - p).norm(), h);
          if (w > 0.0)
          {
            weights += w;
            weighted += w * cloud.Values[j];
            farthest = std::max(farthest, (x - p).norm());
          }
        }
        ASSERT_GT(weights, 0.0);
        const double shepard = weighted / weights;
        const double exact = a + b.dot(x);
        EXPECT_NEAR(out[i], shepard, 1e-6 * std::abs(shepard));
        EXPECT_LE(std::abs(out[i] - exact), b.norm() * farthest + 1e-6 * std::abs(exact));
        sumSquares += (out[i] - exact) * (out[i] - exact);
        ++checked;
      }
    }
    ASSERT_GT(checked, 1000);
    EXPECT_LT(std::sqrt(sumSquares / checked), b.norm() * jitter);
    EXPECT_EQ(
      sampler->ValueRange()[0], *std::min_element(cloud.Values.begin(), cloud.Values.end()));
    EXPECT_EQ(
      sampler->ValueRange()[1], *std::max_element(cloud.Values.begin(), cloud.Values.end()));
  }
}

// One Gaussian particle: the samples are v exp(-r^2 / 2 h^2) inside 3 h and NaN beyond, in both
// modes (normalized, one particle is its own mean: v).
TEST(ParticleSampler, SingleGaussianSamples)
{
  const Eigen::Vector3d centre(0.3, -0.2, 0.1);
  const double v = 2.5;
  const double h = 0.7;
  Cloud cloud;
  cloud.Add(centre, v);
  auto summed = cloud.Sampler(savr::ParticleKernel::Gaussian, false, h);
  auto normalized = cloud.Sampler(savr::ParticleKernel::Gaussian, true, h);
  ASSERT_TRUE(summed && normalized);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> impact(0.0, 4.0 * h);
  int inside = 0;
  int outside = 0;
  for (int r = 0; r < 50; ++r)
  {
    const Eigen::Vector3d direction = RandomDirection(random);
    Eigen::Vector3d across = direction.cross(RandomDirection(random)).normalized();
    const savr::Ray ray = RayThrough(centre + impact(random) * across, direction, 5 * h);
    const int count = 301;
    const double dt = 10 * h / (count - 1);
    std::vector<float> s(count);
    std::vector<float> m(count);
    summed->SampleRay(ray, 0.0, dt, count, s.data());
    normalized->SampleRay(ray, 0.0, dt, count, m.data());
    for (int i = 0; i < count; ++i)
    {
      const double distance = (ray.At(i * dt) - centre).norm();
      if (std::abs(distance - 3 * h) < 1e-9)
      {
        continue; // on the cutoff: either
      }
      if (distance < 3 * h)
      {
        ++inside;
        // exp in double, one rounding to float: within a float's half unit.
        const double expected = v * std::exp(-distance * distance / (2 * h * h));
        EXPECT_NEAR(s[i], expected, 6e-8 * expected);
        EXPECT_NEAR(m[i], v, 6e-8 * v);
      }
      else
      {
        ++outside;
        EXPECT_TRUE(std::isnan(s[i]) && std::isnan(m[i]));
      }
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

// Beer-Lambert through the summed field of one Gaussian particle: with an extinction linear in
// the value (sigma = kappa v), a ray keeps exp(-kappa I) of its light, I the field's line
// integral: along a ray passing at distance d, truncated at 3 h (half chord L = sqrt(9 h^2 -
// d^2)), I = v exp(-d^2 / 2 h^2) sqrt(2 pi) h erf(L / (sqrt(2) h)). Sampled every s, I's error
// is at most the two steps that hold a jump at the cutoff (each at most s times the field
// within s of it, v exp(-(3 h - s)^2 / 2 h^2)) plus the midpoint rule's (2 L) s^2 / 24 max|f''|,
// and |f''| <= v / h^2 (the largest of |exp(-u^2 / 2) (u^2 - 1)| is 1, at u = 0), plus, when the
// samples are stored as codes, half a code per sample over the chord: 2 L code / 2. The pixel's
// alpha, 1 - exp(-kappa I), moves by at most kappa times I's error (and the image is float).
namespace
{
void ExpectBeerLambert(const std::vector<float>& image, const savr::View& view, double v, double h,
  double kappa, double step, double code)
{
  int lit = 0;
  for (int y = 0; y < view.Height; ++y)
  {
    for (int x = 0; x < view.Width; ++x)
    {
      double tMax;
      const savr::Ray ray = view.PixelRay(x, y, tMax);
      const double d = std::hypot(ray.Origin.y(), ray.Origin.z());
      const double alpha = image[4 * (y * view.Width + x) + 3];
      if (d >= 3 * h)
      {
        EXPECT_EQ(alpha, 0.0);
        continue;
      }
      const double half = std::sqrt(9 * h * h - d * d);
      const double integral = v * std::exp(-d * d / (2 * h * h)) * std::sqrt(2 * kPi) * h *
                              std::erf(half / (std::sqrt(2.0) * h));
      const double bound = 2 * v * std::exp(-std::pow(3 * h - step, 2) / (2 * h * h)) * step +
                           2 * half * step * step / 24 * v / (h * h) + 2 * half * code / 2;
      EXPECT_NEAR(alpha, -std::expm1(-kappa * integral), kappa * bound + 1e-6);
      ++lit;
    }
  }
  EXPECT_GT(lit, 100);
}

} // namespace

// The closed form above on the double-precision reference integrator (midpoint rule, no codes)
// and through the engine itself: eight frames of the frame loop (16-bit codes over the value
// range, the transfer function as a table), whose samples lie every dt / 8 along each ray.
TEST(ParticleSampler, SingleGaussianLineIntegral)
{
  const double v = 2.0;
  const double h = 0.5;
  const double kappa = 0.8;
  Cloud cloud;
  cloud.Add(Eigen::Vector3d::Zero(), v);
  auto sampler = cloud.Sampler(savr::ParticleKernel::Gaussian, false, h);
  ASSERT_TRUE(sampler);
  const std::array<double, 2> range = sampler->ValueRange();
  EXPECT_GE(range[1], v);
  EXPECT_EQ(range[0], 0.0);
  const savr::View view = ParallelViewAlongX(15, 3 * h, -5.0, 5.0);
  auto color = [](double) { return Eigen::Vector3d(1, 1, 1); };
  auto opacity = [kappa](double value) { return -std::expm1(-kappa * value); };
  const double step = 1e-3;
  ExpectBeerLambert(savr::ReferenceImage(view, *sampler, { color, opacity, 1.0 }, step), view, v, h,
    kappa, step, 0.0);

  savr::FrameSettings settings;
  settings.SampleDistance = 0.01;
  settings.MaximumFrames = 8;
  savr::FrameLoop loop;
  loop.Reset(view, sampler, settings);
  const auto table = MakeTable(loop.Encoding(), color, opacity);
  while (!loop.Complete())
  {
    loop.AccumulateFrame(table, savr::BlendMode::Composite);
  }
  ASSERT_EQ(loop.Frames(), 8);
  ExpectBeerLambert(loop.Image(), view, v, h, kappa, settings.SampleDistance / 8,
    (range[1] - range[0]) / (loop.Encoding().Levels - 1));
}

// The SPH kernels integrate to 1 over space and vanish at their cutoff; one particle's summed
// field is the kernel. The integral is the midpoint rule on a grid of step s = h / 16 (the
// field sampled along lines); its error is at most s^2 / 24 times the integral of |W_xx| +
// |W_yy| + |W_zz|, which the test takes from second differences of the same samples.
TEST(ParticleSampler, SPHKernelsAreNormalizedAndMatchTheirDefinition)
{
  for (savr::ParticleKernel kernel :
    { savr::ParticleKernel::SPHCubic, savr::ParticleKernel::SPHQuintic })
  {
    SCOPED_TRACE(Name(kernel));
    const double h = 0.8;
    Cloud cloud;
    cloud.Add(Eigen::Vector3d::Zero(), 1.0);
    auto sampler = cloud.Sampler(kernel, false, h);
    ASSERT_TRUE(sampler);
    const double cutoff = Cutoff(kernel) * h;
    const int n = static_cast<int>(std::lround(2 * cutoff / (h / 16)));
    const double s = 2 * cutoff / n;
    double integral = 0.0;
    double curvature = 0.0; // integral of |W_xx| along the lines, times 3 (symmetry)
    std::vector<float> line(n);
    for (int k = 0; k < n; ++k)
    {
      for (int j = 0; j < n; ++j)
      {
        savr::Ray ray;
        ray.Direction = Eigen::Vector3d::UnitX();
        ray.Origin = Eigen::Vector3d(0.0, -cutoff + (j + 0.5) * s, -cutoff + (k + 0.5) * s);
        sampler->SampleRay(ray, -cutoff + 0.5 * s, s, n, line.data());
        for (int i = 0; i < n; ++i)
        {
          const double f = std::isnan(line[i]) ? 0.0 : line[i];
          integral += f * s * s * s;
          if (i > 0 && i + 1 < n)
          {
            auto at = [&](int m)
            { return std::isnan(line[m]) ? 0.0 : static_cast<double>(line[m]); };
            curvature += 3 * std::abs(at(i - 1) - 2 * f + at(i + 1)) / (s * s) * s * s * s;
          }
        }
      }
    }
    EXPECT_NEAR(integral, 1.0, s * s / 24 * curvature + 1e-6);
    EXPECT_LT(s * s / 24 * curvature, 0.01); // the bound itself says something

    savr::Ray ray;
    ray.Direction = Eigen::Vector3d(1, 2, 2) / 3;
    const double peak = Kernel(kernel, 0.0, h);
    for (double r : { 0.0, 0.1, 0.37, 0.8, 0.99, 1.2, 1.6, 2.1, 2.5 })
    {
      float value;
      sampler->SampleRay(ray, r, 1.0, 1, &value);
      if (r < cutoff)
      {
        EXPECT_NEAR(value, Kernel(kernel, r, h), 1e-6 * peak) << r;
      }
      else
      {
        EXPECT_TRUE(std::isnan(value)) << r;
      }
    }
    float edge;
    sampler->SampleRay(ray, cutoff * (1 - 1e-6), 1.0, 1, &edge);
    EXPECT_LT(edge, 1e-15 * peak); // (cutoff gap in q)^3 or ^5 times the normalization
    EXPECT_GE(edge, 0.0f);
    sampler->SampleRay(ray, cutoff, 1.0, 1, &edge);
    EXPECT_TRUE(std::isnan(edge));
  }
}

// Analytic gradients against central differences of the samples, e = 1/1000 of the smallest h
// apart: the difference's error is the float rounding of its two samples (at most 6e-8 of each
// over 2 e) plus its truncation, c e^2 f''', which the difference at e / 2 measures (the two
// differ by 3/4 of it); the tolerance is the rounding plus twice that truncation, plus 1e-5 of
// the gradient for the sums' own rounding. Points within 2 e of a particle's knots (distances
// h, 2 h, 3 h) are left out: a Gaussian jumps at its cutoff, the splines' third derivatives jump
// at every knot, and the differences' error is then no longer O(e^2).
TEST(ParticleSampler, GradientsMatchDifferences)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud cloud;
  for (int j = 0; j < 200; ++j)
  {
    cloud.Add(Eigen::Vector3d(unit(random), unit(random), unit(random)) * 3.0,
      unit(random) * 4.0 - 1.0, 0.4 + 0.4 * unit(random));
  }
  for (savr::ParticleKernel kernel : kKernels)
  {
    for (bool normalized : { true, false })
    {
      SCOPED_TRACE(std::string(Name(kernel)) + (normalized ? " normalized" : " summed"));
      auto sampler = cloud.Sampler(kernel, normalized, 0.0, true);
      ASSERT_TRUE(sampler);
      int checked = 0;
      for (int r = 0; r < 30; ++r)
      {
        const savr::Ray ray =
          RayThrough(Eigen::Vector3d::Constant(1.5), RandomDirection(random), 3.0);
        const int count = 120;
        const double dt = 0.05;
        std::vector<float> values(count);
        std::vector<float> gradients(3 * count);
        sampler->SampleRayGradients(ray, 0.0, dt, count, values.data(), gradients.data());
        for (int i = 0; i < count; ++i)
        {
          const Eigen::Vector3d x = ray.At(i * dt);
          float at[3];
          sampler->GradientAt(ray, i * dt, at);
          for (int a = 0; a < 3; ++a)
          {
            EXPECT_EQ(at[a], gradients[3 * i + a]); // the same sums
          }
          if (std::isnan(values[i]))
          {
            EXPECT_TRUE(at[0] == 0 && at[1] == 0 && at[2] == 0);
            continue;
          }
          double smallest = 1e9; // distance to the nearest knot sphere (r = h, 2 h, 3 h)
          for (std::size_t j = 0; j < cloud.Values.size(); ++j)
          {
            const Eigen::Vector3d p(
              cloud.Points[3 * j], cloud.Points[3 * j + 1], cloud.Points[3 * j + 2]);
            for (int m = 1; m <= Cutoff(kernel); ++m)
            {
              smallest = std::min(smallest, std::abs((x - p).norm() - m * cloud.Radii[j]));
            }
          }
          const double e = 0.4 / 1000;
          if (smallest < 2 * e)
          {
            continue;
          }
          for (int a = 0; a < 3; ++a)
          {
            // The central difference at step `length`, and the bound on its float rounding.
            auto difference = [&](double length, double& rounding)
            {
              savr::Ray probe;
              probe.Direction = Eigen::Vector3d::UnitX();
              float plus;
              float minus;
              probe.Origin = x + length * Eigen::Vector3d::Unit(a);
              sampler->SampleRay(probe, 0.0, 1.0, 1, &plus);
              probe.Origin = x - length * Eigen::Vector3d::Unit(a);
              sampler->SampleRay(probe, 0.0, 1.0, 1, &minus);
              rounding = 6e-8 * (std::abs(plus) + std::abs(minus)) / (2 * length);
              return (static_cast<double>(plus) - minus) / (2 * length);
            };
            double rounding;
            double finer;
            const double coarse = difference(e, rounding);
            const double fine = difference(e / 2, finer);
            // Truncation at e is 4/3 of its change from e to e / 2 (both O(e^2)).
            const double truncation = 4.0 / 3.0 * (std::abs(coarse - fine) + rounding + finer);
            EXPECT_NEAR(gradients[3 * i + a], coarse,
              rounding + 2 * truncation + 1e-5 * std::abs(gradients[3 * i + a]));
          }
          ++checked;
        }
      }
      EXPECT_GT(checked, 500);
    }
  }
}

TEST(ParticleSampler, BadInputGivesAnErrorOrACorrectSampler)
{
  Cloud cloud;
  cloud.Add(Eigen::Vector3d(0, 0, 0), 1.0, 0.5);
  cloud.Add(Eigen::Vector3d(1, 0, 0), 2.0, 0.5);
  auto expectError = [](const savr::ParticleDescription& d, const std::string& contains)
  {
    std::string error;
    EXPECT_FALSE(savr::MakeParticleSampler(d, error)) << contains;
    EXPECT_NE(error.find(contains), std::string::npos) << error;
  };
  savr::ParticleDescription none = cloud.Description(savr::ParticleKernel::Gaussian, true, 0.5);
  none.NumberOfPoints = 0;
  expectError(none, "no particles");
  none = cloud.Description(savr::ParticleKernel::Gaussian, true, 0.5);
  none.Points = nullptr;
  expectError(none, "no particles");
  none = cloud.Description(savr::ParticleKernel::Gaussian, true, 0.5);
  none.Values = nullptr;
  expectError(none, "no values");
  for (double radius :
    { 0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity(), 1e-300, 1e300 })
  {
    for (savr::ParticleKernel kernel : kKernels)
    {
      expectError(cloud.Description(kernel, true, radius), "radius");
    }
  }
  // Per point: the first bad radius is named.
  Cloud radii = cloud;
  for (int j = 0; j < 10; ++j)
  {
    radii.Add(Eigen::Vector3d(j, 1, 0), j, j == 7 || j == 8 ? -0.5 : 0.5);
  }
  expectError(radii.Description(savr::ParticleKernel::SPHCubic, true, 0.5, true), "particle 9");

  // Non-finite positions and values: skipped and counted; none left is an error.
  Cloud broken = cloud;
  broken.Add(Eigen::Vector3d(std::nan(""), 0, 0), 5.0);
  broken.Add(Eigen::Vector3d(0, std::numeric_limits<double>::infinity(), 0), 5.0);
  broken.Add(Eigen::Vector3d(0, 0, 0), std::nan(""));
  std::string error;
  std::size_t skipped = 0;
  auto sampler = savr::MakeParticleSampler(
    broken.Description(savr::ParticleKernel::Gaussian, true, 0.5), error, &skipped);
  ASSERT_TRUE(sampler) << error;
  EXPECT_EQ(skipped, 3u);
  EXPECT_EQ(sampler->SkippedParticles(), 3u);
  EXPECT_EQ(sampler->ParticleCount(), 2u);
  EXPECT_EQ(sampler->ValueRange()[0], 1.0);
  EXPECT_EQ(sampler->ValueRange()[1], 2.0);
  Cloud allBroken;
  allBroken.Add(Eigen::Vector3d(std::nan(""), 0, 0), 1.0);
  expectError(
    allBroken.Description(savr::ParticleKernel::Gaussian, true, 0.5), "no particle has a finite");
}

// A million particles at one point: merged at build time into one, which keeps both fields
// exactly (the mean of the values; their sum times the kernel), so a ray costs one kernel
// evaluation per sample.
TEST(ParticleSampler, CoincidentParticlesAreMerged)
{
  const std::size_t n = 1000000;
  Cloud cloud;
  cloud.Points.reserve(3 * n + 3);
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j)
  {
    const double value = static_cast<double>(j % 7);
    cloud.Add(Eigen::Vector3d(1, 2, 3), value);
    sum += value;
  }
  cloud.Add(Eigen::Vector3d(1, 2, 3.5), 10.0); // another place
  const savr::Ray ray = RayThrough(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 0, 0), 2.0);
  const int count = 101;
  const double dt = 0.04;
  for (bool normalized : { true, false })
  {
    auto sampler = cloud.Sampler(savr::ParticleKernel::SPHCubic, normalized, 0.2);
    ASSERT_TRUE(sampler);
    EXPECT_EQ(sampler->ParticleCount(), 2u);
    std::vector<float> out(count);
    const std::uint64_t work = sampler->SampleRayCounted(ray, 0.0, dt, count, out.data());
    EXPECT_LE(work, 2u * count);
    int reached = 0;
    for (int i = 0; i < count; ++i)
    {
      const double r = std::abs(i * dt - 2.0);
      const double w = Kernel(savr::ParticleKernel::SPHCubic, r, 0.2);
      if (r < 0.4 - 1e-9)
      {
        ++reached;
        // The other particle is 0.5 away from the ray, beyond its support (0.4).
        const double expected = normalized ? sum / n : sum * w;
        EXPECT_NEAR(out[i], expected, 1e-6 * std::abs(expected) + 1e-30);
      }
      else if (r > 0.4 + 1e-9)
      {
        EXPECT_TRUE(std::isnan(out[i]));
      }
    }
    EXPECT_GT(reached, 10);
  }
  // Coincident with different radii: not merged.
  Cloud two;
  two.Add(Eigen::Vector3d(0, 0, 0), 1.0, 0.3);
  two.Add(Eigen::Vector3d(0, 0, 0), 3.0, 0.6);
  auto sampler = two.Sampler(savr::ParticleKernel::Gaussian, true, 0.0, true);
  ASSERT_TRUE(sampler);
  EXPECT_EQ(sampler->ParticleCount(), 2u);
  float value;
  savr::Ray ray2;
  sampler->SampleRay(ray2, 0.3, 1.0, 1, &value);
  const double w1 = std::exp(-0.5);
  const double w2 = std::exp(-0.125);
  EXPECT_NEAR(value, (w1 + 3 * w2) / (w1 + w2), 1e-6);
}

// Every particle reaching everywhere: slow (each sample adds them all) but bounded and right.
TEST(ParticleSampler, HugeRadiusReachesEverywhere)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud cloud;
  for (int j = 0; j < 500; ++j)
  {
    cloud.Add(Eigen::Vector3d(unit(random), unit(random), unit(random)), unit(random));
  }
  auto sampler = cloud.Sampler(savr::ParticleKernel::SPHQuintic, true, 1e6);
  ASSERT_TRUE(sampler);
  const savr::Ray ray =
    RayThrough(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(1, 1, 0), 1000.0);
  std::vector<float> out(64);
  const std::uint64_t work = sampler->SampleRayCounted(ray, 0.0, 1000.0 / 32, 64, out.data());
  EXPECT_LE(work, 500u * 64);
  double mean = 0.0;
  for (double v : cloud.Values)
  {
    mean += v / cloud.Values.size();
  }
  for (float v : out)
  {
    // So far inside every support the weights are equal to 1e-6 relative: the plain mean.
    EXPECT_NEAR(v, mean, 1e-4);
  }

  // Summed, with nearly half the supports a million times the rest: the bound on the field
  // must not test every large particle against a fine grid of cells (billions of pairs).
  Cloud mixed;
  for (int j = 0; j < 20000; ++j)
  {
    mixed.Add(Eigen::Vector3d(unit(random), unit(random), unit(random)), unit(random),
      j % 9 < 4 ? 1e3 : 1e-3);
  }
  auto summed = mixed.Sampler(savr::ParticleKernel::Gaussian, false, 0.0, true);
  ASSERT_TRUE(summed);
  float value;
  summed->SampleRay(ray, 1000.0, 1.0, 1, &value);
  EXPECT_GT(value, 0.0f);
  EXPECT_LE(value, summed->ValueRange()[1]);
}

// The same samples whatever the threads that built the index, and whatever pieces a ray is
// sampled in: samples on a lattice exact in binary (t0 and dt multiples of 1/64) are the same
// points, so the same bits. The value range (a bound, when summed) holds every sample, and is
// not far above them.
TEST(ParticleSampler, ResultsDoNotDependOnThreadsOrPieces)
{
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud cloud;
  for (int j = 0; j < 20000; ++j)
  {
    cloud.Add(Eigen::Vector3d(unit(random), unit(random), unit(random)) * 10.0, unit(random) - 0.3,
      0.2 + 0.3 * unit(random));
  }
  for (savr::ParticleKernel kernel : kKernels)
  {
    for (bool normalized : { true, false })
    {
      SCOPED_TRACE(std::string(Name(kernel)) + (normalized ? " normalized" : " summed"));
      std::shared_ptr<const savr::ParticleSampler> one;
      std::shared_ptr<const savr::ParticleSampler> two;
      tbb::task_arena(1).execute([&] { one = cloud.Sampler(kernel, normalized, 0.0, true); });
      tbb::task_arena(2).execute([&] { two = cloud.Sampler(kernel, normalized, 0.0, true); });
      ASSERT_TRUE(one && two);
      EXPECT_EQ(one->ValueRange(), two->ValueRange());
      EXPECT_EQ(one->IndexBytes(), two->IndexBytes());
      float largest = -std::numeric_limits<float>::infinity();
      for (int r = 0; r < 10; ++r)
      {
        const savr::Ray ray =
          RayThrough(Eigen::Vector3d::Constant(5.0), RandomDirection(random), 10.0);
        const int count = 1280;
        const double dt = 1.0 / 64;
        std::vector<float> a(count);
        std::vector<float> b(count);
        std::vector<float> pieces(count);
        one->SampleRay(ray, 0.0, dt, count, a.data());
        two->SampleRay(ray, 0.0, dt, count, b.data());
        for (int first = 0, k = 0; first < count; ++k)
        {
          const int length = std::min(count - first, 1 + (k * 37) % 300);
          one->SampleRay(ray, first * dt, dt, length, pieces.data() + first);
          first += length;
        }
        const std::array<double, 2> range = one->ValueRange();
        for (int i = 0; i < count; ++i)
        {
          // The range holds every sample (up to the sample's rounding to float).
          EXPECT_FALSE(a[i] < range[0] - 6e-8 * std::abs(range[0])) << a[i];
          EXPECT_FALSE(a[i] > range[1] + 6e-8 * std::abs(range[1])) << a[i];
          EXPECT_TRUE(a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i]))) << i;
          EXPECT_TRUE(a[i] == pieces[i] || (std::isnan(a[i]) && std::isnan(pieces[i]))) << i;
          largest = std::isnan(a[i]) ? largest : std::max(largest, a[i]);
        }
      }
      // Summed, the range is a bound: on this cloud 2 to 3.3 times the largest of millions of
      // samples (see SummedRange), so well within 10 times the largest of these.
      EXPECT_LT(one->ValueRange()[1], (normalized ? 1.0 : 10.0) * largest + 1.0);
    }
  }
}

// Two clusters far apart: between them the samples are NaN and cost no kernel evaluation.
TEST(ParticleSampler, EmptySpaceCostsNothing)
{
  std::mt19937 random(23);
  std::normal_distribution<double> spread(0.0, 0.5);
  Cloud cloud;
  for (double centre : { -10.0, 10.0 })
  {
    for (int j = 0; j < 2000; ++j)
    {
      cloud.Add(Eigen::Vector3d(centre + spread(random), spread(random), spread(random)), 1.0);
    }
  }
  auto sampler = cloud.Sampler(savr::ParticleKernel::Gaussian, false, 0.1);
  ASSERT_TRUE(sampler);
  // The clusters reach at most a few spreads plus 3 h from their centres; |x| < 6 is empty.
  double reach = 0.0;
  for (std::size_t j = 0; j < cloud.Values.size(); ++j)
  {
    reach = std::max(reach, 10.0 - std::abs(cloud.Points[3 * j]) + 0.3);
  }
  ASSERT_LT(reach, 4.0);
  savr::Ray ray;
  ray.Origin = Eigen::Vector3d(-20, 0, 0);
  ray.Direction = Eigen::Vector3d::UnitX();
  const int count = 4001;
  const double dt = 0.01;
  std::vector<float> out(count);
  const std::uint64_t all = sampler->SampleRayCounted(ray, 0.0, dt, count, out.data());
  EXPECT_GT(all, 0u);
  int inGap = 0;
  for (int i = 0; i < count; ++i)
  {
    if (std::abs(-20 + i * dt) < 10 - reach)
    {
      ++inGap;
      EXPECT_TRUE(std::isnan(out[i]));
    }
  }
  EXPECT_GT(inGap, 1000);
  std::vector<float> gap(1000);
  EXPECT_EQ(sampler->SampleRayCounted(ray, 15.0, dt, 1000, gap.data()), 0u);
  for (float v : gap)
  {
    EXPECT_TRUE(std::isnan(v));
  }
  EXPECT_FALSE(std::isnan(out[1000])); // the centre of the first cluster
  EXPECT_GT(sampler->IndexBytes(), cloud.Values.size() * sizeof(savr::ParticleSampler::Particle));
}

// A negative step samples the same points from the other end, and a zero step one point again.
TEST(ParticleSampler, ReversedAndZeroStepsSampleTheSamePoints)
{
  std::mt19937 random(29);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud cloud;
  for (int j = 0; j < 300; ++j)
  {
    cloud.Add(Eigen::Vector3d(unit(random), unit(random), unit(random)) * 4.0, unit(random));
  }
  auto sampler = cloud.Sampler(savr::ParticleKernel::SPHQuintic, true, 0.3);
  ASSERT_TRUE(sampler);
  const savr::Ray ray = RayThrough(Eigen::Vector3d::Constant(2.0), Eigen::Vector3d(1, 2, 3), 4.0);
  const int count = 512;
  const double dt = 1.0 / 64;
  std::vector<float> forward(count);
  std::vector<float> backward(count);
  std::vector<float> gradients(3 * count);
  std::vector<float> backwardGradients(3 * count);
  sampler->SampleRayGradients(ray, 0.0, dt, count, forward.data(), gradients.data());
  sampler->SampleRayGradients(
    ray, (count - 1) * dt, -dt, count, backward.data(), backwardGradients.data());
  int finite = 0;
  for (int i = 0; i < count; ++i)
  {
    const int j = count - 1 - i;
    EXPECT_TRUE(forward[i] == backward[j] || (std::isnan(forward[i]) && std::isnan(backward[j])));
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_EQ(gradients[3 * i + a], backwardGradients[3 * j + a]);
    }
    finite += !std::isnan(forward[i]);
  }
  EXPECT_GT(finite, 100);
  std::vector<float> same(7);
  sampler->SampleRay(ray, 200 * dt, 0.0, 7, same.data());
  for (float v : same)
  {
    EXPECT_EQ(v, forward[200]);
  }
}

// Weights (volumes, as mass / density): the mean is sum of w v W over sum of w W, the sum is sum
// of w v W, both against a brute-force sum here (float rounding: 1e-6 relative), and coincident
// particles with different weights merge exactly. Weights that are not finite and positive
// skip their particles.
TEST(ParticleSampler, WeightsScaleTheSumAndTheMean)
{
  std::mt19937 random(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud cloud;
  std::vector<double> weights;
  for (int j = 0; j < 400; ++j)
  {
    cloud.Add(Eigen::Vector3d(unit(random), unit(random), unit(random)) * 3.0, unit(random));
    weights.push_back(0.1 + 2.0 * unit(random));
  }
  // The same place and radius twice, weights 0.5 and 3: one particle.
  cloud.Add(Eigen::Vector3d(1.5, 1.5, 1.5), 4.0);
  weights.push_back(0.5);
  cloud.Add(Eigen::Vector3d(1.5, 1.5, 1.5), -2.0);
  weights.push_back(3.0);
  for (double bad : { 0.0, -1.0, std::nan("") })
  {
    cloud.Add(Eigen::Vector3d(1, 1, 1), 100.0);
    weights.push_back(bad);
  }
  const double h = 0.4;
  for (bool normalized : { true, false })
  {
    savr::ParticleDescription d = cloud.Description(savr::ParticleKernel::SPHCubic, normalized, h);
    d.Weights = weights.data();
    std::string error;
    std::size_t skipped = 0;
    auto sampler = savr::MakeParticleSampler(d, error, &skipped);
    ASSERT_TRUE(sampler) << error;
    EXPECT_EQ(skipped, 3u);
    EXPECT_EQ(sampler->ParticleCount(), 401u);
    int checked = 0;
    for (int r = 0; r < 20; ++r)
    {
      const savr::Ray ray =
        RayThrough(Eigen::Vector3d::Constant(1.5), RandomDirection(random), 2.0);
      std::vector<float> out(64);
      sampler->SampleRay(ray, 0.0, 1.0 / 16, 64, out.data());
      for (int i = 0; i < 64; ++i)
      {
        const Eigen::Vector3d x = ray.At(i / 16.0);
        double sum = 0.0;
        double sizes = 0.0; // of the terms of the sum, which may cancel
        double weight = 0.0;
        for (std::size_t j = 0; j < 402; ++j)
        {
          const Eigen::Vector3d p(
            cloud.Points[3 * j], cloud.Points[3 * j + 1], cloud.Points[3 * j + 2]);
          const double w = Kernel(savr::ParticleKernel::SPHCubic, (x - p).norm(), h);
          sum += weights[j] * cloud.Values[j] * w;
          sizes += std::abs(weights[j] * cloud.Values[j] * w);
          weight += weights[j] * w;
        }
        if (weight == 0.0)
        {
          EXPECT_TRUE(std::isnan(out[i]));
          continue;
        }
        const double expected = normalized ? sum / weight : sum;
        // Rounding: of the float sample, and of the sums in double (far below 1e-9 of the terms'
        // sizes: the merged particle's 0.5 * 4 - 3 * 2 rounds in its own sum too).
        EXPECT_NEAR(out[i], expected,
          6e-8 * std::abs(expected) + 1e-9 * (normalized ? sizes / weight : sizes));
        ++checked;
      }
    }
    EXPECT_GT(checked, 500);
  }
}

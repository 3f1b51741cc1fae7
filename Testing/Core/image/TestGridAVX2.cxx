// The grid sampler's vector path (eight linear samples at a time, where the CPU has AVX2) gives
// the same numbers, bit for bit, as its scalar path.

#include "encoding/SampleEncoding.h"
#include "blend/ShadingTable.h"
#include "image/GridAVX2.h"
#include "image/GridGradients.h"
#include "image/GridSampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace
{
template <typename T>
std::vector<T> Values(std::size_t n, std::mt19937& random)
{
  std::vector<T> values(n);
  std::uniform_real_distribution<double> any(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double v = any(random);
    if (std::is_same<T, float>::value)
    {
      values[i] = static_cast<T>(-3.0 + 1000.0 * v);
    }
    else
    {
      values[i] = static_cast<T>(v * (sizeof(T) == 1 ? 255.0 : 65535.0));
    }
  }
  return values;
}

// Gradients asked for a run of samples (as a pass asks for the samples it sees) are those of
// the whole ray (`whole`, for the samples `values`), whichever run, and nothing else is written.
void GradientRunsAreTheWholeRays(const savr::Sampler& vector, const savr::Sampler& scalar,
  const savr::Ray& ray, double t0, double dt, const std::vector<float>& values,
  const std::vector<float>& whole, std::mt19937& random)
{
  const int count = static_cast<int>(values.size());
  std::uniform_int_distribution<int> at(0, count - 1);
  for (int run = 0; run < 4; ++run)
  {
    int from = at(random);
    int to = at(random);
    if (from > to)
    {
      std::swap(from, to);
    }
    for (const savr::Sampler* sampler : { &vector, &scalar })
    {
      std::vector<float> g(3 * static_cast<std::size_t>(count), 12345.0f);
      sampler->GradientsAlongRay(ray, t0, dt, from, to, values.data(), g.data());
      for (int i = 0; i < count; ++i)
      {
        const float* expected = i >= from && i <= to ? &whole[3 * i] : nullptr;
        for (int c = 0; c < 3; ++c)
        {
          const float want = expected ? expected[c] : 12345.0f;
          ASSERT_EQ(0, std::memcmp(&g[3 * i + c], &want, sizeof(float)))
            << (sampler == &vector ? "vector" : "scalar") << ", run [" << from << ", " << to
            << "], sample " << i << ", dt " << dt;
        }
      }
    }
  }
}

// Rays through (and past) a grid of `dims` points, sampled by both paths.
template <typename T>
void Compare(savr::ScalarType type, std::array<int, 3> dims, int components, bool cellData,
  int& compared, long long& starts, long long& tight, long long& found, long long& normalsCompared)
{
  std::mt19937 random(7);
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] * components;
  std::vector<T> values = Values<T>(n, random);
  // A constant corner, so that blocks with one value (and blocks whose gradients are all zero)
  // take their own branch.
  for (int k = 0; k < 11; ++k)
    for (int j = 0; j < 11; ++j)
      for (int i = 0; i < 11; ++i)
      {
        values[(i + dims[0] * (j + dims[1] * k)) * components] = static_cast<T>(7);
      }
  savr::GridDescription grid;
  grid.Data = values.data();
  grid.Type = type;
  grid.Components = components;
  grid.Dims = dims;
  grid.CellData = cellData;
  grid.WorldToIndex = Eigen::Affine3d::Identity();
  grid.WorldToIndex.scale(Eigen::Vector3d(1.0 / 0.7, 1.0 / 1.1, 1.0 / 0.9));
  grid.WorldToIndex.translate(Eigen::Vector3d(0.3, -0.2, 0.1));
  std::string error;
  auto vector = savr::MakeGridSampler(grid, error);
  grid.Vectorize = false;
  auto scalar = savr::MakeGridSampler(grid, error);
  ASSERT_TRUE(vector && scalar) << error;
  // Skip every third block that has one.
  std::vector<std::uint8_t> flags(vector->BlockRanges().size() / 2);
  for (std::size_t b = 0; b < flags.size(); ++b)
  {
    flags[b] = b % 3 == 1;
  }
  savr::SkipMask mask;
  mask.Skip = &flags;
  // Mostly skipped space, as flags and as the distances that let samplers pass over it.
  std::vector<std::uint8_t> sparse(flags.size());
  std::bernoulli_distribution visible(0.15);
  for (std::uint8_t& f : sparse)
  {
    f = !visible(random);
  }
  std::vector<std::uint8_t> distances = sparse;
  vector->SkipDistances(distances);
  savr::SkipMask sparseMask;
  sparseMask.Skip = &sparse;
  savr::SkipMask distanceMask;
  distanceMask.Skip = &distances;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector3d size(0.7 * (dims[0] - 1), 1.1 * (dims[1] - 1), 0.9 * (dims[2] - 1));
  const Eigen::Vector3d centre = 0.5 * size - Eigen::Vector3d(0.3 * 0.7, -0.2 * 1.1, 0.1 * 0.9);
  for (int r = 0; r < 200; ++r)
  {
    savr::Ray ray;
    ray.Direction = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    if (r % 10 == 0)
    {
      ray.Direction = Eigen::Vector3d::UnitX(); // along a grid axis
    }
    ray.Origin =
      centre + 0.3 * size.cwiseProduct(Eigen::Vector3d(unit(random), unit(random), unit(random))) -
      2.0 * size.norm() * ray.Direction;
    double tEnter = 0.0;
    double tExit = 0.0;
    if (!vector->Clip(ray, tEnter, tExit))
    {
      continue;
    }
    for (double dt : { 0.37, 1.0, 0.05 })
    {
      const int count = static_cast<int>((tExit - tEnter) / dt) + 3;
      std::vector<float> a(count);
      std::vector<float> b(count);
      for (const savr::SkipMask* skip :
        { static_cast<const savr::SkipMask*>(nullptr), static_cast<const savr::SkipMask*>(&mask) })
      {
        vector->SampleRay(ray, tEnter - dt, dt, count, a.data(), skip);
        scalar->SampleRay(ray, tEnter - dt, dt, count, b.data(), skip);
        ASSERT_EQ(0, std::memcmp(a.data(), b.data(), count * sizeof(float)))
          << "ray " << r << " dt " << dt;
        compared += count;
      }
      // Gradients, and the values that come with them.
      std::vector<float> ga(3 * static_cast<std::size_t>(count));
      std::vector<float> gb(3 * static_cast<std::size_t>(count));
      vector->SampleRayGradients(ray, tEnter - dt, dt, count, a.data(), ga.data());
      scalar->SampleRayGradients(ray, tEnter - dt, dt, count, b.data(), gb.data());
      ASSERT_EQ(0, std::memcmp(a.data(), b.data(), count * sizeof(float)))
        << "values with gradients, ray " << r << " dt " << dt;
      ASSERT_EQ(0, std::memcmp(ga.data(), gb.data(), ga.size() * sizeof(float)))
        << "gradients, ray " << r << " dt " << dt;
      compared += count;
      // Normals encoded by the gradient kernel: the same values, and EncodeNormal's codes of
      // the same gradients (kNoNormal where the value is NaN, outside the grid).
      std::vector<std::uint16_t> normals(count);
      std::vector<float> c(count);
      ASSERT_FALSE(scalar->SampleRayNormals(ray, tEnter - dt, dt, count, c.data(), normals.data()));
      ASSERT_TRUE(vector->SampleRayNormals(ray, tEnter - dt, dt, count, c.data(), normals.data()));
      ASSERT_EQ(0, std::memcmp(c.data(), b.data(), count * sizeof(float)))
        << "values with normals, ray " << r << " dt " << dt;
      for (int i = 0; i < count; ++i)
      {
        ASSERT_EQ(normals[i], savr::EncodeNormal(&gb[3 * static_cast<std::size_t>(i)]))
          << "normal " << i << ", ray " << r << " dt " << dt;
        normalsCompared += normals[i] != savr::kNoNormal;
      }
      GradientRunsAreTheWholeRays(*vector, *scalar, ray, tEnter - dt, dt, a, ga, random);
      // Passing over skipped space by distance gives what block-by-block flags give.
      std::vector<float> e(count);
      vector->SampleRay(ray, tEnter - dt, dt, count, a.data(), &sparseMask);
      vector->SampleRay(ray, tEnter - dt, dt, count, b.data(), &distanceMask);
      scalar->SampleRay(ray, tEnter - dt, dt, count, c.data(), &sparseMask);
      scalar->SampleRay(ray, tEnter - dt, dt, count, e.data(), &distanceMask);
      ASSERT_EQ(0, std::memcmp(a.data(), b.data(), count * sizeof(float)))
        << "vector, ray " << r << " dt " << dt;
      ASSERT_EQ(0, std::memcmp(a.data(), c.data(), count * sizeof(float)))
        << "vector and scalar, ray " << r << " dt " << dt;
      ASSERT_EQ(0, std::memcmp(c.data(), e.data(), count * sizeof(float)))
        << "scalar, ray " << r << " dt " << dt;
      compared += count;
      // Where a pass may start: every sample before is NaN, and the sample there is not.
      for (const savr::SkipMask* skip : { &mask, &sparseMask, &distanceMask })
      {
        vector->SampleRay(ray, tEnter - dt, dt, count, a.data(), skip);
        const int start = vector->FirstUnskipped(ray, tEnter - dt, dt, count, skip);
        ASSERT_EQ(start, scalar->FirstUnskipped(ray, tEnter - dt, dt, count, skip));
        ASSERT_GE(start, 0);
        for (int i = 0; i < std::min(start, count); ++i)
        {
          ASSERT_TRUE(std::isnan(a[i])) << "sample " << i << " before " << start << ", ray " << r;
        }
        if (start > 0 && start < count) // 0 is always allowed
        {
          ASSERT_FALSE(std::isnan(a[start])) << "sample " << start << ", ray " << r;
        }
        starts += start;
        // The same found block by block, in the ray's parameter: every sample before it NaN,
        // none of them past the first that is not.
        const double t0 = tEnter - dt;
        const double t1 = t0 + count * dt;
        const double entry = scalar->FirstUnskippedAt(ray, t0, t1, skip);
        ASSERT_EQ(entry, vector->FirstUnskippedAt(ray, t0, t1, skip));
        ASSERT_TRUE(entry >= t0 && entry <= t1) << "ray " << r;
        for (int i = 0; i < count && t0 + i * dt < entry; ++i)
        {
          ASSERT_TRUE(std::isnan(a[i])) << "sample " << i << " before " << entry << ", ray " << r;
        }
        if (start < count)
        {
          ASSERT_LE(entry, t0 + start * dt) << "ray " << r << " dt " << dt;
        }
        // Within a step of that sample where samples are finer than the blocks' corners.
        tight += start < count && dt < 0.1 && entry > t0 + (start - 1) * dt - 1e-9;
        found += start < count && dt < 0.1;
      }
      // Leaps by distance find the entry the block-by-block walk finds.
      ASSERT_EQ(vector->FirstUnskippedAt(ray, tEnter - dt, tEnter + count * dt, &sparseMask),
        vector->FirstUnskippedAt(ray, tEnter - dt, tEnter + count * dt, &distanceMask))
        << "ray " << r << " dt " << dt;
    }
  }
}
} // namespace

TEST(GridArrays, VectorAndScalarPathsGiveTheSameBits)
{
  if (!savr::detail::HaveAVX2())
  {
    GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs";
  }
  int compared = 0;
  long long starts = 0; // samples that passes may pass over
  long long tight = 0;  // rays whose first unskipped block's entry lies within a step of its sample
  long long found = 0;
  long long normals = 0; // samples with a normal code, from the gradient kernel's encoding
  Compare<std::uint8_t>(
    savr::ScalarType::UInt8, { 37, 29, 41 }, 1, false, compared, starts, tight, found, normals);
  Compare<std::uint8_t>(
    savr::ScalarType::UInt8, { 20, 23, 18 }, 1, true, compared, starts, tight, found, normals);
  Compare<std::uint8_t>(
    savr::ScalarType::UInt8, { 17, 19, 21 }, 4, false, compared, starts, tight, found, normals);
  Compare<std::uint16_t>(
    savr::ScalarType::UInt16, { 33, 21, 25 }, 1, false, compared, starts, tight, found, normals);
  Compare<std::uint16_t>(
    savr::ScalarType::UInt16, { 19, 18, 17 }, 2, true, compared, starts, tight, found, normals);
  Compare<float>(
    savr::ScalarType::Float32, { 31, 27, 22 }, 1, false, compared, starts, tight, found, normals);
  EXPECT_GT(compared, 100000);
  EXPECT_GT(starts, 10000);
  std::cout << "block entries within a step of the first unskipped sample: " << tight << " of "
            << found << "\n";
  EXPECT_GT(found, 1000);
  EXPECT_GT(static_cast<double>(tight), 0.9 * found);
  EXPECT_GT(normals, 10000);
}

// Normals encoded four at a time are EncodeNormal's, bit for bit: random directions and
// lengths, axes, zeros, infinities and NaN.
TEST(GridArrays, VectorNormalsMatchEncodeNormal)
{
  std::mt19937 random(11);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> gradients;
  for (int i = 0; i < 4001; ++i)
  {
    const float scale = std::pow(10.0f, 6.0f * unit(random));
    gradients.insert(
      gradients.end(), { scale * unit(random), scale * unit(random), scale * unit(random) });
  }
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const std::array<float, 3>& g :
    std::vector<std::array<float, 3>>{ { 0, 0, 0 }, { -0.0f, 0, -0.0f }, { 1, 0, 0 }, { 0, -1, 0 },
      { 0, 0, -1 }, { -1, -1, -1 }, { inf, 0, 0 }, { nan, 1, 0 }, { 1e-40f, 0, -1e-40f } })
  {
    gradients.insert(gradients.end(), g.begin(), g.end());
  }
  const int n = static_cast<int>(gradients.size() / 3);
  std::vector<std::uint16_t> normals(n);
  savr::detail::EncodeNormalsAVX2(gradients.data(), n, normals.data());
  for (int i = 0; i < n; ++i)
  {
    ASSERT_EQ(normals[i], savr::EncodeNormal(&gradients[3 * static_cast<std::size_t>(i)]))
      << "gradient " << i;
  }
}

// The per-point gradients of a linear field, interpolated, are its gradient everywhere (one-sided
// differences at the faces included), in world units; cell data alike.
TEST(GridGradients, LinearFieldHasItsGradient)
{
  const std::array<int, 3> dims = { 12, 9, 10 };
  const Eigen::Vector3d spacing(0.7, 1.1, 0.9);
  const Eigen::Vector3d slope(2.0, -3.0, 0.5); // per world unit
  std::vector<float> values(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2]);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i)
      {
        values[i + dims[0] * (j + dims[1] * k)] =
          static_cast<float>(slope.dot(Eigen::Vector3d(i, j, k).cwiseProduct(spacing)) + 10.0);
      }
  for (bool cellData : { false, true })
  {
    savr::GridDescription grid;
    grid.Data = values.data();
    grid.Type = savr::ScalarType::Float32;
    grid.Dims = { dims[0] + cellData, dims[1] + cellData, dims[2] + cellData };
    grid.CellData = cellData;
    grid.WorldToIndex = Eigen::Affine3d::Identity();
    grid.WorldToIndex.scale(spacing.cwiseInverse());
    std::string error;
    auto sampler = savr::MakeGridSampler(grid, error);
    ASSERT_TRUE(sampler) << error;
    EXPECT_EQ(sampler->GradientBytes(), (3 * values.size() + 4) * sizeof(std::int16_t) +
                                          sampler->BlockRanges().size() / 2 * sizeof(std::int32_t));
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0; n < 200; ++n)
    {
      savr::Ray ray;
      ray.Origin = Eigen::Vector3d(unit(random) * (dims[0] - 1) * spacing[0],
        unit(random) * (dims[1] - 1) * spacing[1], unit(random) * (dims[2] - 1) * spacing[2]);
      float g[3];
      sampler->GradientAt(ray, 0.0, g);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(g[a], slope[a], 2e-3)
          << "cell data " << cellData << " at " << ray.Origin.transpose();
      }
    }
  }
}

// Skip distances are the chessboard distance, in blocks, to the nearest block not skipped.
TEST(GridArrays, SkipDistancesAreChessboardDistances)
{
  const std::array<int, 3> dims = { 75, 50, 43 }; // blocks of 8 cells: 10 x 7 x 6
  std::vector<std::uint8_t> values(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2], 1);
  savr::GridDescription grid;
  grid.Data = values.data();
  grid.Type = savr::ScalarType::UInt8;
  grid.Dims = dims;
  grid.WorldToIndex = Eigen::Affine3d::Identity();
  std::string error;
  auto sampler = savr::MakeGridSampler(grid, error);
  ASSERT_TRUE(sampler) << error;
  const int nx = 10;
  const int ny = 7;
  const int nz = 6;
  ASSERT_EQ(static_cast<std::size_t>(2 * nx * ny * nz), sampler->BlockRanges().size());
  std::mt19937 random(3);
  for (double density : { 0.02, 0.2, 0.0 })
  {
    std::bernoulli_distribution visible(density);
    std::vector<std::uint8_t> flags(nx * ny * nz);
    for (std::uint8_t& f : flags)
    {
      f = !visible(random);
    }
    std::vector<std::uint8_t> distances = flags;
    sampler->SkipDistances(distances);
    for (int b = 0; b < nx * ny * nz; ++b)
    {
      int expected = flags[b] ? 255 : 0;
      for (int c = 0; c < nx * ny * nz; ++c)
      {
        if (!flags[c])
        {
          const int ring = std::max({ std::abs(b % nx - c % nx),
            std::abs((b / nx) % ny - (c / nx) % ny), std::abs(b / (nx * ny) - c / (nx * ny)) });
          expected = std::min(expected, ring);
        }
      }
      ASSERT_EQ(expected, distances[b]) << "block " << b << " density " << density;
    }
  }
}

// The vector encoding of samples gives SampleEncoding::Encode's codes, NaN the pass's own code.
TEST(GridArrays, VectorEncodingMatchesEncode)
{
  if (!savr::detail::HaveAVX2())
  {
    GTEST_SKIP() << "this CPU has no AVX2: only the scalar path runs";
  }
  std::mt19937 random(11);
  std::uniform_real_distribution<double> any(-1.0, 1.0);
  struct Case
  {
    std::array<double, 2> range;
    int bits;
    bool nanCode;
  };
  const Case cases[] = { { { 0.0, 255.0 }, 8, false }, { { -3.0, 1000.0 }, 16, true },
    { { -1e-3, 2e-3 }, 0, true }, { { 5.0, 70000.0 }, 32, false } };
  int compared = 0;
  for (const Case& c : cases)
  {
    // A sampler stand-in that reports the case's range.
    struct Stand : savr::Sampler
    {
      Case C;
      bool Clip(const savr::Ray&, double&, double&) const override { return false; }
      std::array<double, 2> ValueRange() const override { return C.range; }
      int ExactBits() const override { return C.bits; }
      bool MayReturnNaN() const override { return C.nanCode; }
      void SampleRay(
        const savr::Ray&, double, double, int, float*, const savr::SkipMask*) const override
      {
      }
    } stand;
    stand.C = c;
    const savr::SampleEncoding e = savr::SampleEncoding::ForSampler(stand);
    std::vector<float> values(1003);
    const double span = c.range[1] - c.range[0];
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      values[i] = static_cast<float>(c.range[0] + span * (0.5 + 0.7 * any(random)));
    }
    values[3] = std::numeric_limits<float>::quiet_NaN();
    values[10] = std::numeric_limits<float>::infinity();
    values[11] = -std::numeric_limits<float>::infinity();
    values[12] = static_cast<float>(c.range[0]);
    values[13] = static_cast<float>(c.range[1]);
    const std::uint32_t nanCode = 17;
    std::vector<std::uint32_t> codes(values.size());
    savr::detail::EncodeAVX2(e.Offset, e.Scale, e.Levels, e.HasNaNCode ? e.NaNCode : 0u, nanCode,
      values.data(), static_cast<int>(values.size()), codes.data());
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      const float v = values[i];
      ASSERT_EQ(codes[i], v == v ? e.Encode(v) : nanCode) << "value " << v;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 4 * 1003);
}

// 8-bit data keeps its gradients as three 10-bit codes in one word: the same gradients, bit for
// bit, as three 16-bit codes, also where differences are largest (0 next to 255, and twice that
// at the faces), in a third less memory.
TEST(GridGradients, PackedCodesAreTheSixteenBitOnes)
{
  const long long dims[3] = { 13, 11, 9 };
  std::mt19937 random(5);
  std::vector<std::uint8_t> values(static_cast<std::size_t>(dims[0] * dims[1] * dims[2]));
  std::bernoulli_distribution extreme(0.5);
  std::uniform_int_distribution<int> any(0, 255);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    // Half the grid alternates 0 and 255 (the largest differences), half is random.
    values[i] =
      static_cast<std::uint8_t>(i < values.size() / 2 ? (extreme(random) ? 255 : 0) : any(random));
  }
  savr::detail::GradientShape shape;
  for (int a = 0; a < 3; ++a)
  {
    shape.Dims[a] = dims[a];
    shape.Blocks[a] = (dims[a] - 2) / 8 + 1;
  }
  shape.Step[0] = 1;
  shape.Step[1] = dims[0];
  shape.Step[2] = dims[0] * dims[1];
  Eigen::Matrix3d toWorld;
  toWorld << 0.9, 0.1, 0.0, -0.2, 1.3, 0.05, 0.0, 0.3, 0.7;
  savr::detail::GradientGrid wide;
  savr::detail::GradientGrid packed;
  wide.Compute(values.data(), shape, toWorld, true, false);
  packed.Compute(values.data(), shape, toWorld, true, true);
  ASSERT_EQ(wide.PackedData(), nullptr);
  ASSERT_NE(packed.PackedData(), nullptr);
  EXPECT_LT(3 * packed.Bytes(), 2 * wide.Bytes() + 64);
  const long long neighbour[3] = { 1, dims[0], dims[0] * dims[1] };
  std::uniform_real_distribution<float> weight(0.0f, 1.0f);
  float largest = 0.0f;
  for (long long k = 0; k + 1 < dims[2]; ++k)
    for (long long j = 0; j + 1 < dims[1]; ++j)
      for (long long i = 0; i + 1 < dims[0]; ++i)
      {
        const long long corner[3] = { i, j, k };
        const float w[3] = { weight(random), weight(random), weight(random) };
        float a[3];
        float b[3];
        wide.Interpolate(corner, neighbour, w, a);
        packed.Interpolate(corner, neighbour, w, b);
        ASSERT_EQ(0, std::memcmp(a, b, sizeof(a))) << "cell " << i << " " << j << " " << k;
        wide.AtPoint(corner, a);
        packed.AtPoint(corner, b);
        ASSERT_EQ(0, std::memcmp(a, b, sizeof(a))) << "point " << i << " " << j << " " << k;
        largest = std::max(largest, std::abs(a[0]));
      }
  // The extremes were there: 510 index units (a face's one-sided difference, doubled) times
  // the map's largest entry in the first row, halved back to the gradient.
  EXPECT_GT(largest, 200.0f);
}

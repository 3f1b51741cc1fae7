// The AMR sampler: finest-level lookup, seamless blocks, level blending, blanking, bad input.
#include "amr/AMRSampler.h"
#include "image/GridSampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace
{

using Field = std::function<double(const Eigen::Vector3d&)>;

// A hierarchy of cell-data blocks whose values are a field at the cell centres; blocks keep
// their values alive.
struct Hierarchy
{
  savr::AMRDescription Description;
  std::vector<std::vector<float>> Values;
  std::vector<std::vector<std::uint8_t>> Ghosts;

  Hierarchy(const Eigen::Vector3d& origin, const Eigen::Vector3d& spacing0, int levels, int ratio)
  {
    this->Description.Origin = origin;
    Eigen::Vector3d h = spacing0;
    for (int l = 0; l < levels; ++l)
    {
      this->Description.Spacing.push_back(h);
      h /= ratio;
    }
  }

  // Adds the block of `level` with cells lo..hi, its values sampled from `field`, with `ghost`
  // layers of cells around it (also sampled from the field).
  void Add(int level, std::array<int, 3> lo, std::array<int, 3> hi, const Field& field,
    int ghost = 0, bool pointData = false)
  {
    savr::AMRBlockDescription b;
    b.Level = level;
    b.Lo = lo;
    b.Hi = hi;
    const Eigen::Vector3d& h = this->Description.Spacing[level];
    std::array<int, 3> values;
    for (int a = 0; a < 3; ++a)
    {
      b.ArrayLo[a] = lo[a] - ghost;
      b.ArrayCells[a] = hi[a] - lo[a] + 1 + 2 * ghost;
      values[a] = b.ArrayCells[a] + (pointData ? 1 : 0);
    }
    std::vector<float> v;
    const double shift = pointData ? 0.0 : 0.5;
    for (int k = 0; k < values[2]; ++k)
      for (int j = 0; j < values[1]; ++j)
        for (int i = 0; i < values[0]; ++i)
        {
          const Eigen::Vector3d p =
            this->Description.Origin + Eigen::Vector3d((b.ArrayLo[0] + i + shift) * h[0],
                                         (b.ArrayLo[1] + j + shift) * h[1],
                                         (b.ArrayLo[2] + k + shift) * h[2]);
          v.push_back(static_cast<float>(field(p)));
        }
    this->Values.push_back(std::move(v));
    this->Description.CellData = !pointData;
    this->Description.Blocks.push_back(b);
  }

  std::shared_ptr<const savr::Sampler> Build()
  {
    for (std::size_t i = 0; i < this->Values.size(); ++i)
    {
      this->Description.Blocks[i].Data = this->Values[i].data();
    }
    std::string error;
    auto sampler = savr::MakeAMRSampler(this->Description, error);
    EXPECT_TRUE(sampler) << error;
    return sampler;
  }
};

double Linear(const Eigen::Vector3d& p)
{
  return 0.25 + 0.5 * p[0] - 0.75 * p[1] + 0.3 * p[2];
}

double Wavy(const Eigen::Vector3d& p)
{
  return std::sin(3.0 * p[0]) * std::cos(2.0 * p[1]) + 0.5 * p[2] * p[2];
}

float SampleAt(const savr::Sampler& s, const Eigen::Vector3d& p)
{
  savr::Ray ray;
  ray.Origin = p;
  float v = 0.0f;
  s.SampleRay(ray, 0.0, 1.0, 1, &v);
  return v;
}

// Random points at least `margin` inside the box [lo, hi].
std::vector<Eigen::Vector3d> Points(
  int n, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double margin)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i)
  {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a)
    {
      p[a] = lo[a] + margin + u(rng) * (hi[a] - lo[a] - 2 * margin);
    }
    points.push_back(p);
  }
  return points;
}

} // namespace

// Trilinear interpolation reproduces a linear field exactly, so every sample away from the
// outer boundary (where values are clamped) must equal the field: on the fine level, on the
// coarse one, in neighbouring blocks and across the coarse-fine boundary.
TEST(AMRSampler, LinearFieldIsExactEverywhereInside)
{
  Hierarchy amr(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(0.25, 0.25, 0.25), 3, 2);
  // Level 0: 8 cells per axis in two blocks; level 1: two neighbouring blocks; level 2: one.
  amr.Add(0, { 0, 0, 0 }, { 3, 7, 7 }, Linear);
  amr.Add(0, { 4, 0, 0 }, { 7, 7, 7 }, Linear);
  amr.Add(1, { 4, 4, 4 }, { 7, 11, 11 }, Linear);
  amr.Add(1, { 8, 4, 4 }, { 11, 11, 11 }, Linear);
  amr.Add(2, { 12, 12, 12 }, { 19, 19, 19 }, Linear);
  auto sampler = amr.Build();
  ASSERT_TRUE(sampler);
  const auto range = sampler->ValueRange();
  EXPECT_LT(range[0], range[1]);
  EXPECT_FALSE(sampler->MayReturnNaN());
  for (const Eigen::Vector3d& p :
    Points(4000, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1), 0.125))
  {
    EXPECT_NEAR(SampleAt(*sampler, p), Linear(p), 2e-6) << p.transpose();
  }
  // Outside the hierarchy: NaN.
  EXPECT_TRUE(std::isnan(SampleAt(*sampler, Eigen::Vector3d(1.5, 0, 0))));
}

// A level split into blocks samples exactly as the same lattice held in one grid: no seams.
TEST(AMRSampler, BlocksOfALevelAreSeamless)
{
  const int n = 12;
  Hierarchy amr(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0.1, 0.1), 1, 2);
  for (int b = 0; b < 8; ++b)
  {
    std::array<int, 3> lo;
    std::array<int, 3> hi;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = ((b >> a) & 1) ? 5 : 0;
      hi[a] = ((b >> a) & 1) ? n - 1 : 4;
    }
    amr.Add(0, lo, hi, Wavy);
  }
  auto sampler = amr.Build();
  ASSERT_TRUE(sampler);

  // The same cell values as one grid of cell data.
  std::vector<float> values;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        values.push_back(static_cast<float>(
          Wavy(Eigen::Vector3d((i + 0.5) * 0.1, (j + 0.5) * 0.1, (k + 0.5) * 0.1))));
      }
  savr::GridDescription grid;
  grid.Data = values.data();
  grid.Dims = { n + 1, n + 1, n + 1 };
  grid.CellData = true;
  grid.WorldToIndex = Eigen::Scaling(10.0, 10.0, 10.0);
  std::string error;
  auto reference = savr::MakeGridSampler(grid, error);
  ASSERT_TRUE(reference) << error;
  for (const Eigen::Vector3d& p :
    Points(4000, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.2, 1.2, 1.2), 0.0))
  {
    EXPECT_NEAR(SampleAt(*sampler, p), SampleAt(*reference, p), 1e-5) << p.transpose();
  }
  // Along a ray, in one call, as the renderer samples.
  savr::Ray ray;
  ray.Origin = Eigen::Vector3d(-0.5, 0.13, 0.71);
  ray.Direction = Eigen::Vector3d(1.0, 0.4, -0.2).normalized();
  std::vector<float> a(300);
  std::vector<float> b(300);
  sampler->SampleRay(ray, 0.0, 0.01, 300, a.data());
  reference->SampleRay(ray, 0.0, 0.01, 300, b.data());
  int inside = 0;
  for (int i = 0; i < 300; ++i)
  {
    ASSERT_EQ(std::isnan(a[i]), std::isnan(b[i])) << i;
    if (!std::isnan(a[i]))
    {
      EXPECT_NEAR(a[i], b[i], 1e-5);
      ++inside;
    }
  }
  EXPECT_GT(inside, 50);
}

// Where a finer level exists it is used: a level-1 block holding different values shows them,
// and the coarse level shows elsewhere.
TEST(AMRSampler, FinestLevelWins)
{
  Hierarchy amr(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 2, 2);
  amr.Add(0, { 0, 0, 0 }, { 7, 7, 7 }, [](const Eigen::Vector3d&) { return 1.0; });
  amr.Add(1, { 4, 4, 4 }, { 11, 11, 11 }, [](const Eigen::Vector3d&) { return 5.0; });
  auto sampler = amr.Build();
  ASSERT_TRUE(sampler);
  EXPECT_FLOAT_EQ(SampleAt(*sampler, Eigen::Vector3d(4, 4, 4)), 5.0f); // deep inside
  EXPECT_FLOAT_EQ(SampleAt(*sampler, Eigen::Vector3d(1, 1, 1)), 1.0f); // coarse only
  EXPECT_FLOAT_EQ(SampleAt(*sampler, Eigen::Vector3d(7, 7, 7)), 1.0f); // far from the fine box
  // Inside the fine box, within half a fine cell of its boundary, the coarse level blends in.
  const float edge = SampleAt(*sampler, Eigen::Vector3d(2.1, 4, 4));
  EXPECT_GT(edge, 1.0f);
  EXPECT_LT(edge, 5.0f);
}

// Point data: trilinear between the block's points, linear fields exact.
TEST(AMRSampler, PointData)
{
  Hierarchy amr(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, 0.5, 0.5), 2, 2);
  amr.Add(0, { 0, 0, 0 }, { 3, 3, 3 }, Linear, 0, true);
  amr.Add(1, { 2, 2, 2 }, { 5, 5, 5 }, Linear, 0, true);
  auto sampler = amr.Build();
  ASSERT_TRUE(sampler);
  for (const Eigen::Vector3d& p :
    Points(2000, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2), 0.0))
  {
    EXPECT_NEAR(SampleAt(*sampler, p), Linear(p), 2e-6) << p.transpose();
  }
}

// Ghost layers around blocks are read where they help and never make a block claim space.
TEST(AMRSampler, GhostLayers)
{
  Hierarchy amr(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.25, 0.25, 0.25), 1, 2);
  amr.Add(0, { 0, 0, 0 }, { 3, 7, 7 }, Linear, 1);
  amr.Add(0, { 4, 0, 0 }, { 7, 7, 7 }, Linear, 1);
  auto sampler = amr.Build();
  ASSERT_TRUE(sampler);
  for (const Eigen::Vector3d& p :
    Points(2000, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2), 0.125))
  {
    EXPECT_NEAR(SampleAt(*sampler, p), Linear(p), 2e-6) << p.transpose();
  }
  EXPECT_TRUE(std::isnan(SampleAt(*sampler, Eigen::Vector3d(2.1, 1, 1))));
}

// Blanked (hidden) cells without a finer block are holes; the volume's matrix places the data.
TEST(AMRSampler, HiddenCellsAndPlacement)
{
  Hierarchy amr(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1, 2);
  amr.Add(0, { 0, 0, 0 }, { 3, 3, 3 }, [](const Eigen::Vector3d&) { return 2.0; });
  std::vector<std::uint8_t> ghosts(64, 0);
  ghosts[1 + 4 * (1 + 4 * 1)] = 32; // cell (1, 1, 1)
  amr.Description.Blocks[0].CellGhosts = ghosts.data();
  amr.Description.WorldToData = Eigen::Translation3d(-10.0, 0.0, 0.0);
  auto sampler = amr.Build();
  ASSERT_TRUE(sampler);
  EXPECT_TRUE(sampler->MayReturnNaN());
  EXPECT_TRUE(std::isnan(SampleAt(*sampler, Eigen::Vector3d(11.5, 1.5, 1.5))));
  EXPECT_FLOAT_EQ(SampleAt(*sampler, Eigen::Vector3d(12.5, 1.5, 1.5)), 2.0f);
  EXPECT_TRUE(std::isnan(SampleAt(*sampler, Eigen::Vector3d(1.5, 1.5, 1.5))));
  savr::Ray ray;
  ray.Origin = Eigen::Vector3d(0, 2, 2);
  ray.Direction = Eigen::Vector3d::UnitX();
  double t0 = 0;
  double t1 = 0;
  ASSERT_TRUE(sampler->Clip(ray, t0, t1));
  EXPECT_NEAR(t0, 10.0, 1e-12);
  EXPECT_NEAR(t1, 14.0, 1e-12);
}

TEST(AMRSampler, BadInputIsRefused)
{
  std::string error;
  savr::AMRDescription empty;
  EXPECT_FALSE(savr::MakeAMRSampler(empty, error));
  EXPECT_FALSE(error.empty());

  Hierarchy amr(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 1), 1, 2);
  amr.Add(0, { 0, 0, 0 }, { 3, 3, 3 }, Linear);
  amr.Description.Blocks[0].Data = amr.Values[0].data();
  error.clear();
  EXPECT_FALSE(savr::MakeAMRSampler(amr.Description, error)); // zero spacing
  EXPECT_NE(error.find("spacing"), std::string::npos);

  Hierarchy onlyFine(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 2, 2);
  onlyFine.Add(1, { 0, 0, 0 }, { 3, 3, 3 }, Linear);
  onlyFine.Description.Blocks[0].Data = onlyFine.Values[0].data();
  error.clear();
  EXPECT_FALSE(savr::MakeAMRSampler(onlyFine.Description, error));
  EXPECT_FALSE(error.empty());

  Hierarchy noData(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), 1, 2);
  noData.Add(0, { 0, 0, 0 }, { 3, 3, 3 }, Linear);
  error.clear();
  EXPECT_FALSE(savr::MakeAMRSampler(noData.Description, error)); // data pointers not set
  EXPECT_FALSE(error.empty());
}

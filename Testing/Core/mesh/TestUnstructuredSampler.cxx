// The unstructured-mesh sampler against closed forms: every linear cell interpolates a linear
// field exactly, so samples must equal the field inside the mesh and be NaN outside it.
#include "mesh/UnstructuredTestMeshes.h"

#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <chrono>
#include <iostream>
#include <limits>

using namespace savr_test;

TEST(UnstructuredSampler, LinearFieldIsExactInEveryCellType)
{
  for (Split split : kAllSplits)
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice(
      { 5, 4, 3 }, Eigen::Vector3d(-1.0, -0.5, 0.2), Eigen::Vector3d(1.5, 1.0, 1.4), split);
    lattice.M.SetPointValues(Linear);
    auto sampler = lattice.M.Sampler();
    ASSERT_TRUE(sampler);
    CheckLinear(*sampler, lattice, 300, 11);
    EXPECT_EQ(sampler->ExactBits(), 0);
    EXPECT_TRUE(sampler->MayReturnNaN());
  }
}

// The largest error of the linear field about `offset` (the lattice's low corner, far from the
// origin) along random rays through `lattice`, at samples inside it that are not NaN; `inside`
// counts them.
double FarFieldError(Lattice& lattice, const Eigen::Vector3d& offset, unsigned seed, int& inside)
{
  const auto field = [&](const Eigen::Vector3d& p) { return Linear(p - offset); };
  lattice.M.SetPointValues(field);
  auto sampler = lattice.M.Sampler();
  inside = 0;
  if (!sampler)
  {
    return std::numeric_limits<double>::infinity();
  }
  double length;
  const auto rays = RandomRays(lattice.Lo, lattice.Hi, 200, seed, length);
  const int count = 201;
  const double dt = length / (count - 1);
  std::vector<float> out(count);
  double worst = 0.0;
  for (const savr::Ray& ray : rays)
  {
    sampler->SampleRay(ray, 0.0, dt, count, out.data());
    for (int i = 0; i < count; ++i)
    {
      if (lattice.Classify(ray.At(i * dt), 1e-6) > 0 && out[i] == out[i])
      {
        ++inside;
        worst = std::max(worst, std::abs(out[i] - field(ray.At(i * dt))));
      }
    }
  }
  return worst;
}

// A mesh a million units from the origin: tetrahedra keep their fields in floats relative to the
// mesh's centre, so a linear field is still exact to float rounding of its values.
TEST(UnstructuredSampler, LinearFieldIsExactFarFromTheOrigin)
{
  const Eigen::Vector3d offset(1e6, -2e6, 3e6);
  for (Split split : { Split::Tetrahedra5, Split::Tetrahedra6, Split::Mixed })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice({ 5, 4, 3 }, offset, offset + Eigen::Vector3d(2.0, 1.5, 1.0), split);
    int inside = 0;
    EXPECT_LT(FarFieldError(lattice, offset, 23, inside), 2e-5);
    EXPECT_GT(inside, 2000);
  }
}

// Curved cells a million units from the origin: their maps are kept as polynomials in floats
// relative to the mesh's centre, so Newton's iteration still finds where a sample lies and a
// linear field stays exact to the float rounding of its values.
TEST(UnstructuredSampler, CurvedCellsFarFromTheOriginKeepTheirField)
{
  const Eigen::Vector3d offset(1e6, -2e6, 3e6);
  for (Split split : { Split::Hexahedra, Split::Wedges, Split::Pyramids })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice({ 6, 5, 4 }, offset, offset + Eigen::Vector3d(3, 2.5, 2), split, nullptr, 0.2);
    int inside = 0;
    EXPECT_LT(FarFieldError(lattice, offset, 29, inside), 2e-4);
    EXPECT_GT(inside, 2000);
  }
}

// Interior points moved: hexahedra, wedges and pyramids get curved (non-planar) quad faces, which
// the walk crosses as two triangles, and many of these cells are not convex; their maps still
// reproduce a linear field exactly. (Not the mixed mesh: its cells do not share faces where their
// types change, and curved faces then leave gaps between cells, in the data itself.)
TEST(UnstructuredSampler, LinearFieldIsExactOnDistortedMeshes)
{
  for (Split split :
    { Split::Hexahedra, Split::Tetrahedra5, Split::Tetrahedra6, Split::Wedges, Split::Pyramids })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice(
      { 6, 5, 4 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 2.5, 2), split, nullptr, 0.2);
    lattice.M.SetPointValues(Linear);
    auto sampler = lattice.M.Sampler();
    ASSERT_TRUE(sampler);
    CheckLinear(*sampler, lattice, 300, 12);
  }
}

TEST(UnstructuredSampler, CellDataReadsTheContainingCell)
{
  for (Split split : { Split::Hexahedra, Split::Tetrahedra6 })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice({ 5, 4, 3 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(5, 4, 3), split);
    Mesh& m = lattice.M;
    for (std::size_t c = 0; c < m.Cells(); ++c)
    {
      m.Values.push_back(static_cast<float>(3 * c + 1));
    }
    auto sampler = m.Sampler(true);
    ASSERT_TRUE(sampler);
    // The containing cell by brute force: barycentric coordinates of tetrahedra, lattice
    // indices of hexahedra.
    auto expected = [&](const Eigen::Vector3d& p) -> double
    {
      const double margin = 1e-6;
      if (split == Split::Hexahedra)
      {
        int index[3];
        for (int a = 0; a < 3; ++a)
        {
          const double f = p[a] - std::floor(p[a]);
          if (f < margin || f > 1.0 - margin)
          {
            return -1.0; // on a face: either cell
          }
          index[a] = static_cast<int>(std::floor(p[a]));
        }
        return 3 * (index[0] + 5 * (index[1] + 4 * index[2])) + 1;
      }
      for (std::size_t c = 0; c < m.Cells(); ++c)
      {
        const std::int64_t* ids = &m.Connectivity[m.Offsets[c]];
        Eigen::Matrix3d e;
        for (int k = 0; k < 3; ++k)
        {
          e.col(k) = m.Point(ids[k + 1]) - m.Point(ids[0]);
        }
        const Eigen::Vector3d b = e.inverse() * (p - m.Point(ids[0]));
        const double b0 = 1.0 - b.sum();
        if (b.minCoeff() > margin && b0 > margin)
        {
          return m.Values[c];
        }
      }
      return -1.0;
    };
    double length;
    const auto rays = RandomRays(lattice.Lo, lattice.Hi, 100, 5, length);
    std::vector<float> out(200);
    int checked = 0;
    int wrong = 0;
    for (const savr::Ray& ray : rays)
    {
      const double dt = length / 199;
      sampler->SampleRay(ray, 0.0, dt, 200, out.data());
      for (int i = 0; i < 200; ++i)
      {
        const Eigen::Vector3d p = ray.At(i * dt);
        const int where = lattice.Classify(p, 1e-6);
        const double want = where > 0 ? expected(p) : -1.0;
        if (where < 0)
        {
          wrong += !std::isnan(out[i]);
        }
        else if (want >= 0.0)
        {
          ++checked;
          wrong += out[i] != static_cast<float>(want);
        }
      }
    }
    EXPECT_EQ(wrong, 0);
    EXPECT_GT(checked, 1000);
  }
}

TEST(UnstructuredSampler, BadInputGivesAnError)
{
  Lattice lattice({ 2, 2, 2 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Split::Mixed);
  lattice.M.SetPointValues(Linear);
  const Mesh good = lattice.M;
  auto expectError = [](const savr::UnstructuredDescription& d, const char* what)
  {
    std::string error;
    EXPECT_FALSE(savr::MakeUnstructuredSampler(d, error)) << what;
    EXPECT_FALSE(error.empty()) << what;
  };
  {
    std::string error;
    EXPECT_TRUE(savr::MakeUnstructuredSampler(good.Description(), error)) << error;
  }
  auto d = good.Description();
  d.Points = nullptr;
  expectError(d, "no points");
  d = good.Description();
  d.NumberOfPoints = 0;
  expectError(d, "zero points");
  d = good.Description();
  d.NumberOfCells = 0;
  expectError(d, "no cells");
  d = good.Description();
  d.Offsets = nullptr;
  expectError(d, "no offsets");
  d = good.Description();
  d.Connectivity = nullptr;
  expectError(d, "no connectivity");
  d = good.Description();
  d.Types = nullptr;
  expectError(d, "no types");
  d = good.Description();
  d.Values = nullptr;
  expectError(d, "no values");

  Mesh bad = good;
  bad.Connectivity[5] = static_cast<std::int64_t>(bad.Points.size() / 3);
  expectError(bad.Description(), "point id past the end");
  bad = good;
  bad.Connectivity[3] = -1;
  expectError(bad.Description(), "negative point id");
  bad = good;
  bad.Types[0] = kTetra; // a hexahedron's 8 points
  expectError(bad.Description(), "wrong number of points");
  bad = good;
  std::swap(bad.Offsets[1], bad.Offsets[2]);
  expectError(bad.Description(), "decreasing offsets");

  // Only unsupported cells (triangles, polyhedra): an error, and the count.
  Mesh other;
  other.AddPoint(Eigen::Vector3d(0, 0, 0));
  other.AddPoint(Eigen::Vector3d(1, 0, 0));
  other.AddPoint(Eigen::Vector3d(0, 1, 0));
  other.AddCell(5, { 0, 1, 2 });
  other.AddCell(42, { 0, 1, 2 });
  other.SetPointValues(Linear);
  std::string error;
  std::size_t skipped = 0;
  EXPECT_FALSE(savr::MakeUnstructuredSampler(other.Description(), error, &skipped));
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(skipped, 2u);
}

TEST(UnstructuredSampler, SkipsUnsupportedCellsAndCountsThem)
{
  Lattice lattice(
    { 3, 3, 3 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 3, 3), Split::Tetrahedra5);
  Mesh& m = lattice.M;
  m.AddCell(5, { 0, 1, 2 });       // triangle
  m.AddCell(7, { 0, 1, 2, 3, 4 }); // polygon
  const std::int64_t far = m.AddPoint(Eigen::Vector3d(std::nan(""), 0, 0));
  m.AddCell(kTetra, { 0, 1, 2, far }); // a non-finite point
  m.SetPointValues(Linear);
  std::string error;
  std::size_t skipped = 0;
  auto sampler = savr::MakeUnstructuredSampler(m.Description(), error, &skipped);
  ASSERT_TRUE(sampler) << error;
  EXPECT_EQ(skipped, 3u);
  CheckLinear(*sampler, lattice, 100, 51);
}

TEST(UnstructuredSampler, ClipRangeAndGradients)
{
  for (Split split : kAllSplits)
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice({ 3, 4, 2 }, Eigen::Vector3d(-1, -2, 0), Eigen::Vector3d(2, 2, 1), split);
    Mesh& m = lattice.M;
    m.SetPointValues(Linear);
    auto sampler = m.Sampler();
    ASSERT_TRUE(sampler);
    const auto range = sampler->ValueRange();
    EXPECT_NEAR(range[0], Linear(Eigen::Vector3d(-1, 2, 0)), 1e-5);
    EXPECT_NEAR(range[1], Linear(Eigen::Vector3d(2, -2, 1)), 1e-5);

    double t0;
    double t1;
    const savr::Ray through = MakeRay(Eigen::Vector3d(-5, 0.5, 0.5), Eigen::Vector3d(0, 0.5, 0.5));
    ASSERT_TRUE(sampler->Clip(through, t0, t1));
    EXPECT_NEAR(t0, 4.0, 1e-4);
    EXPECT_NEAR(t1, 7.0, 1e-4);
    const savr::Ray missing = MakeRay(Eigen::Vector3d(-5, 3, 0.5), Eigen::Vector3d(0, 3, 0.5));
    EXPECT_FALSE(sampler->Clip(missing, t0, t1));

    std::mt19937 random(3);
    std::uniform_real_distribution<double> u(0.02, 0.98);
    for (int k = 0; k < 200; ++k)
    {
      const Eigen::Vector3d p(-1 + 3 * u(random), -2 + 4 * u(random), u(random));
      savr::Ray ray = MakeRay(p - Eigen::Vector3d(0.3, 0.2, 0.1), p);
      float g[3];
      sampler->GradientAt(ray, std::sqrt(0.14), g);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(g[a], kLinearGradient[a], 1e-4) << p.transpose();
      }
    }
    float g[3] = { 1, 1, 1 };
    sampler->GradientAt(missing, 5.0, g);
    EXPECT_EQ(g[0], 0.0f);
    EXPECT_EQ(g[1], 0.0f);
    EXPECT_EQ(g[2], 0.0f);
  }

  // NaN and Inf values: left out of the range, and only the cells holding them read them.
  Lattice lattice(
    { 3, 3, 3 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 3, 3), Split::Hexahedra);
  lattice.M.SetPointValues(Linear);
  lattice.M.Values[lattice.Node(0, 0, 0)] = std::numeric_limits<float>::quiet_NaN();
  lattice.M.Values[lattice.Node(3, 3, 3)] = std::numeric_limits<float>::infinity();
  auto sampler = lattice.M.Sampler();
  ASSERT_TRUE(sampler);
  const auto range = sampler->ValueRange();
  EXPECT_NEAR(range[0], Linear(Eigen::Vector3d(0, 3, 0)), 1e-5);
  EXPECT_NEAR(range[1], Linear(Eigen::Vector3d(3, 0, 3)), 1e-5);
  std::vector<float> out(30);
  sampler->SampleRay(MakeRay(Eigen::Vector3d(-1, 1.5, 1.5), Eigen::Vector3d(0, 1.5, 1.5)), 1.05,
    0.1, 30, out.data());
  for (int i = 0; i < 30; ++i)
  {
    EXPECT_NEAR(out[i], Linear(Eigen::Vector3d(0.05 + 0.1 * i, 1.5, 1.5)), 1e-5);
  }

  // Cell data: central differences one cell apart.
  Lattice cells({ 4, 4, 4 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 4), Split::Hexahedra);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
      {
        cells.M.Values.push_back(static_cast<float>(Linear(Eigen::Vector3d(i, j, k))));
      }
  auto cellSampler = cells.M.Sampler(true);
  ASSERT_TRUE(cellSampler);
  float g[3];
  cellSampler->GradientAt(
    MakeRay(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1)), std::sqrt(3.0) * 1.5, g);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_NEAR(g[a], kLinearGradient[a], 1e-5);
  }
}

// Samples at decreasing parameters, and many samples at one point.
TEST(UnstructuredSampler, ReversedAndRepeatedSamples)
{
  Lattice lattice({ 4, 4, 4 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Split::Mixed);
  lattice.M.SetPointValues(Linear);
  auto sampler = lattice.M.Sampler();
  ASSERT_TRUE(sampler);
  const savr::Ray ray = MakeRay(Eigen::Vector3d(-1, 0.3, 0.4), Eigen::Vector3d(1.5, 0.6, 0.7));
  std::vector<float> forward(100);
  std::vector<float> backward(100);
  sampler->SampleRay(ray, 0.5, 0.03, 100, forward.data());
  sampler->SampleRay(ray, 0.5 + 99 * 0.03, -0.03, 100, backward.data());
  int finite = 0;
  for (int i = 0; i < 100; ++i)
  {
    const float f = forward[i];
    const float b = backward[99 - i];
    if (std::isnan(f) || std::isnan(b))
    {
      EXPECT_TRUE(std::isnan(f) && std::isnan(b)) << i;
      continue;
    }
    ++finite;
    EXPECT_NEAR(f, b, 1e-5);
  }
  EXPECT_GT(finite, 30);
  std::vector<float> same(10);
  sampler->SampleRay(ray, 1.5, 0.0, 10, same.data());
  for (float v : same)
  {
    EXPECT_NEAR(v, Linear(ray.At(1.5)), 1e-5);
  }
}

TEST(UnstructuredSampler, ThreadsGiveTheSameSamples)
{
  Lattice lattice(
    { 8, 7, 6 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2), Split::Mixed, nullptr, 0.2);
  lattice.M.SetPointValues([](const Eigen::Vector3d& p)
    { return std::sin(3 * p.x()) * std::cos(2 * p.y()) + p.z() * p.z(); });
  auto sampler = lattice.M.Sampler();
  ASSERT_TRUE(sampler);
  double length;
  const auto rays = RandomRays(lattice.Lo, lattice.Hi, 4000, 61, length);
  const int count = 150;
  const double dt = length / count;
  std::vector<float> serial(rays.size() * count);
  std::vector<float> parallel(rays.size() * count);
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    sampler->SampleRay(rays[r], 0.0, dt, count, serial.data() + r * count);
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1),
    [&](const tbb::blocked_range<std::size_t>& range)
    {
      for (std::size_t r = range.begin(); r < range.end(); ++r)
      {
        sampler->SampleRay(rays[r], 0.0, dt, count, parallel.data() + r * count);
      }
    });
  EXPECT_TRUE(SameBits(serial, parallel));
  int finite = 0;
  for (float v : serial)
  {
    finite += std::isfinite(v);
  }
  EXPECT_GT(finite, 10000);
}

// Trilinear interpolation on a grid is the hexahedron's isoparametric map on an axis-aligned box:
// the two samplers agree on a non-linear field.
TEST(UnstructuredSampler, HexahedraMatchTheGridSampler)
{
  const int n = 14;
  WaveGrid wave(n);
  auto grid = wave.Sampler();
  Lattice lattice({ n - 1, n - 1, n - 1 }, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1),
    Split::Hexahedra);
  lattice.M.Values = wave.Values; // the same lattice order
  auto mesh = lattice.M.Sampler();
  ASSERT_TRUE(mesh);
  EXPECT_NEAR(mesh->ValueRange()[0], grid->ValueRange()[0], 1e-6);
  EXPECT_NEAR(mesh->ValueRange()[1], grid->ValueRange()[1], 1e-6);
  double length;
  const auto rays = RandomRays(lattice.Lo, lattice.Hi, 500, 71, length);
  const int count = 400;
  const double dt = length / count;
  std::vector<float> a(count);
  std::vector<float> b(count);
  int compared = 0;
  double worst = 0.0;
  for (const savr::Ray& ray : rays)
  {
    mesh->SampleRay(ray, 0.0, dt, count, a.data());
    grid->SampleRay(ray, 0.0, dt, count, b.data());
    for (int i = 0; i < count; ++i)
    {
      const int where = lattice.Classify(ray.At(i * dt), 1e-5);
      if (where > 0)
      {
        ASSERT_TRUE(std::isfinite(a[i]) && std::isfinite(b[i]));
        worst = std::max(worst, std::abs(a[i] - b[i]) / (1.0 + std::abs(b[i])));
        ++compared;
      }
      else if (where < 0)
      {
        EXPECT_TRUE(std::isnan(a[i]));
      }
    }
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(compared, 20000);
}

// 47^3 lattice cells, 5 tetrahedra each (519k), seen through 512 x 512 rays of 100 samples: a
// timing printout, and the field checked on some of the rays.
TEST(UnstructuredSampler, LargeTetrahedralMesh)
{
  const int n = 47;
  auto start = std::chrono::steady_clock::now();
  Lattice lattice(
    { n, n, n }, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1), Split::Tetrahedra5);
  lattice.M.SetPointValues(Linear);
  auto built = std::chrono::steady_clock::now();
  auto sampler = lattice.M.Sampler();
  ASSERT_TRUE(sampler);
  auto indexed = std::chrono::steady_clock::now();

  const int size = 512;
  const int count = 100;
  const savr::View view = PerspectiveView(Eigen::Vector3d(1.5, -2.0, 3.5), Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(0, 1, 0), 35.0, size, size, 0.5, 20.0);
  std::vector<float> samples(static_cast<std::size_t>(size) * size * count);
  std::vector<double> starts(static_cast<std::size_t>(size) * size, 0.0);
  std::vector<double> steps(static_cast<std::size_t>(size) * size, 0.0);
  for (int frame = 0; frame < 2; ++frame)
  {
    auto begin = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<int>(0, size * size, 256),
      [&](const tbb::blocked_range<int>& range)
      {
        for (int p = range.begin(); p < range.end(); ++p)
        {
          const savr::Ray ray = view.PixelRay(p % size, p / size);
          double t0;
          double t1;
          if (!sampler->Clip(ray, t0, t1))
          {
            continue;
          }
          const double dt = (t1 - t0) / count;
          starts[p] = t0 + 0.5 * dt;
          steps[p] = dt;
          sampler->SampleRay(ray, starts[p], dt, count, samples.data() + std::size_t(p) * count);
        }
      });
    auto end = std::chrono::steady_clock::now();
    std::cout << "[ timing   ] " << lattice.M.Cells() << " tetrahedra: lattice "
              << std::chrono::duration<double>(built - start).count() << " s, sampler "
              << std::chrono::duration<double>(indexed - built).count() << " s; frame " << frame
              << " (" << size << "x" << size << " rays, " << count << " samples) "
              << std::chrono::duration<double>(end - begin).count() << " s" << std::endl;
  }
  int checked = 0;
  for (int p = 0; p < size * size; p += 37)
  {
    if (steps[p] == 0.0)
    {
      continue;
    }
    const savr::Ray ray = view.PixelRay(p % size, p / size);
    for (int i = 0; i < count; ++i)
    {
      const Eigen::Vector3d x = ray.At(starts[p] + i * steps[p]);
      const int where = lattice.Classify(x, 1e-6);
      const float v = samples[std::size_t(p) * count + i];
      if (where > 0)
      {
        ++checked;
        ASSERT_NEAR(v, Linear(x), 1e-5 * (1 + std::abs(Linear(x)))) << p << " " << i;
      }
      else if (where < 0)
      {
        ASSERT_TRUE(std::isnan(v)) << p << " " << i;
      }
    }
  }
  EXPECT_GT(checked, 50000);
}

// Rays from outside find their first cell among the cells on the mesh's boundary. A flat
// tetrahedron lying on a tetrahedron's face (rays never walk into it) leaves that face the
// boundary, and rays through it still sample the tetrahedron behind it.
TEST(UnstructuredSampler, FirstCellBehindAFlatCellOnTheBoundary)
{
  Mesh m;
  const auto p0 = m.AddPoint(Eigen::Vector3d(0, 0, 0));
  const auto p1 = m.AddPoint(Eigen::Vector3d(1, 0, 0));
  const auto p2 = m.AddPoint(Eigen::Vector3d(0, 1, 0));
  const auto p3 = m.AddPoint(Eigen::Vector3d(0, 0, 1));
  const auto flat = m.AddPoint(Eigen::Vector3d(0.3, 0.3, 0)); // in the face p0 p1 p2
  m.AddCell(kTetra, { p0, p1, p2, p3 });
  m.AddCell(kTetra, { p0, p1, p2, flat });
  m.SetPointValues(
    [](const Eigen::Vector3d& p) { return 1.0 + p.x() + 2.0 * p.y() + 3.0 * p.z(); });
  auto sampler = m.Sampler();
  ASSERT_TRUE(sampler);
  // From below the face, up into the tetrahedron.
  savr::Ray ray;
  ray.Origin = Eigen::Vector3d(0.2, 0.2, -1.0);
  ray.Direction = Eigen::Vector3d(0, 0, 1);
  float out[3];
  sampler->SampleRay(ray, 1.1, 0.2, 3, out);
  for (int i = 0; i < 3; ++i)
  {
    const double z = 0.1 + 0.2 * i;
    EXPECT_NEAR(out[i], 1.0 + 0.2 + 0.4 + 3.0 * z, 1e-5) << "sample " << i;
  }
}

// A ray that starts inside the mesh, in a cell no boundary face touches, finds that cell: only
// rays from outside look for their first cell among the boundary's.
TEST(UnstructuredSampler, RayFromInsideFindsAnInteriorCell)
{
  Lattice lattice(
    { 3, 3, 3 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(3, 3, 3), Split::Hexahedra);
  lattice.M.SetPointValues(Linear);
  auto sampler = lattice.M.Sampler();
  ASSERT_TRUE(sampler);
  savr::Ray ray;
  ray.Origin = Eigen::Vector3d(1.4, 1.5, 1.6); // in the middle cell
  ray.Direction = Eigen::Vector3d(1, 0, 0);
  float out[6];
  sampler->SampleRay(ray, 0.0, 0.25, 6, out);
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_NEAR(out[i], Linear(ray.At(0.25 * i)), 1e-5) << "sample " << i;
  }
}

// A walk's first cell is looked for first next to the one its thread's previous walk began in
// (MeshFaces::EntersByHull), and only then in the hierarchy. The samples must not depend on that:
// rays in scan order, each entering next to the last, give the bits each ray gives after a ray
// from the far side of the mesh. On an L-shaped mesh, a ray that enters the lower arm from the
// notch is followed by one that crosses the upper arm first and enters the same cell after the
// notch: the notch's side is not on the hull, so that cell must not be taken as its first.
TEST(UnstructuredSampler, SamplesDoNotDependOnThePreviousRay)
{
  const auto field = [](const Eigen::Vector3d& p)
  { return std::sin(0.7 * p.x()) * std::cos(0.5 * p.y()) + 0.1 * p.z() * p.z(); };
  for (Split split : { Split::Tetrahedra5, Split::Hexahedra, Split::Mixed })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice = LShaped(split, 3);
    lattice.M.SetPointValues(field);
    auto sampler = lattice.M.Sampler();
    ASSERT_TRUE(sampler);
    std::vector<savr::Ray> rays;
    // A fan from in front of the face x = 0, row by row.
    const Eigen::Vector3d eye(-4.0, 2.9, 1.4);
    for (int j = 0; j < 30; ++j)
    {
      for (int i = 0; i < 30; ++i)
      {
        rays.push_back(
          MakeRay(eye, Eigen::Vector3d(0.0, -0.3 + 6.6 * i / 29, -0.2 + 3.4 * j / 29)));
      }
    }
    // Down and right: from inside the notch into the lower arm, then from above the upper arm
    // through it and the notch into the same cell of the lower arm.
    for (int k = 0; k < 20; ++k)
    {
      const double x = 3.6 + 0.1 * k;
      const double z = 0.3 + 0.12 * k;
      rays.push_back(MakeRay(Eigen::Vector3d(x - 0.5, 3.5, z), Eigen::Vector3d(x, 3.0, z)));
      rays.push_back(MakeRay(Eigen::Vector3d(x - 3.5, 6.5, z), Eigen::Vector3d(x, 3.0, z)));
    }
    const savr::Ray away = MakeRay(Eigen::Vector3d(1.5, 1.5, 9.0), Eigen::Vector3d(1.6, 1.4, 0.0));
    const int count = 120;
    const double dt = 0.1;
    std::vector<float> scan(rays.size() * count);
    std::vector<float> alone(rays.size() * count);
    std::vector<float> other(count);
    for (std::size_t r = 0; r < rays.size(); ++r)
    {
      sampler->SampleRay(rays[r], 0.0, dt, count, scan.data() + r * count);
    }
    for (std::size_t r = 0; r < rays.size(); ++r)
    {
      sampler->SampleRay(away, 0.0, dt, count, other.data());
      sampler->SampleRay(rays[r], 0.0, dt, count, alone.data() + r * count);
    }
    EXPECT_TRUE(SameBits(scan, alone));
    int finite = 0;
    for (std::size_t k = 0; k < scan.size(); ++k)
    {
      const savr::Ray& ray = rays[k / count];
      const Eigen::Vector3d p = ray.At(dt * static_cast<double>(k % count));
      if (lattice.Classify(p, 1e-6) > 0)
      {
        ++finite;
        ASSERT_NEAR(scan[k], field(p), 0.15) << p.transpose();
      }
    }
    EXPECT_GT(finite, 15000);
  }
}

// Rays sampled together (their walks' steps in turn) give each ray's samples alone, bit for bit:
// rays of different lengths and starts, through the notch (walks that search again), and rays
// that miss the mesh or take no samples, two to six at a time (more than a group).
TEST(UnstructuredSampler, RayGroupsGiveEachRaysSamples)
{
  const auto field = [](const Eigen::Vector3d& p)
  { return std::cos(0.6 * p.x()) + 0.3 * p.y() - 0.2 * p.z() * p.x(); };
  for (Split split : { Split::Tetrahedra5, Split::Hexahedra, Split::Mixed })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice = LShaped(split, 3);
    lattice.M.SetPointValues(field);
    auto sampler = lattice.M.Sampler();
    ASSERT_TRUE(sampler);
    std::vector<savr::Ray> rays;
    const Eigen::Vector3d eye(-4.0, 2.9, 1.4);
    for (int k = 0; k < 60; ++k)
    {
      rays.push_back(MakeRay(eye, Eigen::Vector3d(0.0, -0.3 + 0.11 * k, 0.1 + 0.045 * k)));
      const double x = 3.6 + 0.04 * k;
      const double z = 0.3 + 0.04 * k;
      rays.push_back(MakeRay(Eigen::Vector3d(x - 3.5, 6.5, z), Eigen::Vector3d(x, 3.0, z)));
    }
    rays.push_back(MakeRay(Eigen::Vector3d(1.5, 1.5, 9.0), Eigen::Vector3d(1.6, 1.4, 8.0)));
    const double dt = 0.1;
    const int most = 140;
    int compared = 0;
    for (std::size_t a = 0; a < rays.size(); ++a)
    {
      const int n = 2 + static_cast<int>(a % 5);
      savr::Sampler::RayPiece pieces[6];
      std::vector<std::vector<float>> together(n, std::vector<float>(most, -1.0f));
      std::vector<std::vector<float>> alone(n, std::vector<float>(most, -1.0f));
      for (int g = 0; g < n; ++g)
      {
        const std::size_t r = (a + 37 * g + 5 * g * g) % rays.size();
        const int count = (r + g) % 11 == 5 ? 0 : most - static_cast<int>((r * (g + 1)) % 110);
        const double t0 = 0.02 * static_cast<double>(r % 4) + 0.3 * g;
        pieces[g] = { &rays[r], t0, count, together[g].data() };
        sampler->SampleRay(rays[r], t0, dt, count, alone[g].data());
      }
      sampler->SampleRays(pieces, n, dt);
      for (int g = 0; g < n; ++g)
      {
        ASSERT_TRUE(SameBits(together[g], alone[g])) << a << " " << g;
        for (int i = 0; i < pieces[g].Count; ++i)
        {
          compared += together[g][i] == together[g][i] ? 1 : 0;
        }
      }
    }
    EXPECT_GT(compared, 5000);
  }
}

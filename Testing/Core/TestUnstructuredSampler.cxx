// The unstructured-mesh sampler against closed forms: every linear cell interpolates a linear
// field exactly, so samples must equal the field inside the mesh and be NaN outside it.
#include "TestHelpers.h"
#include "UnstructuredSampler.h"

#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <chrono>
#include <cstring>
#include <iostream>
#include <random>

using namespace savr_test;

namespace
{

enum class Split
{
  Hexahedra,
  Voxels,
  Tetrahedra5,
  Tetrahedra6,
  Wedges,
  Pyramids,
  Mixed
};

const char* Name(Split split)
{
  switch (split)
  {
    case Split::Hexahedra:
      return "hexahedra";
    case Split::Voxels:
      return "voxels";
    case Split::Tetrahedra5:
      return "5 tetrahedra";
    case Split::Tetrahedra6:
      return "6 tetrahedra";
    case Split::Wedges:
      return "wedges";
    case Split::Pyramids:
      return "pyramids";
    case Split::Mixed:
      return "mixed";
  }
  return "";
}

constexpr std::uint8_t kTetra = 10;
constexpr std::uint8_t kVoxel = 11;
constexpr std::uint8_t kHexahedron = 12;
constexpr std::uint8_t kWedge = 13;
constexpr std::uint8_t kPyramid = 14;

double Linear(const Eigen::Vector3d& p)
{
  return 1.5 + 2.0 * p.x() - 0.7 * p.y() + 0.4 * p.z();
}
const Eigen::Vector3d kLinearGradient(2.0, -0.7, 0.4);

/// A mesh in VTK's layout, built by the tests.
struct Mesh
{
  std::vector<double> Points;
  std::vector<std::int64_t> Offsets = { 0 };
  std::vector<std::int64_t> Connectivity;
  std::vector<std::uint8_t> Types;
  std::vector<float> Values; // per point, or per cell for cell data

  std::int64_t AddPoint(const Eigen::Vector3d& p)
  {
    this->Points.insert(this->Points.end(), { p.x(), p.y(), p.z() });
    return static_cast<std::int64_t>(this->Points.size() / 3 - 1);
  }
  Eigen::Vector3d Point(std::int64_t id) const
  {
    return Eigen::Vector3d(
      this->Points[3 * id], this->Points[3 * id + 1], this->Points[3 * id + 2]);
  }
  void AddCell(std::uint8_t type, std::initializer_list<std::int64_t> ids)
  {
    this->Connectivity.insert(this->Connectivity.end(), ids);
    this->Offsets.push_back(static_cast<std::int64_t>(this->Connectivity.size()));
    this->Types.push_back(type);
  }
  std::size_t Cells() const { return this->Types.size(); }
  void SetPointValues(const std::function<double(const Eigen::Vector3d&)>& f)
  {
    this->Values.resize(this->Points.size() / 3);
    for (std::size_t i = 0; i < this->Values.size(); ++i)
    {
      this->Values[i] = static_cast<float>(f(this->Point(static_cast<std::int64_t>(i))));
    }
  }
  savr::UnstructuredDescription Description(bool cellData = false) const
  {
    savr::UnstructuredDescription d;
    d.Points = this->Points.data();
    d.NumberOfPoints = this->Points.size() / 3;
    d.Offsets = this->Offsets.data();
    d.Connectivity = this->Connectivity.data();
    d.Types = this->Types.data();
    d.NumberOfCells = this->Types.size();
    d.Values = this->Values.data();
    d.CellData = cellData;
    return d;
  }
  std::shared_ptr<const savr::Sampler> Sampler(bool cellData = false) const
  {
    std::string error;
    auto sampler = savr::MakeUnstructuredSampler(this->Description(cellData), error);
    EXPECT_TRUE(sampler) << error;
    return sampler;
  }
};

/// The box [lo, hi] cut into n[0] x n[1] x n[2] lattice cells, those for which `keep` holds
/// split into cells of `split`. Interior lattice points move by up to `jitter` cell sizes.
struct Lattice
{
  std::array<int, 3> N;
  Eigen::Vector3d Lo;
  Eigen::Vector3d Hi;
  std::function<bool(int, int, int)> Keep;
  Mesh M;

  Lattice(std::array<int, 3> n, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Split split,
    std::function<bool(int, int, int)> keep = nullptr, double jitter = 0.0)
    : N(n)
    , Lo(lo)
    , Hi(hi)
    , Keep(keep ? keep : [](int, int, int) { return true; })
  {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> shake(-jitter, jitter);
    const Eigen::Vector3d h = this->Spacing();
    for (int k = 0; k <= n[2]; ++k)
      for (int j = 0; j <= n[1]; ++j)
        for (int i = 0; i <= n[0]; ++i)
        {
          Eigen::Vector3d p = lo + Eigen::Vector3d(i * h.x(), j * h.y(), k * h.z());
          const bool interior = i > 0 && i < n[0] && j > 0 && j < n[1] && k > 0 && k < n[2];
          if (jitter > 0.0 && interior)
          {
            p +=
              Eigen::Vector3d(shake(random) * h.x(), shake(random) * h.y(), shake(random) * h.z());
          }
          this->M.AddPoint(p);
        }
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
        {
          if (!this->Keep(i, j, k))
          {
            continue;
          }
          Split s = split;
          if (split == Split::Mixed)
          {
            const Split kinds[6] = { Split::Hexahedra, Split::Tetrahedra5, Split::Wedges,
              Split::Pyramids, Split::Tetrahedra6, Split::Voxels };
            s = kinds[(i + 2 * j + 3 * k) % (jitter > 0.0 ? 5 : 6)];
          }
          this->AddHex(i, j, k, s);
        }
  }

  Eigen::Vector3d Spacing() const
  {
    return (this->Hi - this->Lo).cwiseQuotient(Eigen::Vector3d(this->N[0], this->N[1], this->N[2]));
  }

  std::int64_t Node(int i, int j, int k) const
  {
    return i + (this->N[0] + 1) * (j + (this->N[1] + 1) * static_cast<std::int64_t>(k));
  }

  void AddHex(int i, int j, int k, Split split)
  {
    std::int64_t c[8]; // lattice order: corner (a, b, c) is a + 2 b + 4 c
    for (int b = 0; b < 8; ++b)
    {
      c[b] = this->Node(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
    }
    switch (split)
    {
      case Split::Hexahedra:
      case Split::Mixed:
        this->M.AddCell(kHexahedron, { c[0], c[1], c[3], c[2], c[4], c[5], c[7], c[6] });
        break;
      case Split::Voxels:
        this->M.AddCell(kVoxel, { c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7] });
        break;
      case Split::Tetrahedra6:
      {
        // Around the diagonal 0-7, the same in every lattice cell: conforming.
        const int axes[6][3] = { { 0, 1, 2 }, { 0, 2, 1 }, { 1, 0, 2 }, { 1, 2, 0 }, { 2, 0, 1 },
          { 2, 1, 0 } };
        for (const auto& a : axes)
        {
          const int b1 = 1 << a[0];
          const int b2 = b1 | (1 << a[1]);
          this->M.AddCell(kTetra, { c[0], c[b1], c[b2], c[7] });
        }
        break;
      }
      case Split::Tetrahedra5:
      {
        // A central tetrahedron on the corners of one parity and four around it; the parity
        // alternates between lattice cells so that their face diagonals agree.
        const bool even = ((i + j + k) & 1) == 0;
        const int central[2][4] = { { 1, 2, 4, 7 }, { 0, 3, 5, 6 } };
        const int* centre = central[even ? 0 : 1];
        const int* corners = central[even ? 1 : 0];
        this->M.AddCell(kTetra, { c[centre[0]], c[centre[1]], c[centre[2]], c[centre[3]] });
        for (int v = 0; v < 4; ++v)
        {
          const int b = corners[v];
          this->M.AddCell(kTetra, { c[b], c[b ^ 1], c[b ^ 2], c[b ^ 4] });
        }
        break;
      }
      case Split::Wedges:
        // The lattice cell's bottom quad cut along 0-3, extruded along z.
        this->M.AddCell(kWedge, { c[0], c[1], c[3], c[4], c[5], c[7] });
        this->M.AddCell(kWedge, { c[0], c[3], c[2], c[4], c[7], c[6] });
        break;
      case Split::Pyramids:
      {
        Eigen::Vector3d centre = Eigen::Vector3d::Zero();
        for (int b = 0; b < 8; ++b)
        {
          centre += this->M.Point(c[b]) / 8.0;
        }
        const std::int64_t apex = this->M.AddPoint(centre);
        const int faces[6][4] = { { 0, 2, 6, 4 }, { 1, 5, 7, 3 }, { 0, 4, 5, 1 }, { 2, 3, 7, 6 },
          { 0, 1, 3, 2 }, { 4, 6, 7, 5 } };
        for (const auto& f : faces)
        {
          this->M.AddCell(kPyramid, { c[f[0]], c[f[1]], c[f[2]], c[f[3]], apex });
        }
        break;
      }
    }
  }

  /// +1 when p is inside the kept lattice cells by `margin`, -1 when it is that far outside
  /// them, 0 in between (for lattices without jitter, or with it only inside a full box).
  int Classify(const Eigen::Vector3d& p, double margin) const
  {
    const Eigen::Vector3d h = this->Spacing();
    int lo[3];
    int hi[3];
    bool any = false;
    bool all = true;
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = static_cast<int>(std::floor((p[a] - margin - this->Lo[a]) / h[a]));
      hi[a] = static_cast<int>(std::floor((p[a] + margin - this->Lo[a]) / h[a]));
    }
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i)
        {
          const bool in = i >= 0 && j >= 0 && k >= 0 && i < this->N[0] && j < this->N[1] &&
                          k < this->N[2] && this->Keep(i, j, k);
          any = any || in;
          all = all && in;
        }
    return all ? 1 : (any ? 0 : -1);
  }
};

savr::Ray MakeRay(const Eigen::Vector3d& from, const Eigen::Vector3d& to)
{
  savr::Ray ray;
  ray.origin = from;
  ray.direction = (to - from).normalized();
  return ray;
}

/// Random rays from a sphere around the box through points of the box (grown a little).
std::vector<savr::Ray> RandomRays(
  const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n, unsigned seed, double& length)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  const double radius = 1.5 * (hi - lo).norm();
  length = 2.0 * radius;
  std::vector<savr::Ray> rays;
  for (int r = 0; r < n; ++r)
  {
    const Eigen::Vector3d from =
      centre + radius * Eigen::Vector3d(g(random), g(random), g(random)).normalized();
    Eigen::Vector3d to;
    for (int a = 0; a < 3; ++a)
    {
      to[a] = lo[a] + (hi[a] - lo[a]) * (-0.1 + 1.2 * u(random));
    }
    rays.push_back(MakeRay(from, to));
  }
  return rays;
}

/// Samples random rays and checks them against the field inside and NaN outside.
void CheckLinear(const savr::Sampler& sampler, const Lattice& lattice, int rays, unsigned seed)
{
  double length;
  const auto all = RandomRays(lattice.Lo, lattice.Hi, rays, seed, length);
  const int count = 301;
  const double dt = length / (count - 1);
  const double margin = 1e-6 * (lattice.Hi - lattice.Lo).norm();
  std::vector<float> out(count);
  int inside = 0;
  int outside = 0;
  int failures = 0;
  for (const savr::Ray& ray : all)
  {
    // A random start within one step, as the renderer's offsets
    const double t0 = dt * std::fmod(0.618 * (&ray - all.data()), 1.0);
    sampler.SampleRay(ray, t0, dt, count, out.data());
    for (int i = 0; i < count; ++i)
    {
      const Eigen::Vector3d p = ray.At(t0 + i * dt);
      const int where = lattice.Classify(p, margin);
      if (where > 0)
      {
        ++inside;
        const double f = Linear(p);
        if (!(std::abs(out[i] - f) <= 1e-5 * (1.0 + std::abs(f))) && failures++ < 5)
        {
          ADD_FAILURE() << "inside at (" << p.transpose() << "): " << out[i] << " instead of " << f;
        }
      }
      else if (where < 0)
      {
        ++outside;
        if (!std::isnan(out[i]) && failures++ < 5)
        {
          ADD_FAILURE() << "outside at (" << p.transpose() << "): " << out[i] << " instead of NaN";
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(inside, rays * 20) << "the rays must cross the mesh";
  EXPECT_GT(outside, rays * 20);
}

const Split kAllSplits[] = { Split::Hexahedra, Split::Voxels, Split::Tetrahedra5,
  Split::Tetrahedra6, Split::Wedges, Split::Pyramids, Split::Mixed };

bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

} // namespace

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

// A block of cells removed from the middle of a box: rays leave the mesh into the hole and come
// back out of it.
TEST(UnstructuredSampler, HoleReadsNaNWithValuesOnBothSides)
{
  auto keep = [](int i, int j, int k)
  { return !(i >= 2 && i < 4 && j >= 2 && j < 4 && k >= 2 && k < 4); };
  for (Split split : { Split::Hexahedra, Split::Tetrahedra5, Split::Pyramids, Split::Mixed })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice({ 6, 6, 6 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(6, 6, 6), split, keep);
    lattice.M.SetPointValues(Linear);
    auto sampler = lattice.M.Sampler();
    ASSERT_TRUE(sampler);
    // Along x through the hole: inside on [0, 2] and [4, 6], NaN on (2, 4) and outside.
    const savr::Ray ray = MakeRay(Eigen::Vector3d(-1, 3.3, 2.7), Eigen::Vector3d(0, 3.3, 2.7));
    std::vector<float> out(81);
    sampler->SampleRay(ray, 0.05, 0.1, 81, out.data());
    int before = 0;
    int after = 0;
    for (int i = 0; i < 81; ++i)
    {
      const Eigen::Vector3d p = ray.At(0.05 + i * 0.1);
      const bool inside = (p.x() > 0 && p.x() < 2) || (p.x() > 4 && p.x() < 6);
      if (inside)
      {
        EXPECT_NEAR(out[i], Linear(p), 1e-5 * (1 + std::abs(Linear(p)))) << p.x();
        before += p.x() < 2;
        after += p.x() > 4;
      }
      else
      {
        EXPECT_TRUE(std::isnan(out[i])) << p.x() << ": " << out[i];
      }
    }
    EXPECT_EQ(before, 20);
    EXPECT_EQ(after, 20);
    CheckLinear(*sampler, lattice, 300, 21);
  }
}

// An L-shaped mesh: a ray leaves one arm, crosses the notch and enters the other arm.
TEST(UnstructuredSampler, NonConvexMeshReadsNaNInTheNotch)
{
  auto keep = [](int i, int j, int) { return !(i >= 3 && j >= 3); };
  for (Split split : { Split::Hexahedra, Split::Tetrahedra6, Split::Wedges })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice({ 6, 6, 2 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(6, 6, 2), split, keep);
    lattice.M.SetPointValues(Linear);
    auto sampler = lattice.M.Sampler();
    ASSERT_TRUE(sampler);
    // From (2, 5.5) along (1, -1): arm x < 3 until x = 3, the notch until y = 3 (x = 4.5), then
    // the arm y < 3 until x = 6.
    const savr::Ray ray = MakeRay(Eigen::Vector3d(2, 5.5, 1.1), Eigen::Vector3d(3, 4.5, 1.1));
    const int count = 80;
    const double dt = std::sqrt(2.0) * 4.0 / count;
    std::vector<float> out(count);
    sampler->SampleRay(ray, 0.5 * dt, dt, count, out.data());
    int inArms = 0;
    int inNotch = 0;
    for (int i = 0; i < count; ++i)
    {
      const Eigen::Vector3d p = ray.At((i + 0.5) * dt);
      const int where = lattice.Classify(p, 1e-6);
      if (where > 0)
      {
        ++inArms;
        EXPECT_NEAR(out[i], Linear(p), 1e-5 * (1 + std::abs(Linear(p)))) << p.transpose();
      }
      else if (where < 0)
      {
        inNotch += p.x() < 4.5;
        EXPECT_TRUE(std::isnan(out[i])) << p.transpose();
      }
    }
    EXPECT_GT(inArms, 40);
    EXPECT_GT(inNotch, 20);
    CheckLinear(*sampler, lattice, 300, 31);
  }
}

// Zero-volume cells (flat, repeated points, collapsed to a point) and duplicated cells inside a
// mesh: sampling finishes and reads the field everywhere else.
TEST(UnstructuredSampler, DegenerateCellsDoNotHang)
{
  Lattice lattice(
    { 4, 4, 4 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 4, 4), Split::Hexahedra);
  Mesh& m = lattice.M;
  auto n = [&](int i, int j, int k) { return lattice.Node(i, j, k); };
  // flat hexahedron on the face z = 2 of a lattice cell
  m.AddCell(kHexahedron, { n(1, 1, 2), n(2, 1, 2), n(2, 2, 2), n(1, 2, 2), n(1, 1, 2), n(2, 1, 2),
                           n(2, 2, 2), n(1, 2, 2) });
  // tetrahedra with repeated points, and with four coplanar points
  m.AddCell(kTetra, { n(2, 2, 2), n(2, 2, 2), n(2, 2, 2), n(3, 2, 2) });
  m.AddCell(kTetra, { n(2, 0, 0), n(2, 1, 0), n(2, 0, 1), n(2, 1, 1) });
  // a hexahedron collapsed to one point, a flat pyramid, a flat voxel and a flat wedge
  m.AddCell(kHexahedron, { n(3, 3, 3), n(3, 3, 3), n(3, 3, 3), n(3, 3, 3), n(3, 3, 3), n(3, 3, 3),
                           n(3, 3, 3), n(3, 3, 3) });
  m.AddCell(kPyramid, { n(1, 1, 1), n(2, 1, 1), n(2, 2, 1), n(1, 2, 1), n(1, 1, 1) });
  m.AddCell(kVoxel, { n(2, 2, 3), n(3, 2, 3), n(2, 3, 3), n(3, 3, 3), n(2, 2, 3), n(3, 2, 3),
                      n(2, 3, 3), n(3, 3, 3) });
  m.AddCell(kWedge, { n(0, 0, 1), n(1, 0, 1), n(0, 1, 1), n(0, 0, 1), n(1, 0, 1), n(0, 1, 1) });
  // the same hexahedron twice
  m.AddCell(kHexahedron, { n(1, 2, 1), n(2, 2, 1), n(2, 3, 1), n(1, 3, 1), n(1, 2, 2), n(2, 2, 2),
                           n(2, 3, 2), n(1, 3, 2) });
  m.SetPointValues(Linear);
  auto sampler = m.Sampler();
  ASSERT_TRUE(sampler);
  CheckLinear(*sampler, lattice, 400, 41);
  // Rays through the degenerate cells' planes, along the lattice's axes and diagonals.
  std::vector<float> out(60);
  for (const Eigen::Vector3d& d : { Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1),
         Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0, 1, 1) })
  {
    const savr::Ray ray = MakeRay(Eigen::Vector3d(2, 2, 2) - 3.0 * d, Eigen::Vector3d(2, 2, 2));
    sampler->SampleRay(ray, 0.0, 0.1, 60, out.data());
    for (int i = 0; i < 60; ++i)
    {
      const Eigen::Vector3d p = ray.At(0.1 * i);
      if (lattice.Classify(p, 1e-6) > 0)
      {
        EXPECT_NEAR(out[i], Linear(p), 1e-5 * (1 + std::abs(Linear(p)))) << p.transpose();
      }
    }
  }

  // Only degenerate cells: a sampler that reads NaN everywhere.
  Mesh flat;
  for (const Eigen::Vector3d& p : { Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
         Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 1, 0) })
  {
    flat.AddPoint(p);
  }
  flat.AddCell(kTetra, { 0, 1, 2, 3 });
  flat.AddCell(kHexahedron, { 0, 1, 3, 2, 0, 1, 3, 2 });
  flat.SetPointValues(Linear);
  auto none = flat.Sampler();
  ASSERT_TRUE(none);
  sampler = nullptr;
  const savr::Ray ray = MakeRay(Eigen::Vector3d(0.3, 0.4, -1), Eigen::Vector3d(0.3, 0.4, 0));
  out.resize(200);
  none->SampleRay(ray, 0.0, 0.01, 200, out.data());
  for (float v : out)
  {
    EXPECT_TRUE(std::isnan(v));
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

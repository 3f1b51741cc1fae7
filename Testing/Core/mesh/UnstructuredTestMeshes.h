#pragma once
// Unstructured meshes for the sampler's tests: boxes cut into cells of every kind, optionally
// distorted or with cells left out, with a linear field that every linear cell interpolates
// exactly, and the checks that rely on it.

#include "TestHelpers.h"
#include "mesh/UnstructuredDescription.h"

#include <gtest/gtest.h>

#include <random>

namespace savr_test
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

inline const char* Name(Split split)
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

inline double Linear(const Eigen::Vector3d& p)
{
  return 1.5 + 2.0 * p.x() - 0.7 * p.y() + 0.4 * p.z();
}
inline const Eigen::Vector3d kLinearGradient(2.0, -0.7, 0.4);

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

/// The 6 x 6 x `layers` unit lattice without its cells i, j >= 3: an L whose notch's sides have no
/// cell across and are not on the convex hull.
inline Lattice LShaped(Split split, int layers)
{
  return Lattice({ 6, 6, layers }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(6, 6, layers), split,
    [](int i, int j, int) { return !(i >= 3 && j >= 3); });
}

inline savr::Ray MakeRay(const Eigen::Vector3d& from, const Eigen::Vector3d& to)
{
  savr::Ray ray;
  ray.Origin = from;
  ray.Direction = (to - from).normalized();
  return ray;
}

/// Random rays from a sphere around the box through points of the box (grown a little).
inline std::vector<savr::Ray> RandomRays(
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
inline void CheckLinear(
  const savr::Sampler& sampler, const Lattice& lattice, int rays, unsigned seed)
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

inline const Split kAllSplits[] = { Split::Hexahedra, Split::Voxels, Split::Tetrahedra5,
  Split::Tetrahedra6, Split::Wedges, Split::Pyramids, Split::Mixed };

} // namespace savr_test

// The unstructured sampler where the mesh's faces matter: holes, concavities, and degenerate or
// duplicated cells that the walk across shared faces must step around.
#include "UnstructuredTestMeshes.h"

#include <gtest/gtest.h>

using namespace savr_test;

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

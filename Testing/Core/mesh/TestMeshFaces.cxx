// The mesh's faces: on their own (adjacency, planes, degenerate and non-convex cells), and in the
// sampler where they matter (holes, concavities, and degenerate or duplicated cells that the walk
// across shared faces must step around).
#include "mesh/MeshFaces.h"
#include "mesh/UnstructuredTestMeshes.h"

#include <gtest/gtest.h>

using namespace savr_test;

namespace
{

using savr::unstructured::kNoFace;
using savr::unstructured::kNone;
using savr::unstructured::Line;
using savr::unstructured::MeshFaces;
using savr::unstructured::Side;

// The faces of `mesh`'s cells, kept in the mesh's order.
MeshFaces FacesOf(const Mesh& mesh)
{
  std::vector<std::size_t> cells(mesh.Types.size());
  for (std::size_t c = 0; c < cells.size(); ++c)
  {
    cells[c] = c;
  }
  return MeshFaces(mesh.Description(), cells, 1e-9);
}

int SideCount(const MeshFaces& faces, std::uint32_t cell)
{
  return static_cast<int>(faces.FirstSide(cell + 1) - faces.FirstSide(cell));
}

// Two tetrahedra on either side of the triangle 1, 2, 3.
Mesh TwoTetrahedra()
{
  Mesh mesh;
  mesh.AddPoint(Eigen::Vector3d(0, 0, 0));
  mesh.AddPoint(Eigen::Vector3d(1, 0, 0));
  mesh.AddPoint(Eigen::Vector3d(0, 1, 0));
  mesh.AddPoint(Eigen::Vector3d(0, 0, 1));
  mesh.AddPoint(Eigen::Vector3d(1, 1, 1));
  mesh.AddCell(kTetra, { 0, 1, 2, 3 });
  mesh.AddCell(kTetra, { 1, 2, 3, 4 });
  mesh.SetPointValues(Linear);
  return mesh;
}

} // namespace

TEST(MeshFaces, EverySidePointsOutOfItsCell)
{
  const Mesh mesh = TwoTetrahedra();
  const MeshFaces faces = FacesOf(mesh);
  for (std::uint32_t cell = 0; cell < 2; ++cell)
  {
    ASSERT_EQ(SideCount(faces, cell), 4);
    const Eigen::Vector3d centre = faces.Centre(cell);
    for (const Side* side = faces.FirstSide(cell); side != faces.FirstSide(cell + 1); ++side)
    {
      const Eigen::Vector3d n(side->N[0], side->N[1], side->N[2]);
      EXPECT_NEAR(n.norm(), 1.0, 1e-15);
      EXPECT_LT(n.dot(centre) - side->D, -0.05) << "cell " << cell;
    }
    EXPECT_TRUE(faces.Contains(cell, centre, false));
    EXPECT_FALSE(faces.IsDegenerate(cell));
    EXPECT_FALSE(faces.IsNonConvex(cell));
  }
  EXPECT_FALSE(faces.Contains(0, faces.Centre(1), false));
}

// A line through the shared triangle leaves the first cell where it enters the second: the
// second cell's side is the exact negation of the first's.
TEST(MeshFaces, SharedFaceJoinsTheCellsExactly)
{
  const Mesh mesh = TwoTetrahedra();
  const MeshFaces faces = FacesOf(mesh);
  const Line line(faces.Centre(0), faces.Centre(1) - faces.Centre(0));
  std::uint32_t exit = kNone;
  const double tOut = faces.Exit(0, line, kNoFace, 0.0, exit);
  ASSERT_NE(exit, kNone);
  const Side& leaving = faces.SideAt(exit);
  ASSERT_EQ(leaving.Neighbour, 1);
  EXPECT_GT(tOut, 0.0);
  EXPECT_LT(tOut, 1.0);
  int matches = 0;
  for (const Side* side = faces.FirstSide(1); side != faces.FirstSide(2); ++side)
  {
    if (side->Neighbour == 0)
    {
      ++matches;
      EXPECT_EQ(side->Face, leaving.NeighbourFace);
      EXPECT_EQ(side->NeighbourFace, leaving.Face);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_EQ(side->N[a], -leaving.N[a]);
      }
      EXPECT_EQ(side->D, -leaving.D);
    }
    else
    {
      EXPECT_EQ(side->Neighbour, -1); // the boundary
    }
  }
  EXPECT_EQ(matches, 1);
  // In the second cell, skipping the face it came in by, the line leaves through the boundary.
  std::uint32_t next = kNone;
  const double tNext = faces.Exit(1, line, leaving.NeighbourFace, tOut, next);
  ASSERT_NE(next, kNone);
  EXPECT_EQ(faces.SideAt(next).Neighbour, -1);
  EXPECT_GT(tNext, tOut);
  // The interval of each cell along the line ends and begins at the shared face.
  double a;
  double b;
  ASSERT_TRUE(faces.Interval(0, line, 0.0, false, a, b));
  EXPECT_EQ(b, tOut);
  ASSERT_TRUE(faces.Interval(1, line, 0.0, false, a, b));
  EXPECT_EQ(a, tOut);
  EXPECT_EQ(b, tNext);
}

TEST(MeshFaces, FlatCellsAreDegenerateAndHaveNoSides)
{
  Mesh mesh = TwoTetrahedra();
  mesh.AddPoint(Eigen::Vector3d(0.5, 0.5, 0)); // in the plane of points 0, 1, 2
  mesh.AddCell(kTetra, { 0, 1, 2, 5 });
  mesh.AddCell(kTetra, { 0, 1, 1, 3 }); // a repeated point
  mesh.SetPointValues(Linear);
  const MeshFaces faces = FacesOf(mesh);
  for (std::uint32_t cell : { 2u, 3u })
  {
    EXPECT_TRUE(faces.IsDegenerate(cell)) << cell;
    EXPECT_EQ(SideCount(faces, cell), 0) << cell;
  }
  // The first cell's face on the flat one stays on the boundary.
  for (const Side* side = faces.FirstSide(0); side != faces.FirstSide(1); ++side)
  {
    EXPECT_NE(side->Neighbour, 2);
    EXPECT_NE(side->Neighbour, 3);
  }
}

// A line from outside may take a cell as the mesh's first only through a hull side, after where
// it starts, and well inside that side's triangle; the parameter is Interval's, bit for bit.
TEST(MeshFaces, EntersByHullOnlyThroughAHullSideInsideItsTriangle)
{
  MeshFaces faces = FacesOf(TwoTetrahedra());
  std::uint32_t below = kNone; // cell 0's side on the plane z = 0
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(SideCount(faces, 0)); ++k)
  {
    below = faces.FirstSide(0)[k].N[2] < -0.99 ? k : below;
  }
  ASSERT_NE(below, kNone);
  const Line up(Eigen::Vector3d(0.2, 0.3, -1.0), Eigen::Vector3d(0, 0, 1));
  double tIn = 0.0;
  EXPECT_FALSE(faces.EntersByHull(0, up, 0.0, tIn)); // an open side, not known to be on the hull
  faces.SetHullSide(below);
  ASSERT_TRUE(faces.EntersByHull(0, up, 0.0, tIn));
  double a;
  double b;
  ASSERT_TRUE(faces.Interval(0, up, 0.0, false, a, b));
  EXPECT_EQ(tIn, a);
  EXPECT_DOUBLE_EQ(tIn, 1.0);
  EXPECT_FALSE(faces.EntersByHull(0, up, 1.0, tIn)); // starts on the side: not from outside
  EXPECT_FALSE(faces.EntersByHull(1, up, 0.0, tIn)); // the cell behind
  // Through the edge x = 0 of the side, and just outside it.
  const Line edge(Eigen::Vector3d(0.0, 0.3, -1.0), Eigen::Vector3d(0, 0, 1));
  EXPECT_FALSE(faces.EntersByHull(0, edge, 0.0, tIn));
  const Line beside(Eigen::Vector3d(-0.01, 0.3, -1.0), Eigen::Vector3d(0, 0, 1));
  EXPECT_FALSE(faces.EntersByHull(0, beside, 0.0, tIn));
  // Entering by another side first (the face x = 0, not marked): no.
  const Line slanted(Eigen::Vector3d(-0.5, 0.3, 0.3), Eigen::Vector3d(1.0, 0.0, -0.2));
  EXPECT_FALSE(faces.EntersByHull(0, slanted, 0.0, tIn));
}

// A unit cube whose top corner 6 is pushed down into it: corner 7 lies outside the plane of the
// top face's triangle 4, 5, 6.
TEST(MeshFaces, DentedHexahedronIsNonConvex)
{
  for (double dent : { 0.0, 0.5 })
  {
    Mesh mesh;
    const double corners[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 },
      { 1, 0, 1 }, { 1, 1, 1 - dent }, { 0, 1, 1 } };
    for (const auto& x : corners)
    {
      mesh.AddPoint(Eigen::Vector3d(x[0], x[1], x[2]));
    }
    mesh.AddCell(kHexahedron, { 0, 1, 2, 3, 4, 5, 6, 7 });
    mesh.SetPointValues(Linear);
    const MeshFaces faces = FacesOf(mesh);
    EXPECT_EQ(faces.IsNonConvex(0), dent > 0.0) << dent;
    EXPECT_EQ(SideCount(faces, 0), 12);
    // Just under the undented top corner 7: inside either way.
    EXPECT_TRUE(faces.Contains(0, Eigen::Vector3d(0.1, 0.9, 0.9), true)) << dent;
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
  for (Split split : { Split::Hexahedra, Split::Tetrahedra6, Split::Wedges })
  {
    SCOPED_TRACE(Name(split));
    Lattice lattice = LShaped(split, 2);
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

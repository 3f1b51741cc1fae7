// The cell shapes on their own: shape functions, the parametric map and its inversion, clamping,
// and the tables of vertices and faces, for every kind of cell.

#include "mesh/CellShapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <utility>
#include <vector>

namespace
{

using savr::unstructured::CellKind;
using savr::unstructured::CellVertices;
using savr::unstructured::Polynomial;
using savr::unstructured::ShapeOf;

const CellKind kAllKinds[] = { CellKind::Tetra, CellKind::Voxel, CellKind::Hexahedron,
  CellKind::Wedge, CellKind::Pyramid };

const char* Name(CellKind kind)
{
  switch (kind)
  {
    case CellKind::Tetra:
      return "tetra";
    case CellKind::Voxel:
      return "voxel";
    case CellKind::Hexahedron:
      return "hexahedron";
    case CellKind::Wedge:
      return "wedge";
    case CellKind::Pyramid:
      return "pyramid";
  }
  return "?";
}

// Each vertex's parametric coordinates, in VTK's ordering.
std::vector<Eigen::Vector3d> Nodes(CellKind kind)
{
  switch (kind)
  {
    case CellKind::Tetra:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    case CellKind::Voxel:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 },
        { 0, 1, 1 }, { 1, 1, 1 } };
    case CellKind::Hexahedron:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 },
        { 1, 1, 1 }, { 0, 1, 1 } };
    case CellKind::Wedge:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 } };
    case CellKind::Pyramid:
      return { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  }
  return {};
}

// A cell of `kind` whose vertices are the image of its parametric nodes under an affine map
// (a parallelepiped, prism, ... : its parametric coordinates have a closed form), or, with
// `distortion`, with every vertex then moved by up to that much (they have none), voxels
// excepted.
CellVertices MakeCell(CellKind kind, double distortion, unsigned seed)
{
  Eigen::Matrix3d e;
  e << 2.0, 0.3, -0.2, 0.1, 1.5, 0.4, -0.3, 0.2, 1.2;
  if (kind == CellKind::Voxel)
  {
    // An axis-aligned box by definition: never distorted.
    e = Eigen::Vector3d(2.0, 1.5, 1.2).asDiagonal();
    distortion = 0.0;
  }
  const Eigen::Vector3d origin(0.5, -1.0, 3.0);
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> move(-distortion, distortion);
  CellVertices cell;
  cell.Kind = kind;
  cell.Points = ShapeOf(kind).Points;
  const std::vector<Eigen::Vector3d> nodes = Nodes(kind);
  for (int i = 0; i < cell.Points; ++i)
  {
    cell.X[i] = origin + e * nodes[i];
    for (int a = 0; a < 3; ++a)
    {
      cell.X[i][a] += move(random);
    }
    cell.F[i] = 0.0;
  }
  cell.Direct = savr::unstructured::HasDirectMap(kind, cell.X, 1e-10);
  return cell;
}

// Random parametric coordinates well inside the cell.
Eigen::Vector3d Inside(CellKind kind, std::mt19937& random)
{
  std::uniform_real_distribution<double> u(0.05, 0.95);
  Eigen::Vector3d r(u(random), u(random), u(random));
  if (kind == CellKind::Tetra && r.sum() > 0.95)
  {
    r *= 0.9 / r.sum();
  }
  if (kind == CellKind::Wedge && r[0] + r[1] > 0.95)
  {
    const double scale = 0.9 / (r[0] + r[1]);
    r[0] *= scale;
    r[1] *= scale;
  }
  if (kind == CellKind::Pyramid)
  {
    r[2] *= 0.9; // away from the apex, where r and s are undefined
  }
  return r;
}

Eigen::Vector3d MapOf(const Polynomial& polynomial, const Eigen::Vector3d& r)
{
  const double q[3] = { r[0], r[1], r[2] };
  Eigen::Vector3d x;
  Eigen::Matrix3d jacobian;
  polynomial.Map(q, x, jacobian);
  return x;
}

TEST(CellShapes, ShapeFunctionIsOneAtItsNodeAndZeroAtTheOthers)
{
  for (CellKind kind : kAllKinds)
  {
    CellVertices cell = MakeCell(kind, 0.0, 1);
    const std::vector<Eigen::Vector3d> nodes = Nodes(kind);
    for (int i = 0; i < cell.Points; ++i)
    {
      for (int k = 0; k < cell.Points; ++k)
      {
        cell.F[k] = k == i ? 1.0 : 0.0;
      }
      const Polynomial polynomial(cell);
      for (int j = 0; j < cell.Points; ++j)
      {
        const double r[3] = { nodes[j][0], nodes[j][1], nodes[j][2] };
        EXPECT_NEAR(polynomial.Value(r), i == j ? 1.0 : 0.0, 1e-14)
          << Name(kind) << " N" << i << " at node " << j;
      }
    }
  }
}

TEST(CellShapes, ShapeFunctionsSumToOneAndReproduceLinearFields)
{
  std::mt19937 random(7);
  for (CellKind kind : kAllKinds)
  {
    CellVertices cell = MakeCell(kind, 0.15, 2);
    for (int k = 0; k < cell.Points; ++k)
    {
      cell.F[k] = 1.0;
    }
    const Polynomial unity(cell);
    // A field linear in the world coordinates is reproduced wherever the map takes r.
    const Eigen::Vector3d slope(0.7, -1.3, 2.1);
    for (int k = 0; k < cell.Points; ++k)
    {
      cell.F[k] = 4.0 + slope.dot(cell.X[k]);
    }
    const Polynomial linear(cell);
    for (int n = 0; n < 50; ++n)
    {
      const Eigen::Vector3d r = Inside(kind, random);
      const double q[3] = { r[0], r[1], r[2] };
      EXPECT_NEAR(unity.Value(q), 1.0, 1e-13) << Name(kind);
      EXPECT_NEAR(linear.Value(q), 4.0 + slope.dot(MapOf(linear, r)), 1e-12) << Name(kind);
    }
  }
}

TEST(CellShapes, MapTakesEachNodeToItsVertex)
{
  for (CellKind kind : kAllKinds)
  {
    const CellVertices cell = MakeCell(kind, 0.2, 3);
    const Polynomial polynomial(cell);
    const std::vector<Eigen::Vector3d> nodes = Nodes(kind);
    for (int i = 0; i < cell.Points; ++i)
    {
      EXPECT_LT((MapOf(polynomial, nodes[i]) - cell.X[i]).norm(), 1e-13)
        << Name(kind) << " vertex " << i;
    }
  }
}

TEST(CellShapes, ClosedFormOnlyForCellsWithParallelOppositeEdges)
{
  for (CellKind kind : kAllKinds)
  {
    EXPECT_TRUE(MakeCell(kind, 0.0, 4).Direct) << Name(kind);
  }
  // Moved vertices: tetrahedra stay affine; the others lose their closed form.
  EXPECT_TRUE(MakeCell(CellKind::Tetra, 0.2, 4).Direct);
  for (CellKind kind : { CellKind::Hexahedron, CellKind::Wedge, CellKind::Pyramid })
  {
    EXPECT_FALSE(MakeCell(kind, 0.2, 4).Direct) << Name(kind);
  }
}

// p = x(r) for points r inside undistorted cells (closed form) and distorted ones (Newton's
// iteration), and back.
TEST(CellShapes, InversionRoundTripsInsideTheCell)
{
  std::mt19937 random(11);
  for (double distortion : { 0.0, 0.2 })
  {
    for (CellKind kind : kAllKinds)
    {
      const CellVertices cell = MakeCell(kind, distortion, 5);
      const Polynomial polynomial(cell);
      for (int n = 0; n < 100; ++n)
      {
        const Eigen::Vector3d r = Inside(kind, random);
        double found[3];
        savr::unstructured::Parametric(cell, polynomial, MapOf(polynomial, r), found);
        EXPECT_LT(
          (Eigen::Vector3d(found[0], found[1], found[2]) - r).norm(), cell.Direct ? 1e-12 : 1e-6)
          << Name(kind) << (cell.Direct ? " closed form" : " Newton") << " at " << r.transpose();
      }
    }
  }
}

// The closed form and Newton's iteration agree where both apply.
TEST(CellShapes, ClosedFormAgreesWithNewton)
{
  std::mt19937 random(13);
  for (CellKind kind : kAllKinds)
  {
    CellVertices cell = MakeCell(kind, 0.0, 6);
    ASSERT_TRUE(cell.Direct) << Name(kind);
    const Polynomial polynomial(cell);
    for (int n = 0; n < 50; ++n)
    {
      const Eigen::Vector3d p = MapOf(polynomial, Inside(kind, random));
      double direct[3];
      double newton[3];
      cell.Direct = true;
      savr::unstructured::Parametric(cell, polynomial, p, direct);
      cell.Direct = false;
      savr::unstructured::Parametric(cell, polynomial, p, newton);
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_NEAR(direct[a], newton[a], 1e-6) << Name(kind);
      }
    }
  }
}

TEST(CellShapes, ClampingKeepsCoordinatesWithinTheMargin)
{
  using savr::unstructured::ClampToCell;
  auto clamped = [](CellKind kind, Eigen::Vector3d r, double margin)
  {
    ClampToCell(kind, r.data(), margin);
    return r;
  };
  auto expectNear = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const char* what)
  { EXPECT_LT((a - b).norm(), 1e-12) << what << ": " << a.transpose() << " vs " << b.transpose(); };

  // Inside: unchanged.
  std::mt19937 random(17);
  for (CellKind kind : kAllKinds)
  {
    const Eigen::Vector3d r = Inside(kind, random);
    expectNear(clamped(kind, r, 0.0), r, Name(kind));
  }
  // Boxes: each axis on its own.
  expectNear(clamped(CellKind::Hexahedron, { -1.0, 0.5, 2.0 }, 0.0), { 0.0, 0.5, 1.0 }, "hex");
  expectNear(clamped(CellKind::Voxel, { -1.0, 0.5, 2.0 }, 0.5), { -0.5, 0.5, 1.5 }, "voxel");
  // Simplices: the excess over the diagonal face taken equally from each axis.
  expectNear(
    clamped(CellKind::Tetra, { 0.8, 0.8, 0.8 }, 0.0), { 1.0 / 3, 1.0 / 3, 1.0 / 3 }, "tetra");
  expectNear(clamped(CellKind::Wedge, { 0.9, 0.9, 0.5 }, 0.0), { 0.5, 0.5, 0.5 }, "wedge");
  expectNear(clamped(CellKind::Wedge, { 0.9, 0.9, 1.7 }, 0.5), { 0.75, 0.75, 1.5 }, "wedge, t");
  // Pyramids: never past the apex, whatever the margin.
  expectNear(clamped(CellKind::Pyramid, { 0.5, 0.5, 1.3 }, 0.5), { 0.5, 0.5, 1.0 }, "pyramid");
  expectNear(clamped(CellKind::Pyramid, { 0.5, 0.5, -0.7 }, 0.5), { 0.5, 0.5, -0.5 }, "pyramid");
}

TEST(CellShapes, VtkTypes)
{
  EXPECT_EQ(savr::unstructured::KindOf(10), static_cast<int>(CellKind::Tetra));
  EXPECT_EQ(savr::unstructured::KindOf(11), static_cast<int>(CellKind::Voxel));
  EXPECT_EQ(savr::unstructured::KindOf(12), static_cast<int>(CellKind::Hexahedron));
  EXPECT_EQ(savr::unstructured::KindOf(13), static_cast<int>(CellKind::Wedge));
  EXPECT_EQ(savr::unstructured::KindOf(14), static_cast<int>(CellKind::Pyramid));
  for (int type : { 0, 5, 9, 15, 42, 255 })
  {
    EXPECT_EQ(savr::unstructured::KindOf(static_cast<std::uint8_t>(type)), -1) << type;
  }
}

// Each kind's faces close its surface: every edge lies on exactly two faces, every vertex on a
// face, and V - E + F = 2. Each face is planar in parametric space, with its parametric
// centre inside.
TEST(CellShapes, FacesCloseTheCell)
{
  for (CellKind kind : kAllKinds)
  {
    const auto& shape = ShapeOf(kind);
    const std::vector<Eigen::Vector3d> nodes = Nodes(kind);
    std::map<std::pair<int, int>, int> edges;
    std::vector<int> seen(shape.Points, 0);
    for (int f = 0; f < shape.Faces; ++f)
    {
      const int n = shape.FaceSize[f];
      ASSERT_GE(n, 3) << Name(kind);
      for (int k = 0; k < n; ++k)
      {
        const int a = shape.Face[f][k];
        const int b = shape.Face[f][(k + 1) % n];
        ++edges[{ std::min(a, b), std::max(a, b) }];
        ++seen[a];
      }
      // Planar in parametric space.
      const Eigen::Vector3d& p0 = nodes[shape.Face[f][0]];
      const Eigen::Vector3d normal =
        (nodes[shape.Face[f][1]] - p0).cross(nodes[shape.Face[f][2]] - p0);
      for (int k = 3; k < n; ++k)
      {
        EXPECT_NEAR(normal.dot(nodes[shape.Face[f][k]] - p0), 0.0, 1e-15) << Name(kind);
      }
      // The centre lies strictly on one side of every face.
      const Eigen::Vector3d centre(shape.Centre[0], shape.Centre[1], shape.Centre[2]);
      EXPECT_GT(std::abs(normal.dot(centre - p0)), 1e-3) << Name(kind) << " face " << f;
    }
    for (const auto& edge : edges)
    {
      EXPECT_EQ(edge.second, 2) << Name(kind) << " edge " << edge.first.first << "-"
                                << edge.first.second;
    }
    for (int v = 0; v < shape.Points; ++v)
    {
      EXPECT_GE(seen[v], 3) << Name(kind) << " vertex " << v;
    }
    EXPECT_EQ(shape.Points - static_cast<int>(edges.size()) + shape.Faces, 2) << Name(kind);
  }
}

} // namespace

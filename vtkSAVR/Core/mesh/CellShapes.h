#pragma once
// The linear cells an unstructured mesh is made of (tetrahedra, voxels, hexahedra, wedges and
// pyramids) in VTK's vertex orderings: their shape functions, the map from parametric to world
// coordinates and its inversion, and the clamping of parametric coordinates to the cell.
// Inline: the walk evaluates them for every sample.

#include <Eigen/Core>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace savr
{
namespace unstructured
{

constexpr int kNewtonIterations = 20;
// Parametric coordinates may leave the cell by this much before they are clamped: quad faces
// are not planar in general, and a ray walks across their two triangles, so a sample can lie a
// little outside the cell's curved faces, where its own map extrapolates the field best.
constexpr double kParametricMargin = 0.5;

enum class CellKind : std::uint8_t
{
  Tetra,
  Voxel,
  Hexahedron,
  Wedge,
  Pyramid
};

// Vertices and faces of each kind of cell in VTK's ordering. Faces list their vertices in
// cyclic order; their orientation does not matter (outward normals are found geometrically).
struct CellShape
{
  int Points;
  int Faces;
  int FaceSize[6];
  int Face[6][4];
  double Centre[3]; // parametric centre, where Newton's iteration starts
};

constexpr CellShape kShapes[5] = {
  { 4, 4, { 3, 3, 3, 3, 0, 0 }, { { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 }, { 0, 2, 1 } },
    { 0.25, 0.25, 0.25 } },
  { 8, 6, { 4, 4, 4, 4, 4, 4 },
    { { 0, 2, 6, 4 }, { 1, 5, 7, 3 }, { 0, 4, 5, 1 }, { 2, 3, 7, 6 }, { 0, 1, 3, 2 },
      { 4, 6, 7, 5 } },
    { 0.5, 0.5, 0.5 } },
  { 8, 6, { 4, 4, 4, 4, 4, 4 },
    { { 0, 4, 7, 3 }, { 1, 2, 6, 5 }, { 0, 1, 5, 4 }, { 3, 7, 6, 2 }, { 0, 3, 2, 1 },
      { 4, 5, 6, 7 } },
    { 0.5, 0.5, 0.5 } },
  { 6, 5, { 3, 3, 4, 4, 4, 0 },
    { { 0, 1, 2 }, { 3, 5, 4 }, { 0, 3, 4, 1 }, { 1, 4, 5, 2 }, { 2, 5, 3, 0 } },
    { 1.0 / 3.0, 1.0 / 3.0, 0.5 } },
  { 5, 5, { 4, 3, 3, 3, 3, 0 },
    { { 0, 3, 2, 1 }, { 0, 1, 4 }, { 1, 2, 4 }, { 2, 3, 4 }, { 3, 0, 4 } }, { 0.5, 0.5, 0.25 } },
};

inline const CellShape& ShapeOf(CellKind kind)
{
  return kShapes[static_cast<int>(kind)];
}

// The kind of a VTK cell type, or -1 for types the sampler does not support.
inline int KindOf(std::uint8_t vtkType)
{
  switch (vtkType)
  {
    case 10:
      return static_cast<int>(CellKind::Tetra);
    case 11:
      return static_cast<int>(CellKind::Voxel);
    case 12:
      return static_cast<int>(CellKind::Hexahedron);
    case 13:
      return static_cast<int>(CellKind::Wedge);
    case 14:
      return static_cast<int>(CellKind::Pyramid);
    default:
      return -1;
  }
}

// Shape functions in the monomial basis 1, r, s, t, rs, rt, st, rst, per kind and vertex:
// N_i(r, s, t) = sum over m of C[kind][i][m] times monomial m.
struct MonomialTable
{
  double C[5][8][8];

  MonomialTable()
    : C{}
  {
    // Tetrahedron: 1 - r - s - t, r, s, t.
    const double tetra[4][4] = { { 1, -1, -1, -1 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 },
      { 0, 0, 0, 1 } };
    for (int i = 0; i < 4; ++i)
    {
      for (int m = 0; m < 4; ++m)
      {
        this->C[static_cast<int>(CellKind::Tetra)][i][m] = tetra[i][m];
      }
    }
    // Voxel and hexahedron: products of r or 1 - r, s or 1 - s, t or 1 - t by corner.
    static const int lattice[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 },
      { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 } };
    static const int quads[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 },
      { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
    // The axes in each monomial.
    static const int axes[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 0 },
      { 1, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 } };
    for (CellKind kind : { CellKind::Voxel, CellKind::Hexahedron })
    {
      const int(*corner)[3] = kind == CellKind::Voxel ? lattice : quads;
      for (int i = 0; i < 8; ++i)
      {
        for (int m = 0; m < 8; ++m)
        {
          double c = 1.0;
          for (int a = 0; a < 3; ++a)
          {
            // r = 0 + 1 r, 1 - r = 1 - 1 r
            c *= axes[m][a] ? (corner[i][a] ? 1.0 : -1.0) : (corner[i][a] ? 0.0 : 1.0);
          }
          this->C[static_cast<int>(kind)][i][m] = c;
        }
      }
    }
    // Wedge: (1 - r - s)(1 - t), r (1 - t), s (1 - t), (1 - r - s) t, r t, s t.
    const double wedge[6][8] = { { 1, -1, -1, -1, 0, 1, 1, 0 }, { 0, 1, 0, 0, 0, -1, 0, 0 },
      { 0, 0, 1, 0, 0, 0, -1, 0 }, { 0, 0, 0, 1, 0, -1, -1, 0 }, { 0, 0, 0, 0, 0, 1, 0, 0 },
      { 0, 0, 0, 0, 0, 0, 1, 0 } };
    // Pyramid: (1 - r)(1 - s)(1 - t), r (1 - s)(1 - t), r s (1 - t), (1 - r) s (1 - t), t.
    const double pyramid[5][8] = { { 1, -1, -1, -1, 1, 1, 1, -1 }, { 0, 1, 0, 0, -1, -1, 0, 1 },
      { 0, 0, 0, 0, 1, 0, 0, -1 }, { 0, 0, 1, 0, -1, 0, -1, 1 }, { 0, 0, 0, 1, 0, 0, 0, 0 } };
    for (int i = 0; i < 6; ++i)
    {
      for (int m = 0; m < 8; ++m)
      {
        this->C[static_cast<int>(CellKind::Wedge)][i][m] = wedge[i][m];
        this->C[static_cast<int>(CellKind::Pyramid)][i][m] = i < 5 ? pyramid[i][m] : 0.0;
      }
    }
  }
};

inline const MonomialTable kMonomials;

// Keeps parametric coordinates within `margin` of the cell's parametric domain.
inline void ClampToCell(CellKind kind, double r[3], double margin)
{
  const double lo = -margin;
  const double hi = 1.0 + margin;
  for (int a = 0; a < 3; ++a)
  {
    r[a] = std::min(std::max(r[a], lo), hi);
  }
  if (kind == CellKind::Tetra || kind == CellKind::Wedge)
  {
    const int axes = kind == CellKind::Tetra ? 3 : 2;
    double sum = 0.0;
    for (int a = 0; a < axes; ++a)
    {
      sum += r[a];
    }
    if (sum > hi)
    {
      const double excess = (sum - hi) / axes;
      for (int a = 0; a < axes; ++a)
      {
        r[a] -= excess;
      }
    }
  }
  else if (kind == CellKind::Pyramid)
  {
    r[2] = std::min(r[2], 1.0); // the apex; beyond it the map folds back
  }
}

// A cell's vertices and values, gathered on the stack for interpolation.
struct CellVertices
{
  CellKind Kind;
  int Points;
  bool Direct; // parametric coordinates have a closed form (see DirectMap)
  Eigen::Vector3d X[8];
  double F[8];
};

// Vertices spanning the parametric axes from vertex 0, per kind.
constexpr int kAxes[5][3] = { { 1, 2, 3 }, { 1, 2, 4 }, { 1, 3, 4 }, { 1, 2, 3 }, { 1, 3, 4 } };

// Whether the cell's parametric coordinates have a closed form (see DirectMap): its opposite
// edges are parallel and of equal length, up to `tolerance`.
inline bool HasDirectMap(CellKind kind, const Eigen::Vector3d x[8], double tolerance)
{
  // Each vertex as the sum of others: x[a] + x[b] - x[c].
  static const int hexahedron[4][4] = { { 2, 1, 3, 0 }, { 5, 1, 4, 0 }, { 7, 3, 4, 0 },
    { 6, 2, 4, 0 } };
  static const int wedge[2][4] = { { 4, 1, 3, 0 }, { 5, 2, 3, 0 } };
  static const int pyramid[1][4] = { { 2, 1, 3, 0 } };
  const int(*rules)[4] = nullptr;
  int count = 0;
  switch (kind)
  {
    case CellKind::Tetra:
    case CellKind::Voxel: // axis-aligned by definition
      return true;
    case CellKind::Hexahedron:
      rules = hexahedron;
      count = 4;
      break;
    case CellKind::Wedge:
      rules = wedge;
      count = 2;
      break;
    case CellKind::Pyramid:
      rules = pyramid;
      count = 1;
      break;
  }
  for (int k = 0; k < count; ++k)
  {
    const int* r = rules[k];
    if (!((x[r[0]] - (x[r[1]] + x[r[2]] - x[r[3]])).norm() <= tolerance))
    {
      return false;
    }
  }
  return true;
}

// Closed-form parametric coordinates. Tetrahedra, voxels, parallelepiped hexahedra and prism
// wedges have affine maps, x = x0 + E r; a pyramid on a parallelogram has
// x = x0 + E ((1 - t) r, (1 - t) s, t). Either way q = E^-1 (x - x0) is affine in x, and along a
// ray in its parameter.
struct DirectMap
{
  Eigen::Matrix3d Inverse;
  Eigen::Vector3d Origin;
  CellKind Kind;

  bool Set(const CellVertices& cell)
  {
    const int* axes = kAxes[static_cast<int>(cell.Kind)];
    Eigen::Matrix3d e;
    for (int a = 0; a < 3; ++a)
    {
      e.col(a) = cell.X[axes[a]] - cell.X[0];
    }
    const double det = e.determinant();
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
    {
      return false;
    }
    this->Inverse = e.inverse();
    this->Origin = cell.X[0];
    this->Kind = cell.Kind;
    return true;
  }

  Eigen::Vector3d Q(const Eigen::Vector3d& x) const { return this->Inverse * (x - this->Origin); }

  void Parametric(const Eigen::Vector3d& q, double r[3]) const
  {
    r[0] = q[0];
    r[1] = q[1];
    r[2] = q[2];
    if (this->Kind == CellKind::Pyramid)
    {
      const double tm = 1.0 - q[2];
      if (std::abs(tm) > 1e-12)
      {
        r[0] = q[0] / tm;
        r[1] = q[1] / tm;
      }
      else
      {
        r[0] = r[1] = 0.5; // the apex
      }
    }
  }
};

// A cell's map x(r) and field f(r) as polynomials in the monomials 1, r, s, t, rs, rt, st, rst
// (every kind's shape functions are), built once per cell visit: cheap to evaluate, with their
// derivatives, in Newton's iteration.
struct Polynomial
{
  Eigen::Vector3d A[8]; // of x
  double B[8];          // of f

  Polynomial() = default;
  explicit Polynomial(const CellVertices& cell)
  {
    const auto& c = kMonomials.C[static_cast<int>(cell.Kind)];
    for (int m = 0; m < 8; ++m)
    {
      this->A[m].setZero();
      this->B[m] = 0.0;
      for (int i = 0; i < cell.Points; ++i)
      {
        if (c[i][m] != 0.0)
        {
          this->A[m] += c[i][m] * cell.X[i];
          this->B[m] += c[i][m] * cell.F[i];
        }
      }
    }
  }

  void Map(const double r[3], Eigen::Vector3d& x, Eigen::Matrix3d& jacobian) const
  {
    const double rs = r[0] * r[1];
    const double rt = r[0] * r[2];
    const double st = r[1] * r[2];
    x = this->A[0] + r[0] * this->A[1] + r[1] * this->A[2] + r[2] * this->A[3] + rs * this->A[4] +
        rt * this->A[5] + st * this->A[6] + (rs * r[2]) * this->A[7];
    jacobian.col(0) = this->A[1] + r[1] * this->A[4] + r[2] * this->A[5] + st * this->A[7];
    jacobian.col(1) = this->A[2] + r[0] * this->A[4] + r[2] * this->A[6] + rt * this->A[7];
    jacobian.col(2) = this->A[3] + r[0] * this->A[5] + r[1] * this->A[6] + rs * this->A[7];
  }

  double Value(const double r[3]) const
  {
    const double rs = r[0] * r[1];
    return this->B[0] + r[0] * this->B[1] + r[1] * this->B[2] + r[2] * this->B[3] +
           rs * this->B[4] + r[0] * r[2] * this->B[5] + r[1] * r[2] * this->B[6] +
           rs * r[2] * this->B[7];
  }

  // The field's derivatives along r, s, t.
  Eigen::Vector3d Derivatives(const double r[3]) const
  {
    return Eigen::Vector3d(
      this->B[1] + r[1] * this->B[4] + r[2] * this->B[5] + r[1] * r[2] * this->B[7],
      this->B[2] + r[0] * this->B[4] + r[2] * this->B[6] + r[0] * r[2] * this->B[7],
      this->B[3] + r[0] * this->B[5] + r[1] * this->B[6] + r[0] * r[1] * this->B[7]);
  }

  // Newton's iteration for the parametric coordinates r of p, starting from r; stops when x(r) is
  // within a 1e-8 fraction of the cell's size from p (finer than the samples' float values).
  void Invert(const Eigen::Vector3d& p, double r[3]) const
  {
    for (int iteration = 0; iteration < kNewtonIterations; ++iteration)
    {
      Eigen::Vector3d x;
      Eigen::Matrix3d jacobian;
      this->Map(r, x, jacobian);
      const Eigen::Vector3d residual = x - p;
      if (residual.squaredNorm() <= 1e-16 * jacobian.squaredNorm())
      {
        return;
      }
      Eigen::Matrix3d inverse;
      double det;
      bool invertible;
      jacobian.computeInverseAndDetWithCheck(inverse, det, invertible, 0.0);
      if (!invertible || !std::isfinite(det))
      {
        return;
      }
      const Eigen::Vector3d step = inverse * residual;
      for (int a = 0; a < 3; ++a)
      {
        // Bounded so that a bad start or a badly shaped cell cannot send the iteration away.
        r[a] = std::min(std::max(r[a] - step[a], -1.0), 2.0);
      }
      if (step.squaredNorm() <= 1e-12)
      {
        // A step of at most 1e-6: the iteration converges quadratically, so what is left is
        // of the order of its square, and checking that would take another map.
        return;
      }
    }
  }
};

// Parametric coordinates of p in the cell, from the closed form or Newton's iteration from the
// centre.
inline void Parametric(
  const CellVertices& cell, const Polynomial& polynomial, const Eigen::Vector3d& p, double r[3])
{
  DirectMap direct;
  if (cell.Direct && direct.Set(cell))
  {
    direct.Parametric(direct.Q(p), r);
    return;
  }
  const double* centre = ShapeOf(cell.Kind).Centre;
  r[0] = centre[0];
  r[1] = centre[1];
  r[2] = centre[2];
  polynomial.Invert(p, r);
}

} // namespace unstructured
} // namespace savr

#include "UnstructuredSampler.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <new>
#include <vector>

namespace savr
{
namespace
{

constexpr std::uint32_t kNone = 0xffffffffu;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Cells and their sides (triangles of their faces, at most 12 per cell) are indexed by 32-bit
// integers.
constexpr std::size_t kMaxCells = 0xfffffffeu / 12;
// Cells whose volume is below this fraction of their bounding box's largest edge cubed are
// degenerate: rays never walk through them (they look for the next cell instead).
constexpr double kDegenerateVolume = 1e-10;
// Samples this close (a fraction of the mesh's diagonal) outside the mesh still read the nearest
// cell: entry and exit points are computed with round-off and must not read as NaN.
constexpr double kBoundaryTolerance = 1e-7;
// Zero-length steps in a row (a ray through an edge or a vertex) before the walk gives up on
// adjacency and asks the spatial index for the next cell.
constexpr int kMaxStall = 64;
constexpr int kNewtonIterations = 20;
// Parametric coordinates may leave the cell by this much before they are clamped: quad faces
// are not planar in general, and a ray walks across their two triangles, so a sample can lie a
// little outside the cell's curved faces, where its own map extrapolates the field best.
constexpr double kParametricMargin = 0.5;
constexpr int kLeafSize = 4;
constexpr int kStackSize = 96; // the BVH's median splits keep its depth near log2(cells)

enum class Kind : std::uint8_t
{
  Tetra,
  Voxel,
  Hexahedron,
  Wedge,
  Pyramid
};

// Vertices and faces of each kind of cell in VTK's ordering. Faces list their vertices in
// cyclic order; their orientation does not matter (outward normals are found geometrically).
struct KindInfo
{
  int Points;
  int Faces;
  int FaceSize[6];
  int Face[6][4];
  double Centre[3]; // parametric centre, where Newton's iteration starts
};

const KindInfo kKinds[5] = {
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

int KindOf(std::uint8_t vtkType)
{
  switch (vtkType)
  {
    case 10:
      return static_cast<int>(Kind::Tetra);
    case 11:
      return static_cast<int>(Kind::Voxel);
    case 12:
      return static_cast<int>(Kind::Hexahedron);
    case 13:
      return static_cast<int>(Kind::Wedge);
    case 14:
      return static_cast<int>(Kind::Pyramid);
    default:
      return -1;
  }
}

inline double Dot(const double a[3], const double b[3])
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// One triangle of a cell's faces (a quad face has two), as the cell sees it: the plane
// n . x = d with n of unit length pointing out of the cell (zero for a degenerate triangle), and
// the cell across it. A face's planes are computed once, and its second cell holds their exact
// negations: the parameter where a ray leaves one cell is the one where it enters the next.
struct Side
{
  double N[3];
  double D;
  std::int32_t Neighbour;     // the cell across, or -1
  std::uint8_t NeighbourFace; // the face of the neighbour that this face is
  std::uint8_t Face;          // the cell's face this triangle belongs to (its faces in order)
  std::uint8_t Local;         // that face in the kind's table
  std::uint8_t Triangle;      // 0 or 1
};

constexpr std::uint8_t kNoFace = 0xff;

// Per-cell flags.
constexpr std::uint8_t kDegenerate = 1;
constexpr std::uint8_t kNonConvex = 2; // some vertex lies outside one of its faces' triangles
constexpr std::uint8_t kDirect = 4;    // parametric coordinates have a closed form (see Direct)

// BVH node: a leaf when Count > 0 (cells LeafCells[Index, Index + Count)), else the parent of
// nodes Index and Index + 1.
struct Node
{
  float Lo[3];
  float Hi[3];
  std::uint32_t Index;
  std::uint32_t Count;
};

// The line o + t d that a ray samples, and what the index's box tests need of it.
struct Line
{
  double O[3];
  double D[3];
  double Inverse[3];
  bool Parallel[3];

  Line(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->O[a] = origin[a];
      this->D[a] = direction[a];
      this->Parallel[a] = direction[a] == 0.0;
      this->Inverse[a] = this->Parallel[a] ? 0.0 : 1.0 / direction[a];
    }
  }
};

// Shape functions in the monomial basis 1, r, s, t, rs, rt, st, rst, per kind and vertex:
// N_i(r, s, t) = sum over m of kMonomials[kind][i][m] times monomial m.
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
        this->C[static_cast<int>(Kind::Tetra)][i][m] = tetra[i][m];
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
    for (Kind kind : { Kind::Voxel, Kind::Hexahedron })
    {
      const int(*corner)[3] = kind == Kind::Voxel ? lattice : quads;
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
        this->C[static_cast<int>(Kind::Wedge)][i][m] = wedge[i][m];
        this->C[static_cast<int>(Kind::Pyramid)][i][m] = i < 5 ? pyramid[i][m] : 0.0;
      }
    }
  }
};

const MonomialTable kMonomials;

// Keeps parametric coordinates within `margin` of the cell's parametric domain.
void ClampToCell(Kind kind, double r[3], double margin)
{
  const double lo = -margin;
  const double hi = 1.0 + margin;
  for (int a = 0; a < 3; ++a)
  {
    r[a] = std::min(std::max(r[a], lo), hi);
  }
  if (kind == Kind::Tetra || kind == Kind::Wedge)
  {
    const int axes = kind == Kind::Tetra ? 3 : 2;
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
  else if (kind == Kind::Pyramid)
  {
    r[2] = std::min(r[2], 1.0); // the apex; beyond it the map folds back
  }
}

// A cell's vertices and values, gathered on the stack for interpolation.
struct CellData
{
  Kind Type;
  int Points;
  bool Direct; // kDirect
  Eigen::Vector3d X[8];
  double F[8];
};

// Vertices spanning the parametric axes from vertex 0, per kind.
const int kAxes[5][3] = { { 1, 2, 3 }, { 1, 2, 4 }, { 1, 3, 4 }, { 1, 2, 3 }, { 1, 3, 4 } };

// Closed-form parametric coordinates. Tetrahedra, voxels, parallelepiped hexahedra and prism
// wedges have affine maps, x = x0 + E r; a pyramid on a parallelogram has
// x = x0 + E ((1 - t) r, (1 - t) s, t). Either way q = E^-1 (x - x0) is affine in x, and along a
// ray in its parameter.
struct Direct
{
  Eigen::Matrix3d Inverse;
  Eigen::Vector3d Origin;
  Kind Type;

  bool Set(const CellData& cell)
  {
    const int* axes = kAxes[static_cast<int>(cell.Type)];
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
    this->Type = cell.Type;
    return true;
  }

  Eigen::Vector3d Q(const Eigen::Vector3d& x) const { return this->Inverse * (x - this->Origin); }

  void Parametric(const Eigen::Vector3d& q, double r[3]) const
  {
    r[0] = q[0];
    r[1] = q[1];
    r[2] = q[2];
    if (this->Type == Kind::Pyramid)
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

  explicit Polynomial(const CellData& cell)
  {
    const auto& c = kMonomials.C[static_cast<int>(cell.Type)];
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
    }
  }
};

// Parametric coordinates of p in the cell, from the closed form or Newton's iteration from the
// centre.
void Parametric(
  const CellData& cell, const Polynomial& polynomial, const Eigen::Vector3d& p, double r[3])
{
  Direct direct;
  if (cell.Direct && direct.Set(cell))
  {
    direct.Parametric(direct.Q(p), r);
    return;
  }
  const double* centre = kKinds[static_cast<int>(cell.Type)].Centre;
  r[0] = centre[0];
  r[1] = centre[1];
  r[2] = centre[2];
  polynomial.Invert(p, r);
}

// 21 bits of each coordinate interleaved.
std::uint64_t Morton(const std::uint32_t q[3])
{
  std::uint64_t code = 0;
  for (int b = 20; b >= 0; --b)
  {
    for (int a = 0; a < 3; ++a)
    {
      code = (code << 1) | ((q[a] >> b) & 1u);
    }
  }
  return code;
}

// Asks for the cache lines from p on.
inline void Prefetch(const void* p, int lines)
{
#if defined(__GNUC__) || defined(__clang__)
  for (int k = 0; k < lines; ++k)
  {
    __builtin_prefetch(static_cast<const char*>(p) + 64 * k);
  }
#else
  (void)p;
  (void)lines;
#endif
}

float RoundDown(double v)
{
  float f = static_cast<float>(v);
  return static_cast<double>(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                    : f;
}

float RoundUp(double v)
{
  float f = static_cast<float>(v);
  return static_cast<double>(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

class UnstructuredSampler final : public Sampler
{
public:
  // `kept` lists the description's cells to use (supported, valid).
  UnstructuredSampler(const UnstructuredDescription& mesh, const std::vector<std::size_t>& kept)
    : CellValues(mesh.cellData)
  {
    this->Points.assign(mesh.points, mesh.points + 3 * mesh.numberOfPoints);
    this->OrderCells(mesh, kept);
    this->FindDegenerateCells();
    this->BuildFaces();
    this->FindNonConvexCells();
    this->BuildIndex();
    this->ScanValues();
  }

  bool Clip(const Ray& ray, double& tEnter, double& tExit) const override
  {
    const Line line(ray.origin, ray.direction);
    return this->ClipLine(line, tEnter, tExit) && tEnter < tExit;
  }

  std::array<double, 2> ValueRange() const override { return this->Range; }
  int ExactBits() const override { return 0; }
  // Rays may pass through holes, concavities and gaps between cells.
  bool MayReturnNaN() const override { return true; }

  void SampleRay(const Ray& ray, double t0, double dt, int count, float* out,
    const SkipMask* skip) const override
  {
    (void)skip; // no blocks
    this->Sample(ray, t0, dt, count, out, nullptr);
  }

  // The gradients come from the cell each sample is found in by the walk.
  void SampleRayGradients(
    const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const override
  {
    if (count > 0)
    {
      std::fill(gradients, gradients + 3 * static_cast<std::size_t>(count), 0.0f);
    }
    this->Sample(ray, t0, dt, count, out, gradients);
  }

  // Point data: the analytic gradient of the containing cell's interpolant. Cell data: central
  // differences one cell size apart, one-sided where a side is outside the mesh.
  void GradientAt(const Ray& ray, double t, float gradient[3]) const override
  {
    gradient[0] = gradient[1] = gradient[2] = 0.0f;
    const Eigen::Vector3d p = ray.At(t);
    if (!p.allFinite())
    {
      return;
    }
    const std::uint32_t cell = this->FindContaining(p);
    if (cell != kNone)
    {
      Store(this->GradientIn(cell, p), gradient);
    }
  }

private:
  static void Store(const Eigen::Vector3d& g, float* gradient)
  {
    for (int a = 0; a < 3; ++a)
    {
      gradient[a] = std::isfinite(g[a]) ? static_cast<float>(g[a]) : 0.0f;
    }
  }

  void Sample(const Ray& ray, double t0, double dt, int count, float* out, float* gradients) const
  {
    if (count <= 0)
    {
      return;
    }
    std::fill(out, out + count, std::numeric_limits<float>::quiet_NaN());
    if (!std::isfinite(t0) || !std::isfinite(dt) || !ray.origin.allFinite() ||
        !ray.direction.allFinite())
    {
      return;
    }
    // Walked forward: samples at decreasing parameters are the same points on the reversed ray.
    const double sign = dt < 0.0 ? -1.0 : 1.0;
    const Line line(ray.origin, sign * ray.direction);
    t0 *= sign;
    dt *= sign;
    double lo;
    double hi;
    if (!this->ClipLine(line, lo, hi))
    {
      return;
    }
    hi = std::min(hi, t0 + (count - 1) * dt + this->Tolerance);
    lo = std::max(lo, t0 - this->Tolerance);
    if (lo <= hi)
    {
      this->Walk(line, t0, dt, count, lo, hi, out, gradients);
    }
  }

  // The gradient in `cell` (which contains p). Point data: the points' gradients (each the mean
  // of its cells' interpolant gradients there) interpolated like the values, so that shading is
  // smooth across cells (the interpolant's own gradient jumps from cell to cell). Cell data:
  // central differences one cell size apart, one-sided where a side is outside the mesh.
  Eigen::Vector3d GradientIn(std::uint32_t cell, const Eigen::Vector3d& p) const
  {
    if (!this->CellValues)
    {
      const std::vector<float>& pointGradients = this->PointGradients();
      CellData data = this->Gather(cell);
      const Polynomial polynomial(data);
      double r[3];
      Parametric(data, polynomial, p, r);
      ClampToCell(data.Type, r, kParametricMargin);
      const std::uint32_t* ids = this->CellPoints.data() + 8 * static_cast<std::size_t>(cell);
      Eigen::Vector3d g;
      for (int a = 0; a < 3; ++a)
      {
        for (int k = 0; k < data.Points; ++k)
        {
          data.F[k] = pointGradients[3 * static_cast<std::size_t>(ids[k]) + a];
        }
        g[a] = Polynomial(data).Value(r);
      }
      return g;
    }
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    const double h = this->CellSize(cell);
    const double centre = this->Values[cell];
    for (int a = 0; a < 3; ++a)
    {
      Eigen::Vector3d step = Eigen::Vector3d::Zero();
      step[a] = h;
      const double plus = this->ValueAt(p + step);
      const double minus = this->ValueAt(p - step);
      if (plus == plus && minus == minus)
      {
        g[a] = (plus - minus) / (2.0 * h);
      }
      else if (plus == plus)
      {
        g[a] = (plus - centre) / h;
      }
      else if (minus == minus)
      {
        g[a] = (centre - minus) / h;
      }
    }
    return g;
  }

  // Sorts the cells along a Morton curve of their centres, so that neighbours in space are
  // neighbours in memory, and copies them (and cell values) in that order.
  void OrderCells(const UnstructuredDescription& mesh, const std::vector<std::size_t>& kept)
  {
    const std::size_t cells = kept.size();
    std::vector<double> centres(3 * cells);
    double lo[3] = { kInfinity, kInfinity, kInfinity };
    double hi[3] = { -kInfinity, -kInfinity, -kInfinity };
    for (std::size_t c = 0; c < cells; ++c)
    {
      const std::int64_t* ids = mesh.connectivity + mesh.offsets[kept[c]];
      const int n = kKinds[KindOf(mesh.types[kept[c]])].Points;
      double sum[3] = { 0.0, 0.0, 0.0 };
      for (int k = 0; k < n; ++k)
      {
        const double* x = mesh.points + 3 * ids[k];
        for (int a = 0; a < 3; ++a)
        {
          sum[a] += x[a];
          lo[a] = std::min(lo[a], x[a]);
          hi[a] = std::max(hi[a], x[a]);
        }
      }
      for (int a = 0; a < 3; ++a)
      {
        centres[3 * c + a] = sum[a] / n;
      }
    }
    const double diagonal =
      std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
    this->Tolerance = kBoundaryTolerance * diagonal;
    for (int a = 0; a < 3; ++a)
    {
      // Clip's box: grown well beyond the tolerance so that no sample that may read a cell is
      // clipped away.
      this->ClipLo[a] = lo[a] - 10.0 * this->Tolerance;
      this->ClipHi[a] = hi[a] + 10.0 * this->Tolerance;
    }

    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(cells);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 4096),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t c = range.begin(); c < range.end(); ++c)
        {
          std::uint32_t q[3];
          for (int a = 0; a < 3; ++a)
          {
            const double extent = hi[a] - lo[a];
            const double u = extent > 0.0 ? (centres[3 * c + a] - lo[a]) / extent : 0.0;
            q[a] = static_cast<std::uint32_t>(std::min(std::max(u, 0.0), 1.0) * 2097151.0);
          }
          order[c] = { Morton(q), static_cast<std::uint32_t>(c) };
        }
      });
    tbb::parallel_sort(order.begin(), order.end());

    this->CellCount = static_cast<std::uint32_t>(cells);
    this->Kinds.resize(cells);
    this->CellPoints.assign(8 * cells, kNone);
    if (this->CellValues)
    {
      this->Values.resize(cells);
    }
    else
    {
      this->Values.assign(mesh.values, mesh.values + mesh.numberOfPoints);
    }
    for (std::size_t c = 0; c < cells; ++c)
    {
      const std::size_t source = kept[order[c].second];
      const int kind = KindOf(mesh.types[source]);
      this->Kinds[c] = static_cast<Kind>(kind);
      const std::int64_t* ids = mesh.connectivity + mesh.offsets[source];
      for (int k = 0; k < kKinds[kind].Points; ++k)
      {
        this->CellPoints[8 * c + k] = static_cast<std::uint32_t>(ids[k]);
      }
      if (this->CellValues)
      {
        this->Values[c] = mesh.values[source];
      }
    }
  }

  // The distinct vertices of face `local` of `cell` in cyclic order; how many (3 or 4, or fewer
  // for a face collapsed by repeated points).
  int FaceVertices(std::uint32_t cell, int local, std::uint32_t v[4]) const
  {
    const KindInfo& info = kKinds[static_cast<int>(this->Kinds[cell])];
    const std::uint32_t* ids = this->CellPoints.data() + 8 * static_cast<std::size_t>(cell);
    int n = 0;
    for (int k = 0; k < info.FaceSize[local]; ++k)
    {
      const std::uint32_t id = ids[info.Face[local][k]];
      if (std::find(v, v + n, id) == v + n)
      {
        v[n++] = id;
      }
    }
    return n;
  }

  // Pairs the cells' faces by their sorted vertex ids, computes each face's planes once, and
  // gives each cell its sides. Two cells pair up only from opposite sides of a face: overlapping
  // (duplicated, tangled) cells stay unpaired, and rays crossing such faces ask the index for the
  // next cell. Degenerate cells get no sides: rays never walk into them.
  void BuildFaces()
  {
    struct Entry
    {
      std::uint32_t Key[4];
      std::uint32_t Cell;
      std::uint8_t Local;  // the face in the kind's table
      std::uint8_t Face;   // its place among the cell's faces
      std::uint8_t Offset; // its first side among the cell's sides
      std::uint8_t Above;  // the cell's centre on the positive side of the face
    };
    const std::size_t cells = this->CellCount;
    // Faces collapsed by repeated points to fewer than 3 distinct vertices are dropped.
    std::vector<std::uint32_t> faces(cells + 1, 0);
    this->SideBegin.assign(cells + 1, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 4096),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t c = range.begin(); c < range.end(); ++c)
        {
          const auto cell = static_cast<std::uint32_t>(c);
          if (this->IsDegenerate(cell))
          {
            continue;
          }
          const KindInfo& info = kKinds[static_cast<int>(this->Kinds[c])];
          for (int f = 0; f < info.Faces; ++f)
          {
            std::uint32_t v[4] = { 0, 0, 0, 0 };
            const int n = this->FaceVertices(cell, f, v);
            faces[c + 1] += n >= 3 ? 1 : 0;
            this->SideBegin[c + 1] += n == 4 ? 2 : (n == 3 ? 1 : 0);
          }
        }
      });
    for (std::size_t c = 0; c < cells; ++c)
    {
      faces[c + 1] += faces[c];
      this->SideBegin[c + 1] += this->SideBegin[c];
    }
    std::vector<Entry> entries(faces[cells]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 4096),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t c = range.begin(); c < range.end(); ++c)
        {
          if (faces[c + 1] == faces[c])
          {
            continue;
          }
          const auto cell = static_cast<std::uint32_t>(c);
          const KindInfo& info = kKinds[static_cast<int>(this->Kinds[c])];
          const Eigen::Vector3d centre = this->Centre(cell);
          std::uint32_t face = 0;
          int offset = 0;
          for (int f = 0; f < info.Faces; ++f)
          {
            Entry& e = entries[faces[c] + face];
            const int n = this->FaceVertices(cell, f, e.Key);
            if (n < 3)
            {
              continue;
            }
            // The face's normal for its vertices in a cyclic order that every cell with the face
            // agrees on: from the smallest id, towards the smaller of its two neighbours.
            int m = 0;
            for (int k = 1; k < n; ++k)
            {
              m = e.Key[k] < e.Key[m] ? k : m;
            }
            const int step = e.Key[(m + 1) % n] < e.Key[(m + n - 1) % n] ? 1 : n - 1;
            Eigen::Vector3d q[4];
            Eigen::Vector3d middle = Eigen::Vector3d::Zero();
            for (int k = 0; k < n; ++k)
            {
              q[k] = this->Point(e.Key[(m + k * step) % n]);
              middle += q[k] / n;
            }
            const Eigen::Vector3d normal =
              n == 3 ? (q[1] - q[0]).cross(q[2] - q[0]) : (q[2] - q[0]).cross(q[3] - q[1]);
            e.Above = normal.dot(centre - middle) > 0.0;
            if (n == 3)
            {
              e.Key[3] = kNone;
            }
            std::sort(e.Key, e.Key + n);
            e.Cell = cell;
            e.Local = static_cast<std::uint8_t>(f);
            e.Face = static_cast<std::uint8_t>(face++);
            e.Offset = static_cast<std::uint8_t>(offset);
            offset += n == 4 ? 2 : 1;
          }
        }
      });
    tbb::parallel_sort(entries.begin(), entries.end(),
      [](const Entry& a, const Entry& b)
      {
        for (int k = 0; k < 4; ++k)
        {
          if (a.Key[k] != b.Key[k])
          {
            return a.Key[k] < b.Key[k];
          }
        }
        return a.Cell != b.Cell ? a.Cell < b.Cell : a.Local < b.Local;
      });

    // Faces as pairs of entries (the second kNone on the boundary).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    pairs.reserve(entries.size() / 2 + 16);
    std::vector<std::uint8_t> paired;
    for (std::size_t g = 0; g < entries.size();)
    {
      std::size_t end = g + 1;
      while (
        end < entries.size() && std::equal(entries[g].Key, entries[g].Key + 4, entries[end].Key))
      {
        ++end;
      }
      const auto first = static_cast<std::uint32_t>(g);
      if (end - g == 1)
      {
        pairs.emplace_back(first, kNone);
      }
      else if (end - g == 2 && entries[g].Above != entries[g + 1].Above)
      {
        pairs.emplace_back(first, first + 1); // the usual case: two cells, one on each side
      }
      else
      {
        // Pairs of cells from opposite sides, in order; the others alone.
        paired.assign(end - g, 0);
        std::size_t above = g;
        std::size_t below = g;
        for (;;)
        {
          while (above < end && !entries[above].Above)
          {
            ++above;
          }
          while (below < end && entries[below].Above)
          {
            ++below;
          }
          if (above == end || below == end)
          {
            break;
          }
          pairs.emplace_back(static_cast<std::uint32_t>(std::min(above, below)),
            static_cast<std::uint32_t>(std::max(above, below)));
          paired[above - g] = paired[below - g] = 1;
          ++above;
          ++below;
        }
        for (std::size_t k = g; k < end; ++k)
        {
          if (!paired[k - g])
          {
            pairs.emplace_back(static_cast<std::uint32_t>(k), kNone);
          }
        }
      }
      g = end;
    }

    this->Sides.resize(this->SideBegin[cells]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pairs.size(), 4096),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t k = range.begin(); k < range.end(); ++k)
        {
          const Entry& owner = entries[pairs[k].first];
          if (pairs[k].second == kNone)
          {
            this->AddFace(owner.Cell, owner.Local, owner.Face, owner.Offset, -1, 0, kNoFace, 0);
            continue;
          }
          const Entry& other = entries[pairs[k].second];
          this->AddFace(owner.Cell, owner.Local, owner.Face, owner.Offset,
            static_cast<std::int32_t>(other.Cell), other.Local, other.Face, other.Offset);
        }
      });
  }

  // Vertices of triangle k of face `local` of `cell`. A quad is cut along the diagonal from its
  // smallest vertex id, and its triangles are numbered by their third vertex, the smaller id
  // first: both cells of a face see the same triangles, in the same order.
  void Triangle(std::uint32_t cell, int local, int k, Eigen::Vector3d triangle[3]) const
  {
    std::uint32_t v[4] = { 0, 0, 0, 0 };
    const int n = this->FaceVertices(cell, local, v);
    int m = 0;
    for (int i = 1; i < n; ++i)
    {
      m = v[i] < v[m] ? i : m;
    }
    triangle[0] = this->Point(v[m]);
    if (n == 3)
    {
      triangle[1] = this->Point(v[(m + 1) % 3]);
      triangle[2] = this->Point(v[(m + 2) % 3]);
      return;
    }
    // (m, m + 1, m + 2) or (m, m + 2, m + 3): both wound as the quad.
    const bool next = (k == 0) == (v[(m + 1) % 4] < v[(m + 3) % 4]);
    triangle[1] = this->Point(v[(m + (next ? 1 : 2)) % 4]);
    triangle[2] = this->Point(v[(m + (next ? 2 : 3)) % 4]);
  }

  // Computes the planes of face `local` of `cell` (the cell's face number `face`, its sides from
  // `offset` on) once, pointing away from the cell's centre (towards the neighbour's when the
  // cell's centre is too close to the face to tell), and gives them to both cells.
  void AddFace(std::uint32_t cell, int local, std::uint8_t face, int offset, std::int32_t neighbour,
    int neighbourLocal, std::uint8_t neighbourFace, int neighbourOffset)
  {
    std::uint32_t v[4] = { 0, 0, 0, 0 };
    const int n = this->FaceVertices(cell, local, v);
    const int triangles = n == 4 ? 2 : 1;
    Eigen::Vector3d normals[2];
    Eigen::Vector3d anchors[2];
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (int k = 0; k < triangles; ++k)
    {
      Eigen::Vector3d t[3];
      this->Triangle(cell, local, k, t);
      normals[k] = (t[1] - t[0]).cross(t[2] - t[0]);
      anchors[k] = t[0];
      total += normals[k];
    }
    Eigen::Vector3d middle = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
    {
      middle += this->Point(v[k]) / n;
    }
    double side = total.dot(this->Centre(cell) - middle);
    if (!(std::abs(side) > 1e-9 * total.norm() * this->CellSize(cell)) && neighbour >= 0)
    {
      side = -total.dot(this->Centre(static_cast<std::uint32_t>(neighbour)) - middle);
    }
    const double orientation = side > 0.0 ? -1.0 : 1.0;
    for (int k = 0; k < triangles; ++k)
    {
      Side& mine = this->Sides[this->SideBegin[cell] + offset + k];
      const double length = normals[k].norm();
      if (length > 0.0 && std::isfinite(length))
      {
        const Eigen::Vector3d unit = (orientation / length) * normals[k];
        for (int a = 0; a < 3; ++a)
        {
          mine.N[a] = unit[a];
        }
        mine.D = unit.dot(anchors[k]);
      }
      else
      {
        mine.N[0] = mine.N[1] = mine.N[2] = mine.D = 0.0;
      }
      mine.Neighbour = neighbour;
      mine.NeighbourFace = neighbourFace;
      mine.Face = face;
      mine.Local = static_cast<std::uint8_t>(local);
      mine.Triangle = static_cast<std::uint8_t>(k);
      if (neighbour >= 0)
      {
        Side& theirs = this->Sides[this->SideBegin[neighbour] + neighbourOffset + k];
        for (int a = 0; a < 3; ++a)
        {
          theirs.N[a] = -mine.N[a];
        }
        theirs.D = -mine.D;
        theirs.Neighbour = static_cast<std::int32_t>(cell);
        theirs.NeighbourFace = face;
        theirs.Face = neighbourFace;
        theirs.Local = static_cast<std::uint8_t>(neighbourLocal);
        theirs.Triangle = static_cast<std::uint8_t>(k);
      }
    }
  }

  Eigen::Vector3d Point(std::uint32_t id) const
  {
    const double* x = this->Points.data() + 3 * static_cast<std::size_t>(id);
    return Eigen::Vector3d(x[0], x[1], x[2]);
  }

  Eigen::Vector3d Centre(std::uint32_t cell) const
  {
    const int n = kKinds[static_cast<int>(this->Kinds[cell])].Points;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int k = 0; k < n; ++k)
    {
      sum += this->Point(this->CellPoints[8 * static_cast<std::size_t>(cell) + k]);
    }
    return sum / n;
  }

  // Cells whose faces are not all planar may be non-convex: some vertex lies outside the plane
  // of one of the cell's triangles. The walk tests such cells' triangles themselves.
  void FindNonConvexCells()
  {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->CellCount, 4096),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t c = range.begin(); c < range.end(); ++c)
        {
          const auto cell = static_cast<std::uint32_t>(c);
          const int n = kKinds[static_cast<int>(this->Kinds[cell])].Points;
          const double tolerance = 1e-9 * this->CellSize(cell);
          bool convex = true;
          for (std::uint32_t k = this->SideBegin[c]; k < this->SideBegin[c + 1] && convex; ++k)
          {
            const Side& side = this->Sides[k];
            for (int i = 0; i < n; ++i)
            {
              const double* x = this->Points.data() + 3 * this->CellPoints[8 * c + i];
              if (Dot(side.N, x) - side.D > tolerance)
              {
                convex = false;
                break;
              }
            }
          }
          if (!convex)
          {
            this->Flags[c] |= kNonConvex;
          }
        }
      });
  }

  bool IsDegenerate(std::uint32_t cell) const { return (this->Flags[cell] & kDegenerate) != 0; }
  bool IsNonConvex(std::uint32_t cell) const { return (this->Flags[cell] & kNonConvex) != 0; }

  // A cell is degenerate when its volume (tetrahedra from its centre to its faces' triangles,
  // each counted positive) is negligible beside its size.
  void FindDegenerateCells()
  {
    this->Flags.assign(this->CellCount, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->CellCount, 4096),
      [&](const tbb::blocked_range<std::size_t>& range)
      {
        for (std::size_t c = range.begin(); c < range.end(); ++c)
        {
          const auto cell = static_cast<std::uint32_t>(c);
          const KindInfo& info = kKinds[static_cast<int>(this->Kinds[cell])];
          const Eigen::Vector3d centre = this->Centre(cell);
          Eigen::Vector3d lo = centre;
          Eigen::Vector3d hi = centre;
          double volume = 0.0;
          for (int f = 0; f < info.Faces; ++f)
          {
            const int* face = info.Face[f];
            const Eigen::Vector3d a = this->Point(this->CellPoints[8 * c + face[0]]) - centre;
            for (int k = 1; k + 1 < info.FaceSize[f]; ++k)
            {
              const Eigen::Vector3d b = this->Point(this->CellPoints[8 * c + face[k]]) - centre;
              const Eigen::Vector3d d = this->Point(this->CellPoints[8 * c + face[k + 1]]) - centre;
              volume += std::abs(a.dot(b.cross(d))) / 6.0;
            }
          }
          for (int k = 0; k < info.Points; ++k)
          {
            const Eigen::Vector3d x = this->Point(this->CellPoints[8 * c + k]);
            lo = lo.cwiseMin(x);
            hi = hi.cwiseMax(x);
          }
          const double size = (hi - lo).maxCoeff();
          this->Flags[c] = volume > kDegenerateVolume * size * size * size ? 0 : kDegenerate;
          this->Flags[c] |= this->HasDirectMap(cell, 1e-10 * size) ? kDirect : 0;
        }
      });
  }

  // Whether the cell's parametric coordinates have a closed form (see Direct): its opposite
  // edges are parallel and of equal length, up to `tolerance`.
  bool HasDirectMap(std::uint32_t cell, double tolerance) const
  {
    const std::uint32_t* ids = this->CellPoints.data() + 8 * static_cast<std::size_t>(cell);
    auto x = [&](int k) { return this->Point(ids[k]); };
    // Each vertex as the sum of others: x[a] + x[b] - x[c].
    static const int hexahedron[4][4] = { { 2, 1, 3, 0 }, { 5, 1, 4, 0 }, { 7, 3, 4, 0 },
      { 6, 2, 4, 0 } };
    static const int wedge[2][4] = { { 4, 1, 3, 0 }, { 5, 2, 3, 0 } };
    static const int pyramid[1][4] = { { 2, 1, 3, 0 } };
    const int(*rules)[4] = nullptr;
    int count = 0;
    switch (this->Kinds[cell])
    {
      case Kind::Tetra:
      case Kind::Voxel: // axis-aligned by definition
        return true;
      case Kind::Hexahedron:
        rules = hexahedron;
        count = 4;
        break;
      case Kind::Wedge:
        rules = wedge;
        count = 2;
        break;
      case Kind::Pyramid:
        rules = pyramid;
        count = 1;
        break;
    }
    for (int k = 0; k < count; ++k)
    {
      const int* r = rules[k];
      if (!((x(r[0]) - (x(r[1]) + x(r[2]) - x(r[3]))).norm() <= tolerance))
      {
        return false;
      }
    }
    return true;
  }

  // A BVH over the bounding boxes of the cells that are not degenerate, split at the median
  // centre along the widest axis.
  void BuildIndex()
  {
    struct Item
    {
      float Lo[3];
      float Hi[3];
      float Centre[3];
      std::uint32_t Cell;
    };
    std::vector<Item> items;
    items.reserve(this->CellCount);
    for (std::uint32_t c = 0; c < this->CellCount; ++c)
    {
      if (this->IsDegenerate(c))
      {
        continue;
      }
      const int n = kKinds[static_cast<int>(this->Kinds[c])].Points;
      Eigen::Vector3d lo = this->Point(this->CellPoints[8 * static_cast<std::size_t>(c)]);
      Eigen::Vector3d hi = lo;
      for (int k = 1; k < n; ++k)
      {
        const Eigen::Vector3d x =
          this->Point(this->CellPoints[8 * static_cast<std::size_t>(c) + k]);
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
      Item item;
      for (int a = 0; a < 3; ++a)
      {
        // Grown: a cell's interval along a ray, from its face planes, may stray out of its box
        // by round-off.
        item.Lo[a] = RoundDown(lo[a] - this->Tolerance);
        item.Hi[a] = RoundUp(hi[a] + this->Tolerance);
        item.Centre[a] = static_cast<float>(0.5 * (lo[a] + hi[a]));
      }
      item.Cell = c;
      items.push_back(item);
    }
    if (items.empty())
    {
      return;
    }
    this->Nodes.reserve(2 * (items.size() / 2 + 1));
    this->Nodes.emplace_back();
    struct Task
    {
      std::uint32_t Node;
      std::size_t Begin;
      std::size_t End;
    };
    std::vector<Task> tasks = { { 0, 0, items.size() } };
    while (!tasks.empty())
    {
      const Task task = tasks.back();
      tasks.pop_back();
      float lo[3] = { items[task.Begin].Lo[0], items[task.Begin].Lo[1], items[task.Begin].Lo[2] };
      float hi[3] = { items[task.Begin].Hi[0], items[task.Begin].Hi[1], items[task.Begin].Hi[2] };
      float cLo[3] = { items[task.Begin].Centre[0], items[task.Begin].Centre[1],
        items[task.Begin].Centre[2] };
      float cHi[3] = { cLo[0], cLo[1], cLo[2] };
      for (std::size_t i = task.Begin; i < task.End; ++i)
      {
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], items[i].Lo[a]);
          hi[a] = std::max(hi[a], items[i].Hi[a]);
          cLo[a] = std::min(cLo[a], items[i].Centre[a]);
          cHi[a] = std::max(cHi[a], items[i].Centre[a]);
        }
      }
      Node& node = this->Nodes[task.Node];
      for (int a = 0; a < 3; ++a)
      {
        node.Lo[a] = lo[a];
        node.Hi[a] = hi[a];
      }
      const std::size_t count = task.End - task.Begin;
      if (count <= static_cast<std::size_t>(kLeafSize))
      {
        node.Index = static_cast<std::uint32_t>(task.Begin);
        node.Count = static_cast<std::uint32_t>(count);
        continue;
      }
      int axis = 0;
      for (int a = 1; a < 3; ++a)
      {
        if (cHi[a] - cLo[a] > cHi[axis] - cLo[axis])
        {
          axis = a;
        }
      }
      const std::size_t middle = task.Begin + count / 2;
      std::nth_element(items.begin() + task.Begin, items.begin() + middle, items.begin() + task.End,
        [axis](const Item& a, const Item& b) { return a.Centre[axis] < b.Centre[axis]; });
      const auto child = static_cast<std::uint32_t>(this->Nodes.size());
      node.Index = child;
      node.Count = 0;
      this->Nodes.emplace_back();
      this->Nodes.emplace_back();
      tasks.push_back({ child, task.Begin, middle });
      tasks.push_back({ child + 1, middle, task.End });
    }
    this->LeafCells.resize(items.size());
    for (std::size_t i = 0; i < items.size(); ++i)
    {
      this->LeafCells[i] = items[i].Cell;
    }
  }

  void ScanValues()
  {
    double lo = kInfinity;
    double hi = -kInfinity;
    auto scan = [&](float v)
    {
      if (std::isfinite(v))
      {
        lo = std::min(lo, static_cast<double>(v));
        hi = std::max(hi, static_cast<double>(v));
      }
    };
    if (this->CellValues)
    {
      for (float v : this->Values)
      {
        scan(v);
      }
    }
    else
    {
      // Only the points of the cells kept.
      std::vector<std::uint8_t> used(this->Values.size(), 0);
      for (std::uint32_t id : this->CellPoints)
      {
        if (id != kNone)
        {
          used[id] = 1;
        }
      }
      for (std::size_t i = 0; i < used.size(); ++i)
      {
        if (used[i])
        {
          scan(this->Values[i]);
        }
      }
    }
    this->Range = lo <= hi ? std::array<double, 2>{ lo, hi } : std::array<double, 2>{ 0.0, 0.0 };
  }

  bool ClipLine(const Line& line, double& tEnter, double& tExit) const
  {
    tEnter = -kInfinity;
    tExit = kInfinity;
    for (int a = 0; a < 3; ++a)
    {
      if (line.Parallel[a])
      {
        if (!(line.O[a] >= this->ClipLo[a] && line.O[a] <= this->ClipHi[a]))
        {
          return false;
        }
        continue;
      }
      const double ta = (this->ClipLo[a] - line.O[a]) * line.Inverse[a];
      const double tb = (this->ClipHi[a] - line.O[a]) * line.Inverse[a];
      tEnter = std::max(tEnter, std::min(ta, tb));
      tExit = std::min(tExit, std::max(ta, tb));
    }
    return tEnter <= tExit;
  }

  // Parameter interval [tNear, ...] of the line inside a node's box, within [tLo, tHi].
  static bool HitBox(const Node& node, const Line& line, double tLo, double tHi, double& tNear)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (line.Parallel[a])
      {
        if (line.O[a] < node.Lo[a] || line.O[a] > node.Hi[a])
        {
          return false;
        }
        continue;
      }
      double ta = (node.Lo[a] - line.O[a]) * line.Inverse[a];
      double tb = (node.Hi[a] - line.O[a]) * line.Inverse[a];
      if (ta > tb)
      {
        std::swap(ta, tb);
      }
      tLo = std::max(tLo, ta);
      tHi = std::min(tHi, tb);
    }
    tNear = tLo;
    return tLo <= tHi;
  }

  // Where the line crosses a side's plane. Its neighbour's side holds the exact negations of
  // its numbers, so the parameter where a ray leaves a cell is the one where it enters the next.
  static double Crossing(const Side& side, const Line& line, double denominator)
  {
    return (side.D - Dot(side.N, line.O)) / denominator;
  }

  // Whether the line's crossing at t of the plane of a side of `cell` lies in its triangle (grown
  // by a hair, so that a line through an edge hits one of its triangles).
  bool Hits(std::uint32_t cell, const Side& side, const Line& line, double t) const
  {
    Eigen::Vector3d v[3];
    this->Triangle(cell, side.Local, side.Triangle, v);
    const Eigen::Vector3d p(
      line.O[0] + t * line.D[0], line.O[1] + t * line.D[1], line.O[2] + t * line.D[2]);
    const Eigen::Vector3d e0 = v[1] - v[0];
    const Eigen::Vector3d e1 = v[2] - v[0];
    const Eigen::Vector3d n = e0.cross(e1);
    const double area = n.squaredNorm();
    if (!(area > 0.0))
    {
      return false;
    }
    const Eigen::Vector3d q = p - v[0];
    const double u = n.dot(q.cross(e1)) / area;
    const double w = n.dot(e0.cross(q)) / area;
    constexpr double grow = 1e-7;
    return u >= -grow && w >= -grow && u + w <= 1.0 + grow;
  }

  // The parameter where the line leaves `cell` through the first of its faces other than
  // `skip` (the face it came in by), and the side it leaves by (kNone when no side faces
  // forward). Convex cells: the nearest plane the line leaves by. Non-convex cells: the nearest
  // triangle the line leaves by, after tIn.
  double Exit(std::uint32_t cell, const Line& line, std::uint8_t skip, double tIn,
    std::uint32_t& exitSide) const
  {
    const std::uint32_t begin = this->SideBegin[cell];
    const std::uint32_t end = this->SideBegin[cell + 1];
    for (int pass = this->IsNonConvex(cell) ? 0 : 1; pass < 2; ++pass)
    {
      double best = kInfinity;
      exitSide = kNone;
      for (std::uint32_t k = begin; k < end; ++k)
      {
        const Side& side = this->Sides[k];
        const double denominator = Dot(side.N, line.D);
        if (denominator > 0.0 && side.Face != skip)
        {
          const double t = Crossing(side, line, denominator);
          if (t < best &&
              (pass == 1 || (t >= tIn - this->Tolerance && this->Hits(cell, side, line, t))))
          {
            best = t;
            exitSide = k;
          }
        }
      }
      if (exitSide != kNone)
      {
        return best;
      }
    }
    return kInfinity;
  }

  // The interval [a, b] of the line inside `cell` that holds tMin or comes first after it;
  // false when there is none. Convex cells: the intersection of the sides' half-spaces.
  // Non-convex cells: the first triangle the line leaves by after tMin (strictly after, with
  // `strict`) and the last it enters by before that.
  bool Interval(
    std::uint32_t cell, const Line& line, double tMin, bool strict, double& a, double& b) const
  {
    const std::uint32_t begin = this->SideBegin[cell];
    const std::uint32_t end = this->SideBegin[cell + 1];
    if (this->IsNonConvex(cell))
    {
      a = -kInfinity;
      b = kInfinity;
      for (int pass = 0; pass < 2; ++pass) // leaving, then entering
      {
        for (std::uint32_t k = begin; k < end; ++k)
        {
          const Side& side = this->Sides[k];
          const double denominator = Dot(side.N, line.D);
          if (denominator == 0.0)
          {
            continue;
          }
          const double t = Crossing(side, line, denominator);
          if (pass == 0 && denominator > 0.0 && (strict ? t > tMin : t >= tMin) && t < b &&
              this->Hits(cell, side, line, t))
          {
            b = t;
          }
          else if (pass == 1 && denominator < 0.0 && t <= b && t > a &&
                   this->Hits(cell, side, line, t))
          {
            a = t;
          }
        }
        if (b == kInfinity)
        {
          break; // no triangle hit: the half-spaces decide
        }
      }
      if (b < kInfinity)
      {
        return true;
      }
    }
    a = -kInfinity;
    b = kInfinity;
    for (std::uint32_t k = begin; k < end; ++k)
    {
      const Side& side = this->Sides[k];
      const double denominator = Dot(side.N, line.D);
      if (denominator == 0.0)
      {
        if (Dot(side.N, line.O) - side.D > 0.0)
        {
          return false;
        }
        continue;
      }
      const double t = Crossing(side, line, denominator);
      if (denominator > 0.0)
      {
        b = std::min(b, t);
      }
      else
      {
        a = std::max(a, t);
      }
    }
    return begin < end && a <= b;
  }

  // Whether p lies in the cell: inside its sides' half-spaces, or, for a non-convex cell and
  // with `exact`, at parametric coordinates inside its domain.
  bool Contains(std::uint32_t cell, const Eigen::Vector3d& p, bool exact) const
  {
    const double x[3] = { p[0], p[1], p[2] };
    bool inside = this->SideBegin[cell] < this->SideBegin[cell + 1];
    for (std::uint32_t k = this->SideBegin[cell]; k < this->SideBegin[cell + 1]; ++k)
    {
      const Side& side = this->Sides[k];
      if (Dot(side.N, x) - side.D > this->Tolerance)
      {
        inside = false;
        break;
      }
    }
    if (inside || !exact || !this->IsNonConvex(cell))
    {
      return inside;
    }
    const CellData data = this->Gather(cell);
    const Polynomial polynomial(data);
    double r[3];
    Parametric(data, polynomial, p, r);
    ClampToCell(data.Type, r, 1e-6);
    Eigen::Vector3d mapped;
    Eigen::Matrix3d jacobian;
    polynomial.Map(r, mapped, jacobian);
    return (mapped - p).norm() <= this->Tolerance + 1e-6 * this->CellSize(cell);
  }

  // The first cell that the line is inside at tMin or enters after it, up to tMax, and where.
  // With `strict`, only cells that the line leaves after tMin (not at it) count: after a ray
  // leaves a cell at tMin, the cell itself must not be found again.
  bool FindFirst(const Line& line, double tMin, double tMax, bool strict, std::uint32_t& cell,
    double& tEnter) const
  {
    double tNear;
    if (this->Nodes.empty() || !HitBox(this->Nodes[0], line, tMin, tMax, tNear))
    {
      return false;
    }
    struct Entry
    {
      std::uint32_t Node;
      double T;
    };
    Entry stack[kStackSize];
    int top = 0;
    stack[top++] = { 0, tNear };
    bool found = false;
    double best = tMax;
    double bestExit = -kInfinity;
    while (top > 0)
    {
      const Entry entry = stack[--top];
      if (entry.T > best || (found && entry.T == best))
      {
        continue;
      }
      const Node& node = this->Nodes[entry.Node];
      if (node.Count > 0)
      {
        for (std::uint32_t i = node.Index; i < node.Index + node.Count; ++i)
        {
          const std::uint32_t c = this->LeafCells[i];
          double a;
          double b;
          if (!this->Interval(c, line, tMin, strict, a, b) || (strict ? !(b > tMin) : !(b >= tMin)))
          {
            continue;
          }
          const double enter = std::max(a, tMin);
          if (enter < best || (enter == best && b > bestExit))
          {
            best = enter;
            bestExit = b;
            cell = c;
            found = true;
          }
        }
        continue;
      }
      double t[2];
      const bool hit[2] = { HitBox(this->Nodes[node.Index], line, tMin, best, t[0]),
        HitBox(this->Nodes[node.Index + 1], line, tMin, best, t[1]) };
      const int nearer = hit[0] && hit[1] ? (t[1] < t[0] ? 1 : 0) : (hit[0] ? 0 : 1);
      for (int k : { 1 - nearer, nearer }) // the nearer child on top
      {
        if (hit[k] && top < kStackSize)
        {
          stack[top++] = { node.Index + static_cast<std::uint32_t>(k), t[k] };
        }
      }
    }
    tEnter = best;
    return found;
  }

  // A cell (not degenerate) containing p, or kNone: first by the cells' half-spaces, then, for
  // points in none, by the parametric coordinates of non-convex cells.
  std::uint32_t FindContaining(const Eigen::Vector3d& p) const
  {
    if (this->Nodes.empty())
    {
      return kNone;
    }
    for (int pass = 0; pass < 2; ++pass)
    {
      std::uint32_t stack[kStackSize];
      int top = 0;
      stack[top++] = 0;
      while (top > 0)
      {
        const Node& node = this->Nodes[stack[--top]];
        if (p[0] < node.Lo[0] || p[0] > node.Hi[0] || p[1] < node.Lo[1] || p[1] > node.Hi[1] ||
            p[2] < node.Lo[2] || p[2] > node.Hi[2])
        {
          continue;
        }
        if (node.Count > 0)
        {
          for (std::uint32_t i = node.Index; i < node.Index + node.Count; ++i)
          {
            const std::uint32_t cell = this->LeafCells[i];
            if ((pass == 0 || this->IsNonConvex(cell)) && this->Contains(cell, p, pass == 1))
            {
              return cell;
            }
          }
          continue;
        }
        if (top + 2 <= kStackSize)
        {
          stack[top++] = node.Index;
          stack[top++] = node.Index + 1;
        }
      }
    }
    return kNone;
  }

  // The field at p (NaN outside the mesh).
  double ValueAt(const Eigen::Vector3d& p) const
  {
    const std::uint32_t cell = this->FindContaining(p);
    if (cell == kNone)
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (this->CellValues)
    {
      return this->Values[cell];
    }
    const CellData data = this->Gather(cell);
    const Polynomial polynomial(data);
    double r[3];
    Parametric(data, polynomial, p, r);
    ClampToCell(data.Type, r, kParametricMargin);
    return polynomial.Value(r);
  }

  // Per point (3 floats): the mean of the gradients of its cells' interpolants at the point,
  // computed the first time gradients are asked for (a scene without shading never pays).
  const std::vector<float>& PointGradients() const
  {
    std::call_once(this->PointGradientsOnce,
      [this]
      {
        const std::size_t points = this->Points.size() / 3;
        std::vector<double> sum(3 * points, 0.0);
        std::vector<std::uint32_t> count(points, 0);
        for (std::uint32_t cell = 0; cell < this->CellCount; ++cell)
        {
          if (this->IsDegenerate(cell))
          {
            continue;
          }
          const CellData data = this->Gather(cell);
          const std::uint32_t* ids = this->CellPoints.data() + 8 * static_cast<std::size_t>(cell);
          Eigen::Vector3d centre = Eigen::Vector3d::Zero();
          for (int k = 0; k < data.Points; ++k)
          {
            centre += data.X[k] / data.Points;
          }
          for (int k = 0; k < data.Points; ++k)
          {
            // Just inside the corner: a pyramid's map is singular at its apex.
            const Eigen::Vector3d g =
              this->PointGradient(cell, data.X[k] + 1e-3 * (centre - data.X[k]));
            if (g.allFinite())
            {
              for (int a = 0; a < 3; ++a)
              {
                sum[3 * static_cast<std::size_t>(ids[k]) + a] += g[a];
              }
              ++count[ids[k]];
            }
          }
        }
        this->PointGradientData.assign(3 * points, 0.0f);
        for (std::size_t i = 0; i < points; ++i)
        {
          for (int a = 0; a < 3 && count[i] > 0; ++a)
          {
            this->PointGradientData[3 * i + a] = static_cast<float>(sum[3 * i + a] / count[i]);
          }
        }
      });
    return this->PointGradientData;
  }

  // Largest edge of the cell's bounding box.
  double CellSize(std::uint32_t cell) const
  {
    const int n = kKinds[static_cast<int>(this->Kinds[cell])].Points;
    Eigen::Vector3d lo = this->Point(this->CellPoints[8 * static_cast<std::size_t>(cell)]);
    Eigen::Vector3d hi = lo;
    for (int k = 1; k < n; ++k)
    {
      const Eigen::Vector3d x =
        this->Point(this->CellPoints[8 * static_cast<std::size_t>(cell) + k]);
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    return (hi - lo).maxCoeff();
  }

  CellData Gather(std::uint32_t cell) const
  {
    CellData data;
    data.Type = this->Kinds[cell];
    data.Points = kKinds[static_cast<int>(data.Type)].Points;
    data.Direct = (this->Flags[cell] & kDirect) != 0;
    const std::uint32_t* ids = this->CellPoints.data() + 8 * static_cast<std::size_t>(cell);
    for (int k = 0; k < data.Points; ++k)
    {
      data.X[k] = this->Point(ids[k]);
      data.F[k] = this->CellValues ? 0.0 : static_cast<double>(this->Values[ids[k]]);
    }
    return data;
  }

  // Gradient of the point data's interpolant in `cell` at p: the parametric gradient turned
  // into world space by the inverse transposed Jacobian.
  Eigen::Vector3d PointGradient(std::uint32_t cell, const Eigen::Vector3d& p) const
  {
    const CellData data = this->Gather(cell);
    const Polynomial polynomial(data);
    double r[3];
    Parametric(data, polynomial, p, r);
    ClampToCell(data.Type, r, kParametricMargin);
    Eigen::Vector3d x;
    Eigen::Matrix3d jacobian;
    polynomial.Map(r, x, jacobian);
    const Eigen::Vector3d parametric = polynomial.Derivatives(r);
    const double det = jacobian.determinant();
    if (!(std::abs(det) > 0.0) || !std::isfinite(det))
    {
      return Eigen::Vector3d::Zero();
    }
    return jacobian.inverse().transpose() * parametric;
  }

  // Samples [begin, end) of the ray, all inside `cell` (or within the tolerance of it), and, when
  // `gradients` is given, their gradients in the same cell.
  void Interpolate(std::uint32_t cell, const Line& line, double t0, double dt, int begin, int end,
    float* out, float* gradients) const
  {
    if (gradients && begin < end)
    {
      const Eigen::Vector3d o(line.O[0], line.O[1], line.O[2]);
      const Eigen::Vector3d d(line.D[0], line.D[1], line.D[2]);
      for (int i = begin; i < end; ++i)
      {
        Store(this->GradientIn(cell, o + (t0 + i * dt) * d),
          gradients + 3 * static_cast<std::size_t>(i));
      }
    }
    if (this->CellValues)
    {
      std::fill(out + begin, out + end, this->Values[cell]);
      return;
    }
    const CellData data = this->Gather(cell);
    const Eigen::Vector3d o(line.O[0], line.O[1], line.O[2]);
    const Eigen::Vector3d d(line.D[0], line.D[1], line.D[2]);
    Direct direct;
    if (data.Direct && direct.Set(data))
    {
      // Inverted once: q is affine along the ray.
      const Eigen::Vector3d q0 = direct.Q(o);
      const Eigen::Vector3d qd = direct.Inverse * d;
      if (data.Type == Kind::Tetra)
      {
        // The field itself is linear along the ray.
        const double f0 = data.F[0];
        const Eigen::Vector3d df(data.F[1] - f0, data.F[2] - f0, data.F[3] - f0);
        const double alpha = f0 + df.dot(q0);
        const double beta = df.dot(qd);
        for (int i = begin; i < end; ++i)
        {
          out[i] = static_cast<float>(alpha + beta * (t0 + i * dt));
        }
        return;
      }
      const Polynomial polynomial(data);
      for (int i = begin; i < end; ++i)
      {
        double r[3];
        direct.Parametric(q0 + (t0 + i * dt) * qd, r);
        ClampToCell(data.Type, r, 0.0); // planar faces: only round-off and the tolerance out
        out[i] = static_cast<float>(polynomial.Value(r));
      }
      return;
    }
    // Newton's iteration, from the cell's centre for the first sample and from the previous
    // sample's coordinates for the next.
    const Polynomial polynomial(data);
    const double* centre = kKinds[static_cast<int>(data.Type)].Centre;
    double r[3] = { centre[0], centre[1], centre[2] };
    for (int i = begin; i < end; ++i)
    {
      polynomial.Invert(o + (t0 + i * dt) * d, r);
      double clamped[3] = { r[0], r[1], r[2] };
      ClampToCell(data.Type, clamped, kParametricMargin);
      out[i] = static_cast<float>(polynomial.Value(clamped));
    }
  }

  // Finds the first cell with the index, then walks across shared faces; after a boundary face
  // (a hole, a concavity), a degenerate cell or a stall, asks the index for the next cell along
  // the ray. Each index query moves strictly forward, and the walk's steps are bounded.
  void Walk(const Line& line, double t0, double dt, int count, double lo, double hi, float* out,
    float* gradients) const
  {
    const double tolerance = this->Tolerance;
    const std::size_t maxSteps = 4 * static_cast<std::size_t>(this->CellCount) + 1024;
    std::size_t steps = 0;
    int i = 0;
    double tSearch = lo;
    bool strict = false;
    std::uint32_t previous = kNone;
    double previousExit = -kInfinity;
    while (i < count)
    {
      std::uint32_t cell = kNone;
      double tIn = kInfinity;
      if (++steps > maxSteps || !this->FindFirst(line, tSearch, hi, strict, cell, tIn))
      {
        cell = kNone;
        tIn = kInfinity;
      }
      // Samples before the cell are outside the mesh, but those within the tolerance of the
      // cell left last or of the next one read those.
      for (; i < count && t0 + i * dt < tIn; ++i)
      {
        const double t = t0 + i * dt;
        if (previous != kNone && t <= previousExit + tolerance)
        {
          this->Interpolate(previous, line, t0, dt, i, i + 1, out, gradients);
        }
        else if (cell != kNone && t >= tIn - tolerance)
        {
          this->Interpolate(cell, line, t0, dt, i, i + 1, out, gradients);
        }
      }
      if (cell == kNone)
      {
        return;
      }
      std::uint8_t entryFace = kNoFace;
      int stall = 0;
      while (true)
      {
        std::uint32_t exitSide;
        double tOut = this->Exit(cell, line, entryFace, tIn, exitSide);
        if (exitSide == kNone || !(tOut >= tIn))
        {
          tOut = tIn; // clipped a corner (round-off), or a broken cell: no progress here
        }
        const std::int32_t next = exitSide == kNone ? -1 : this->Sides[exitSide].Neighbour;
        if (next >= 0)
        {
          // The walk is bound by memory latency: fetch the next cell while sampling this one.
          Prefetch(this->Sides.data() + this->SideBegin[next], 3);
          Prefetch(this->CellPoints.data() + 8 * static_cast<std::size_t>(next), 1);
        }
        int end = i;
        while (end < count && t0 + end * dt <= tOut)
        {
          ++end;
        }
        if (end > i)
        {
          this->Interpolate(cell, line, t0, dt, i, end, out, gradients);
          i = end;
        }
        if (i >= count)
        {
          return;
        }
        stall = tOut > tIn ? 0 : stall + 1;
        if (next < 0 || this->IsDegenerate(static_cast<std::uint32_t>(next)) || stall > kMaxStall ||
            ++steps > maxSteps)
        {
          previous = cell;
          previousExit = tOut;
          // The index finds a cell the ray leaves after tSearch; should the walk from it not move
          // on (a non-convex cell's triangles disagreeing by round-off), step past the point.
          tSearch = tOut > tSearch ? tOut : std::nextafter(tSearch + tolerance * 1e-3, kInfinity);
          strict = true;
          break;
        }
        cell = static_cast<std::uint32_t>(next);
        tIn = tOut;
        entryFace = this->Sides[exitSide].NeighbourFace;
      }
    }
  }

  bool CellValues;
  std::uint32_t CellCount = 0;
  std::vector<double> Points;            // 3 per point
  std::vector<float> Values;             // per point, or per cell (in the cells' order)
  std::vector<Kind> Kinds;               // per cell
  std::vector<std::uint32_t> CellPoints; // 8 per cell, kNone past the cell's points
  std::vector<std::uint32_t> SideBegin;  // per cell and one: its first side
  std::vector<Side> Sides;               // per cell, in order
  std::vector<std::uint8_t> Flags;       // per cell: kDegenerate, kNonConvex
  std::vector<Node> Nodes;
  std::vector<std::uint32_t> LeafCells;
  // Clip's box: the bounds of the cells' points, grown.
  double ClipLo[3] = { 0, 0, 0 };
  double ClipHi[3] = { 0, 0, 0 };
  double Tolerance = 0.0;
  std::array<double, 2> Range = { 0.0, 0.0 };
  mutable std::once_flag PointGradientsOnce;
  mutable std::vector<float> PointGradientData; // see PointGradients
};

} // namespace

std::shared_ptr<const Sampler> MakeUnstructuredSampler(
  const UnstructuredDescription& mesh, std::string& error, std::size_t* skippedCells)
{
  if (skippedCells)
  {
    *skippedCells = 0;
  }
  if (!mesh.points || mesh.numberOfPoints == 0)
  {
    error = "the mesh has no points";
    return nullptr;
  }
  if (mesh.numberOfPoints >= kNone)
  {
    error = "the mesh has too many points (at most 2^32 - 2)";
    return nullptr;
  }
  if (!mesh.offsets || !mesh.connectivity || !mesh.types || mesh.numberOfCells == 0)
  {
    error = "the mesh has no cells (offsets, connectivity or types missing)";
    return nullptr;
  }
  if (!mesh.values)
  {
    error = "the mesh has no scalar values";
    return nullptr;
  }
  if (mesh.offsets[0] < 0)
  {
    error = "the mesh's cell offsets start below 0";
    return nullptr;
  }
  std::vector<std::size_t> kept;
  std::size_t skipped = 0;
  const auto points = static_cast<std::int64_t>(mesh.numberOfPoints);
  for (std::size_t c = 0; c < mesh.numberOfCells; ++c)
  {
    const std::int64_t begin = mesh.offsets[c];
    const std::int64_t end = mesh.offsets[c + 1];
    if (end < begin)
    {
      error = "the mesh's cell offsets decrease at cell " + std::to_string(c);
      return nullptr;
    }
    const int kind = KindOf(mesh.types[c]);
    if (kind < 0)
    {
      ++skipped;
      continue;
    }
    if (end - begin != kKinds[kind].Points)
    {
      error = "cell " + std::to_string(c) + " (VTK type " + std::to_string(mesh.types[c]) +
              ") has " + std::to_string(end - begin) + " points instead of " +
              std::to_string(kKinds[kind].Points);
      return nullptr;
    }
    bool finite = true;
    for (std::int64_t k = begin; k < end; ++k)
    {
      const std::int64_t id = mesh.connectivity[k];
      if (id < 0 || id >= points)
      {
        error = "cell " + std::to_string(c) + " refers to point " + std::to_string(id) +
                ", outside [0, " + std::to_string(points) + ")";
        return nullptr;
      }
      const double* x = mesh.points + 3 * id;
      finite = finite && std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]);
    }
    if (!finite)
    {
      ++skipped;
      continue;
    }
    kept.push_back(c);
  }
  if (skippedCells)
  {
    *skippedCells = skipped;
  }
  if (kept.empty())
  {
    error = "the mesh has no supported cells (tetrahedra, hexahedra, voxels, wedges or pyramids "
            "with finite points); " +
            std::to_string(skipped) + " cells skipped";
    return nullptr;
  }
  if (kept.size() > kMaxCells)
  {
    error = "the mesh has too many cells (at most " + std::to_string(kMaxCells) + ")";
    return nullptr;
  }
  try
  {
    return std::make_shared<UnstructuredSampler>(mesh, kept);
  }
  catch (const std::bad_alloc&)
  {
    error = "not enough memory for the mesh's faces and index";
    return nullptr;
  }
}

} // namespace savr

// The unstructured sampler's gradients: per point from the cells' interpolants (point data),
// or central differences (cell data), computed once, in parallel, while shading asks for them.
#include "mesh/UnstructuredWalk.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <vector>

namespace savr
{
namespace unstructured
{

// The gradient in `cell` (which contains p). Point data: the points' gradients (each the mean
// of its cells' interpolant gradients there) interpolated like the values, so that shading is
// smooth across cells (the interpolant's own gradient jumps from cell to cell). Cell data:
// central differences one cell size apart, one-sided where a side is outside the mesh.
Eigen::Vector3d UnstructuredSampler::GradientIn(std::uint32_t cell, const Eigen::Vector3d& p) const
{
  if (!this->CellValues)
  {
    const std::vector<float>& pointGradients = this->PointGradients();
    CellVertices data = this->Gather(cell);
    const Polynomial polynomial(data);
    double r[3];
    Parametric(data, polynomial, p, r);
    ClampToCell(data.Kind, r, kParametricMargin);
    const std::uint32_t* ids = this->Faces.PointIds(cell);
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
  const double h = this->Faces.CellSize(cell);
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

// Per point (3 floats): the mean of the gradients of its cells' interpolants at the point,
// computed the first time gradients are asked for (a scene without shading never pays).
const std::vector<float>& UnstructuredSampler::PointGradients() const
{
  std::call_once(this->PointGradientsOnce,
    [this]
    {
      // The first caller may be a worker of a caller's parallel loop. Isolated, it does not
      // take another task of that loop while it waits for its own: such a task would ask for
      // the gradients again and wait for itself.
      tbb::this_task_arena::isolate([this] { this->ComputePointGradients(); });
    });
  return this->PointGradientData;
}

void UnstructuredSampler::ComputePointGradients() const
{
  const std::size_t points = this->Faces.PointCount();
  const std::uint32_t cells = this->Faces.CellCount();
  std::vector<double> sum(3 * points, 0.0);
  std::vector<std::uint32_t> count(points, 0);
  // The corners' gradients are computed in parallel a block of cells at a time and summed in
  // the cells' order, so that the sums do not depend on the thread count.
  constexpr std::uint32_t kBlock = 1u << 14;
  std::vector<Eigen::Vector3d> corners(8 * static_cast<std::size_t>(std::min(cells, kBlock)));
  for (std::uint32_t first = 0, last = 0; first < cells; first = last)
  {
    last = first + std::min(cells - first, kBlock);
    tbb::parallel_for(tbb::blocked_range<std::uint32_t>(first, last, 64),
      [&](const tbb::blocked_range<std::uint32_t>& range)
      {
        for (std::uint32_t cell = range.begin(); cell != range.end(); ++cell)
        {
          if (!this->Faces.IsDegenerate(cell))
          {
            this->CornerGradients(cell, &corners[8 * static_cast<std::size_t>(cell - first)]);
          }
        }
      });
    for (std::uint32_t cell = first; cell < last; ++cell)
    {
      if (this->Faces.IsDegenerate(cell))
      {
        continue;
      }
      const std::uint32_t* ids = this->Faces.PointIds(cell);
      const Eigen::Vector3d* g = &corners[8 * static_cast<std::size_t>(cell - first)];
      for (int k = 0; k < ShapeOf(this->Faces.Kind(cell)).Points; ++k)
      {
        if (g[k].allFinite())
        {
          for (int a = 0; a < 3; ++a)
          {
            sum[3 * static_cast<std::size_t>(ids[k]) + a] += g[k][a];
          }
          ++count[ids[k]];
        }
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
}

// The gradients of the point data's interpolant in `cell` at each of its corners, taken just
// inside the corner (a pyramid's map is singular at its apex), from one gathering of the cell.
void UnstructuredSampler::CornerGradients(std::uint32_t cell, Eigen::Vector3d* gradients) const
{
  const CellVertices data = this->Gather(cell);
  const Polynomial polynomial(data);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int k = 0; k < data.Points; ++k)
  {
    centre += data.X[k] / data.Points;
  }
  for (int k = 0; k < data.Points; ++k)
  {
    gradients[k] = InterpolantGradient(data, polynomial, data.X[k] + 1e-3 * (centre - data.X[k]));
  }
}

// Gradient of the interpolant of `data` at p: the parametric gradient turned into world space
// by the inverse transposed Jacobian; zero where the map is singular.
Eigen::Vector3d UnstructuredSampler::InterpolantGradient(
  const CellVertices& data, const Polynomial& polynomial, const Eigen::Vector3d& p)
{
  double r[3];
  Parametric(data, polynomial, p, r);
  ClampToCell(data.Kind, r, kParametricMargin);
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

} // namespace unstructured
} // namespace savr

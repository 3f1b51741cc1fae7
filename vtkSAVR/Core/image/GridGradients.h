#pragma once
// Per-point gradients of a regular grid, for shading and gradient opacity: computed once per
// data change (on first use, in parallel), kept as three integers per point (16 bits each, or,
// for 8-bit data, whose differences are exact in 10 bits, 10 bits each in one 32-bit word), and
// interpolated as the values are. The interpolation of the points' central differences equals
// the central difference, one point apart, of the interpolated field (exactly, away from the
// grid's faces), for three interpolations' reads instead of six interpolations.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace savr
{
namespace detail
{

/// The value grid a GradientGrid is computed over.
struct GradientShape
{
  long long Dims[3] = { 1, 1, 1 }; // values along each axis
  long long Step[3] = { 0, 0, 0 }; // array elements between neighbours along each axis
  int BlockShift = 3;              // log2 of the cells per block edge (as the sampler's)
  long long Blocks[3] = { 1, 1, 1 };
};

class GradientGrid
{
public:
  /// Computes the codes from `value(element)` (the value at an array element), in parallel
  /// over slices (each point depends on its neighbours only, so the result does not depend on
  /// the thread count). `indexToWorld` turns a gradient in index units into world units (the
  /// transpose of the linear part of the world-to-index map). `exactIntegers`: the values are
  /// integers whose differences fit the codes, which then hold them exactly; with `packed`
  /// (8-bit integers only: their differences fit 10 bits), three 10-bit codes per point in one
  /// 32-bit word (PackedData), the same codes in two thirds of the memory and one read.
  template <typename T>
  void Compute(const T* values, const GradientShape& shape, const Eigen::Matrix3d& indexToWorld,
    bool exactIntegers, bool packed = false);

  /// Instead of Compute: keeps no codes, only what computing one where it is asked for needs
  /// (the scale, for values that are not exact integers, takes one pass over them). CodeAt,
  /// InterpolateFrom and AtPointFrom then give the bits Compute's codes would.
  template <typename T>
  void PrepareOnDemand(const T* values, const GradientShape& shape,
    const Eigen::Matrix3d& indexToWorld, bool exactIntegers);
  bool OnDemand() const { return this->Demand; }

  /// The code of point (i, j, k) along `axis`, as Compute stores it.
  template <typename T>
  std::int32_t CodeAt(const T* values, long long i, long long j, long long k, int axis) const;

  /// Interpolate and AtPoint with codes computed from `values` (PrepareOnDemand).
  template <typename T>
  void InterpolateFrom(const T* values, const long long i0[3], const long long neighbour[3],
    const float w[3], float gradient[3]) const
  {
    const long long d[3] = { neighbour[0] != 0, neighbour[1] != 0, neighbour[2] != 0 };
    float index[3];
    for (int a = 0; a < 3; ++a)
    {
      const auto at = [&](long long x, long long y, long long z)
      { return static_cast<float>(this->CodeAt(values, i0[0] + x, i0[1] + y, i0[2] + z, a)); };
      const float c00 = Lerp(at(0, 0, 0), at(d[0], 0, 0), w[0]);
      const float c10 = Lerp(at(0, d[1], 0), at(d[0], d[1], 0), w[0]);
      const float c01 = Lerp(at(0, 0, d[2]), at(d[0], 0, d[2]), w[0]);
      const float c11 = Lerp(at(0, d[1], d[2]), at(d[0], d[1], d[2]), w[0]);
      index[a] = Lerp(Lerp(c00, c10, w[1]), Lerp(c01, c11, w[1]), w[2]);
    }
    this->World(index, gradient);
  }
  template <typename T>
  void AtPointFrom(const T* values, const long long i[3], float gradient[3]) const
  {
    const float index[3] = { static_cast<float>(this->CodeAt(values, i[0], i[1], i[2], 0)),
      static_cast<float>(this->CodeAt(values, i[0], i[1], i[2], 1)),
      static_cast<float>(this->CodeAt(values, i[0], i[1], i[2], 2)) };
    this->World(index, gradient);
  }

  bool Empty() const { return this->Codes.empty() && this->Packed.empty(); }
  std::size_t Bytes() const
  {
    return this->Codes.capacity() * sizeof(std::int16_t) +
           this->Packed.capacity() * sizeof(std::uint32_t) +
           this->ZeroBlocks.capacity() * sizeof(std::int32_t);
  }
  /// Bytes Compute takes for a grid of `points` points in `blocks` blocks.
  static std::size_t BytesFor(std::size_t points, std::size_t blocks, bool packed = false)
  {
    return (packed ? points * sizeof(std::uint32_t)
                   : (3 * points + kPadding) * sizeof(std::int16_t)) +
           blocks * sizeof(std::int32_t);
  }

  /// Three codes per point, point (i, j, k) at 3 (i + Dims.x (j + Dims.y k)); padded so that an
  /// 8-byte read at the last point stays inside.
  const std::int16_t* CodeData() const { return this->Codes.data(); }
  /// Packed grids (else null): point (i, j, k)'s codes at i + Dims.x (j + Dims.y k), x in bits
  /// 0-9, y in 10-19, z in 20-29, each a two's complement 10-bit integer.
  const std::uint32_t* PackedData() const
  {
    return this->Packed.empty() ? nullptr : this->Packed.data();
  }
  /// The codes of one packed word.
  static std::int32_t Unpack(std::uint32_t word, int axis)
  {
    return static_cast<std::int32_t>(word << (22 - 10 * axis)) >> 22;
  }
  /// Per block of cells: 1 when every code of its points (faces included) is zero.
  const std::int32_t* ZeroBlockData() const { return this->ZeroBlocks.data(); }
  /// Row-major 3x3: the world gradient is ToWorld times the interpolated codes.
  const float* ToWorldData() const { return this->ToWorld; }
  const long long* PointStep() const { return this->Step; }

  /// The world gradient at lower corner `i0` with weights `w` (as the sampler's trilinear
  /// interpolation takes them); the AVX2 kernel computes the same bits.
  void Interpolate(
    const long long i0[3], const long long neighbour[3], const float w[3], float gradient[3]) const
  {
    const long long point = i0[0] * this->Step[0] + i0[1] * this->Step[1] + i0[2] * this->Step[2];
    const long long sx = neighbour[0];
    const long long sy = neighbour[1];
    const long long sz = neighbour[2];
    float index[3];
    for (int a = 0; a < 3; ++a)
    {
      const auto at = [&](long long o) { return static_cast<float>(this->Code(point + o, a)); };
      const float c00 = Lerp(at(0), at(sx), w[0]);
      const float c10 = Lerp(at(sy), at(sy + sx), w[0]);
      const float c01 = Lerp(at(sz), at(sz + sx), w[0]);
      const float c11 = Lerp(at(sz + sy), at(sz + sy + sx), w[0]);
      index[a] = Lerp(Lerp(c00, c10, w[1]), Lerp(c01, c11, w[1]), w[2]);
    }
    this->World(index, gradient);
  }

  /// The world gradient of point `i` (nearest interpolation).
  void AtPoint(const long long i[3], float gradient[3]) const
  {
    const long long point = i[0] * this->Step[0] + i[1] * this->Step[1] + i[2] * this->Step[2];
    const float index[3] = { static_cast<float>(this->Code(point, 0)),
      static_cast<float>(this->Code(point, 1)), static_cast<float>(this->Code(point, 2)) };
    this->World(index, gradient);
  }

  static float Lerp(float a, float b, float w) { return a + w * (b - a); }

private:
  std::int32_t Code(long long point, int axis) const
  {
    return this->Packed.empty() ? this->Codes[static_cast<std::size_t>(3 * point + axis)]
                                : Unpack(this->Packed[static_cast<std::size_t>(point)], axis);
  }
  // Adding zero turns -0 into +0, so that every path gives the same zero.
  void World(const float index[3], float gradient[3]) const
  {
    const float* m = this->ToWorld;
    for (int r = 0; r < 3; ++r)
    {
      gradient[r] =
        ((m[3 * r] * index[0] + m[3 * r + 1] * index[1]) + m[3 * r + 2] * index[2]) + 0.0f;
    }
  }
  // Runs body(k0, k1) over slices [k0, k1) of [0, slices), in parallel.
  static void ForSlices(long long slices, const std::function<void(long long, long long)>& body);
  void FinishBlocks(const GradientShape& shape);

  // The difference Compute's codes hold, for point (i, j, k) along `axis` (see Compute).
  template <typename T>
  static double Difference(
    const T* values, const GradientShape& shape, long long i, long long j, long long k, int axis);
  // The ToWorld map for codes that are differences times `scale`.
  void SetToWorld(const Eigen::Matrix3d& indexToWorld, double scale);
  // The largest difference's magnitude (for the scale of values that are not exact integers).
  template <typename T>
  static double LargestDifference(const T* values, const GradientShape& shape);

  static constexpr std::size_t kPadding = 4;
  bool Demand = false;      // PrepareOnDemand: no codes kept
  GradientShape Shape;      // when on demand
  double Scale = 1.0;       // codes per difference, when on demand
  bool Exact = false;       // the differences are the codes, when on demand
  std::vector<std::int16_t> Codes;   // 3 per point, unless packed
  std::vector<std::uint32_t> Packed; // 1 per point, when packed
  std::vector<std::int32_t> ZeroBlocks;
  float ToWorld[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  long long Step[3] = { 1, 1, 1 }; // points between neighbours along each axis
};

template <typename T>
void GradientGrid::Compute(const T* values, const GradientShape& shape,
  const Eigen::Matrix3d& indexToWorld, bool exactIntegers, bool packed)
{
  packed = packed && exactIntegers;
  const long long nx = shape.Dims[0];
  const long long ny = shape.Dims[1];
  const long long nz = shape.Dims[2];
  this->Step[0] = 1;
  this->Step[1] = nx;
  this->Step[2] = nx * ny;
  // Twice the gradient in index units, row by row: the central difference, or twice the
  // one-sided one at a face; 0 along an axis with a single value or where a neighbour is not
  // finite. `out` takes 3 per point of row (j, k).
  const auto differences = [&](long long j, long long k, double* out)
  {
    const T* row = values + j * shape.Step[1] + k * shape.Step[2];
    const T* rows[3][2]; // per axis: the lower and the upper neighbour's row
    double factor[3];    // per axis: 1, 2 at a face, 0 along a single value
    const long long at[3] = { 0, j, k };
    for (int a = 1; a < 3; ++a)
    {
      const long long n = shape.Dims[a];
      rows[a][0] = at[a] > 0 ? row - shape.Step[a] : row;
      rows[a][1] = at[a] + 1 < n ? row + shape.Step[a] : row;
      factor[a] = n < 2 ? 0.0 : (at[a] == 0 || at[a] + 1 == n ? 2.0 : 1.0);
    }
    const long long sx = shape.Step[0];
    for (long long i = 0; i < nx; ++i)
    {
      const long long lo = i > 0 ? i - 1 : i;
      const long long hi = i + 1 < nx ? i + 1 : i;
      const double fx = nx < 2 ? 0.0 : (i == 0 || i + 1 == nx ? 2.0 : 1.0);
      const double d[3] = { fx * (static_cast<double>(row[hi * sx]) - row[lo * sx]),
        factor[1] * (static_cast<double>(rows[1][1][i * sx]) - rows[1][0][i * sx]),
        factor[2] * (static_cast<double>(rows[2][1][i * sx]) - rows[2][0][i * sx]) };
      for (int a = 0; a < 3; ++a)
      {
        out[3 * i + a] = std::isfinite(d[a]) ? d[a] : 0.0;
      }
    }
  };
  // Codes are the differences times `scale`: 1 for integers whose differences fit, else what
  // maps the largest difference to the largest code.
  double scale = 1.0;
  if (!exactIntegers)
  {
    std::vector<double> sliceMax(static_cast<std::size_t>(nz), 0.0);
    ForSlices(nz,
      [&](long long k0, long long k1)
      {
        std::vector<double> d(3 * static_cast<std::size_t>(nx));
        for (long long k = k0; k < k1; ++k)
        {
          double m = 0.0;
          for (long long j = 0; j < ny; ++j)
          {
            differences(j, k, d.data());
            for (const double v : d)
            {
              m = std::max(m, std::abs(v));
            }
          }
          sliceMax[static_cast<std::size_t>(k)] = m;
        }
      });
    double largest = 0.0;
    for (const double m : sliceMax)
    {
      largest = std::max(largest, m);
    }
    scale = largest > 0.0 ? 32767.0 / largest : 1.0;
  }
  this->SetToWorld(indexToWorld, scale);
  this->Demand = false;
  const std::size_t points = static_cast<std::size_t>(nx * ny * nz);
  this->Codes.clear();
  this->Codes.shrink_to_fit();
  this->Packed.clear();
  this->Packed.shrink_to_fit();
  if (packed)
  {
    this->Packed.assign(points, 0u);
  }
  else
  {
    this->Codes.assign(3 * points + kPadding, 0);
  }
  std::int16_t* codes = this->Codes.data();
  std::uint32_t* words = this->Packed.data();
  ForSlices(nz,
    [&](long long k0, long long k1)
    {
      std::vector<double> d(3 * static_cast<std::size_t>(nx));
      for (long long k = k0; k < k1; ++k)
        for (long long j = 0; j < ny; ++j)
        {
          differences(j, k, d.data());
          if (packed)
          {
            // Exact integers of at most 510 in magnitude: each fits 10 bits.
            std::uint32_t* out = words + nx * (j + ny * k);
            for (long long i = 0; i < nx; ++i)
            {
              std::uint32_t word = 0;
              for (int a = 0; a < 3; ++a)
              {
                const double c = std::min(std::max(d[3 * i + a], -511.0), 511.0);
                word |= (static_cast<std::uint32_t>(static_cast<std::int32_t>(c)) & 0x3FFu)
                        << (10 * a);
              }
              out[i] = word;
            }
            continue;
          }
          std::int16_t* out = codes + 3 * nx * (j + ny * k);
          for (long long e = 0; e < 3 * nx; ++e)
          {
            const double c = exactIntegers ? d[e] : std::round(d[e] * scale);
            out[e] = static_cast<std::int16_t>(std::min(std::max(c, -32767.0), 32767.0));
          }
        }
    });
  this->FinishBlocks(shape);
}

template <typename T>
double GradientGrid::Difference(
  const T* values, const GradientShape& shape, long long i, long long j, long long k, int axis)
{
  // As Compute's rows: the central difference, twice the one-sided one at a face, 0 along an
  // axis with a single value or where a neighbour is not finite.
  const long long at[3] = { i, j, k };
  const long long n = shape.Dims[axis];
  if (n < 2)
  {
    return 0.0;
  }
  const T* point = values + i * shape.Step[0] + j * shape.Step[1] + k * shape.Step[2];
  const T* lo = at[axis] > 0 ? point - shape.Step[axis] : point;
  const T* hi = at[axis] + 1 < n ? point + shape.Step[axis] : point;
  const double factor = at[axis] == 0 || at[axis] + 1 == n ? 2.0 : 1.0;
  const double d = factor * (static_cast<double>(*hi) - *lo);
  return std::isfinite(d) ? d : 0.0;
}

template <typename T>
double GradientGrid::LargestDifference(const T* values, const GradientShape& shape)
{
  std::vector<double> sliceMax(static_cast<std::size_t>(shape.Dims[2]), 0.0);
  ForSlices(shape.Dims[2],
    [&](long long k0, long long k1)
    {
      for (long long k = k0; k < k1; ++k)
      {
        double m = 0.0;
        for (long long j = 0; j < shape.Dims[1]; ++j)
          for (long long i = 0; i < shape.Dims[0]; ++i)
            for (int a = 0; a < 3; ++a)
            {
              m = std::max(m, std::abs(Difference(values, shape, i, j, k, a)));
            }
        sliceMax[static_cast<std::size_t>(k)] = m;
      }
    });
  double largest = 0.0;
  for (const double m : sliceMax)
  {
    largest = std::max(largest, m);
  }
  return largest;
}

template <typename T>
void GradientGrid::PrepareOnDemand(const T* values, const GradientShape& shape,
  const Eigen::Matrix3d& indexToWorld, bool exactIntegers)
{
  this->Codes.clear();
  this->Codes.shrink_to_fit();
  this->Packed.clear();
  this->Packed.shrink_to_fit();
  this->ZeroBlocks.clear();
  this->ZeroBlocks.shrink_to_fit();
  this->Step[0] = 1;
  this->Step[1] = shape.Dims[0];
  this->Step[2] = shape.Dims[0] * shape.Dims[1];
  this->Shape = shape;
  this->Exact = exactIntegers;
  double scale = 1.0;
  if (!exactIntegers)
  {
    const double largest = LargestDifference(values, shape);
    scale = largest > 0.0 ? 32767.0 / largest : 1.0;
  }
  this->Scale = scale;
  this->SetToWorld(indexToWorld, scale);
  this->Demand = true;
}

template <typename T>
std::int32_t GradientGrid::CodeAt(
  const T* values, long long i, long long j, long long k, int axis) const
{
  const double d = Difference(values, this->Shape, i, j, k, axis);
  // Exact integers (8-bit data) are at most 510 in magnitude: within the packed codes' 10 bits.
  const double c = this->Exact ? d : std::round(d * this->Scale);
  return static_cast<std::int32_t>(std::min(std::max(c, -32767.0), 32767.0));
}

} // namespace detail
} // namespace savr

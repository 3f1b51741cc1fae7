#include "FrameLoop.h"

#include "GridKernel.h"

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace savr
{

namespace
{
// A ray never takes more samples than this per frame; longer rays are cut (and the caller is
// expected to have refused such settings before).
constexpr double kMaxSamplesPerRay = 1 << 22;
// Samples taken at once by a single pass, which stops sampling a ray once it is opaque.
constexpr int kChunk = 64;

// Composites a tabulated sample (its opacity, then its colour times it) front to back.
inline void CompositeEntry(const double* entry, Eigen::Array3d& C, double& T)
{
  C += T * Eigen::Array3d(entry[1], entry[2], entry[3]);
  T *= 1.0 - entry[0];
}

// A single composite pass without lighting, gradient opacity or second codes: samples `step`
// apart from u * step on, blended as SampleStream feeds CompositeBlendT<false> (each sample
// stands for the interval between the midpoints to its neighbours, the first from the ray
// entry, the last to the exit), but with no per-sample bookkeeping: interior intervals are
// one step (`premultiplied`: PremultipliedTable for the step), so an interior sample costs a
// lookup and a composite without branches (a transparent one adds zeros, changing no bit).
// Adds the samples taken to `taken`.
Pixel PlainComposite(const Sampler& source, const SampleEncoding& encoding,
  const TransferFunctionTable& tf, const AlphaCache& alphas, const Ray& r, double tEnter,
  double length, double step, double u, int n, double termination, const SkipMask* skip,
  std::uint32_t nanCode, const double* premultiplied, std::vector<float>& values,
  std::vector<std::uint32_t>& codes, std::uint64_t& taken)
{
  const bool vectorEncode = detail::HaveAVX2();
  const std::uint32_t infiniteCode = encoding.HasNaNCode ? encoding.NaNCode : 0u;
  const auto pos = [&](int k) { return (k + u) * step; };
  // The last sample inside the ray.
  int last = n - 1;
  while (last >= 0 && !(pos(last) < length))
  {
    --last;
  }
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();
  for (int j0 = 0, count = 0; j0 <= last; j0 += count)
  {
    // Shorter pieces as the ray nears its end, so that few samples are taken past it.
    const int piece = T > 0.5 ? kChunk : (T > 0.1 ? kChunk / 2 : kChunk / 4);
    count = std::min(piece, last + 1 - j0);
    source.SampleRay(r, tEnter + (j0 + u) * step, step, count, values.data(), skip);
    taken += count;
    // The codes of the piece: as Encode gives them, NaN as nanCode.
    if (vectorEncode)
    {
      if (!detail::EncodeAVX2(encoding.Offset, encoding.Scale, encoding.Levels, infiniteCode,
            nanCode, values.data(), count, codes.data()) &&
          tf.Extinction(nanCode) == 0.0)
      {
        continue; // all skipped or outside: nothing to add
      }
    }
    else
    {
      for (int i = 0; i < count; ++i)
      {
        const float v = values[i];
        codes[i] = v == v ? encoding.Encode(v) : nanCode;
      }
    }
    // Interior samples (not the first or last of the ray) in a tight loop.
    const int interiorBegin = j0 == 0 ? 1 : 0;
    const int interiorEnd = std::max(interiorBegin, std::min(count, last - j0));
    for (int i = 0; i < count; ++i)
    {
      if (i == interiorBegin)
      {
        for (; i < interiorEnd; ++i)
        {
          const std::uint32_t code = codes[i];
          // One step: the opacity and the colour times it, tabulated.
          const double* entry = premultiplied + 4 * static_cast<std::size_t>(code);
          CompositeEntry(entry, C, T);
          if (T < termination)
          {
            return detail::FrontToBack(C, T);
          }
        }
        if (i >= count)
        {
          break;
        }
      }
      const std::uint32_t code = codes[i];
      const int k = j0 + i;
      if (tf.Extinction(code) == 0.0)
      {
        continue;
      }
      const double lo = k > 0 ? 0.5 * (pos(k - 1) + pos(k)) : 0.0;
      const double hi = k < last ? 0.5 * (pos(k) + pos(k + 1)) : length;
      const double a = alphas.Alpha(tf, code, hi - lo);
      const float* rgb = tf.Color(code);
      C += (T * a) * Eigen::Array3d(rgb[0], rgb[1], rgb[2]);
      T *= 1.0 - a;
      if (T < termination)
      {
        return detail::FrontToBack(C, T);
      }
    }
  }
  return detail::FrontToBack(C, T);
}

// Per code, the opacity of an interval of length h and the colour times it.
void PremultipliedTable(const TransferFunctionTable& tf, double h, std::vector<double>& table)
{
  table.resize(4 * static_cast<std::size_t>(tf.Size()));
  for (std::uint32_t c = 0; c < tf.Size(); ++c)
  {
    const float* rgb = tf.Color(c);
    double* entry = &table[4 * static_cast<std::size_t>(c)];
    entry[0] = tf.Extinction(c) > 0.0 ? tf.IntervalAlpha(c, h) : 0.0;
    for (int i = 0; i < 3; ++i)
    {
      entry[1 + i] = entry[0] * rgb[i];
    }
  }
}

// Rows [begin, end) of a stored ray whose every rank has a table (`tables[s]`: the premultiplied
// table of rank s's interval), composited front to back; `F` frames when above 0, else
// `ray.frames` (a known count lets the compiler unroll the row). Returns whether the ray
// reached the termination transmittance.
template <int F, typename Code>
bool CompositeRows(const RayLayout<Code>& ray, const double* const* tables, int begin, int end,
  Eigen::Array3d& C, double& T, double termination)
{
  const int frames = F > 0 ? F : ray.frames;
  const int* order = ray.order;
  const std::size_t capacity = static_cast<std::size_t>(ray.capacity);
  // Locals, which stay in registers: through the references, every sample would store them
  // (a table read might alias them).
  Eigen::Array3d c = C;
  double t = T;
  bool stopped = false;
  for (int j = begin; j < end && !stopped; ++j)
  {
    const Code* row = ray.codes + static_cast<std::size_t>(j) * capacity;
    for (int s = 0; s < frames; ++s)
    {
      CompositeEntry(tables[s] + 4 * static_cast<std::size_t>(row[order[s]]), c, t);
      if (t < termination)
      {
        stopped = true;
        break;
      }
    }
  }
  C = c;
  T = t;
  return stopped;
}

// Rows [begin, end) of a stored ray, every rank with a table, as CompositeRows<0> does, at
// any frame count.
template <typename Code>
bool CompositeRowsOf(const RayLayout<Code>& ray, const double* const* tables, int begin, int end,
  Eigen::Array3d& C, double& T, double termination)
{
  switch (ray.frames)
  {
    case 1:
      return CompositeRows<1>(ray, tables, begin, end, C, T, termination);
    case 2:
      return CompositeRows<2>(ray, tables, begin, end, C, T, termination);
    case 3:
      return CompositeRows<3>(ray, tables, begin, end, C, T, termination);
    case 4:
      return CompositeRows<4>(ray, tables, begin, end, C, T, termination);
    default:
      return CompositeRows<0>(ray, tables, begin, end, C, T, termination);
  }
}

// Finds the rows of a stored ray that hold a code at or above a threshold (below it, every
// code is transparent), looking only at the slots of the frames taken. With AVX2, 32 bytes at
// a time where a row's slots divide them.
template <typename Code>
struct RowScan
{
  std::uint32_t Threshold = 0; // codes below it are transparent; 0: none known to be
  int Capacity = 1;            // slots per row
  int Frames = 1;              // slots in use, from the first
  bool Vector = false;         // 32 bytes at a time (Mask: which of them are slots in use)
  alignas(32) Code Mask[32 / sizeof(Code)] = {};

  RowScan(std::uint32_t threshold, int capacity, int frames, bool vectorize)
    : Threshold(threshold)
    , Capacity(capacity)
    , Frames(frames)
  {
    constexpr int lanes = 32 / sizeof(Code);
    this->Vector = vectorize && capacity > 0 && lanes % capacity == 0 &&
                   threshold <= static_cast<Code>(~Code(0));
    for (int k = 0; this->Vector && k < lanes; ++k)
    {
      this->Mask[k] = k % capacity < frames ? static_cast<Code>(~Code(0)) : Code(0);
    }
  }

  /// The first row in [0, rows) with a code at or above the threshold; `rows` when none.
  int First(const Code* codes, int rows) const
  {
    int j = 0;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    if (this->Vector)
    {
      // Whole vectors, then the rows after them (vectors hold whole rows).
      const std::size_t end = static_cast<std::size_t>(rows) * this->Capacity;
      const std::size_t i = this->FirstVector(codes, end);
      j = static_cast<int>((i < end ? i : end - end % (32 / sizeof(Code))) / this->Capacity);
    }
#endif
    for (; j < rows && !this->Hit(codes, j); ++j)
    {
    }
    return j;
  }

  /// The last row in [begin, rows) with a code at or above the threshold; begin - 1 when none.
  int Last(const Code* codes, int begin, int rows) const
  {
    int j = rows;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    if (this->Vector)
    {
      // Whole vectors back from the end, then the rows before them.
      const std::size_t first = static_cast<std::size_t>(begin) * this->Capacity;
      const std::size_t end = static_cast<std::size_t>(rows) * this->Capacity;
      const std::size_t found = this->LastVector(codes, first, end);
      if (found != static_cast<std::size_t>(-1))
      {
        return static_cast<int>(found / this->Capacity);
      }
      j = static_cast<int>((first + (end - first) % (32 / sizeof(Code))) / this->Capacity);
    }
#endif
    while (j-- > begin)
    {
      if (this->Hit(codes, j))
      {
        return j;
      }
    }
    return begin - 1;
  }

private:
  // Whether row j has a code at or above the threshold in a slot in use.
  bool Hit(const Code* codes, int j) const
  {
    const Code* row = codes + static_cast<std::size_t>(j) * this->Capacity;
    for (int s = 0; s < this->Frames; ++s)
    {
      if (row[s] >= this->Threshold)
      {
        return true;
      }
    }
    return false;
  }

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  // Lanes at or above the threshold in slots in use, as a byte mask.
  __attribute__((target("avx2"))) int Hits(const Code* at) const
  {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(at));
    const __m256i mask = _mm256_load_si256(reinterpret_cast<const __m256i*>(this->Mask));
    __m256i above;
    if (sizeof(Code) == 1)
    {
      const __m256i t = _mm256_set1_epi8(static_cast<char>(this->Threshold));
      above = _mm256_cmpeq_epi8(_mm256_max_epu8(v, t), v);
    }
    else
    {
      const __m256i t = _mm256_set1_epi16(static_cast<short>(this->Threshold));
      above = _mm256_cmpeq_epi16(_mm256_max_epu16(v, t), v);
    }
    return _mm256_movemask_epi8(_mm256_and_si256(above, mask));
  }
  // The first code in [0, end) that is a hit, in whole vectors from 0; `end` when none there.
  __attribute__((target("avx2"))) std::size_t FirstVector(const Code* codes, std::size_t end) const
  {
    constexpr std::size_t lanes = 32 / sizeof(Code);
    for (std::size_t i = 0; i + lanes <= end; i += lanes)
    {
      const int hits = this->Hits(codes + i);
      if (hits != 0)
      {
        return i +
               static_cast<std::size_t>(__builtin_ctz(static_cast<unsigned>(hits))) / sizeof(Code);
      }
    }
    return end;
  }
  // The last code in [first, end) that is a hit, in whole vectors back from `end`; -1 when none
  // there.
  __attribute__((target("avx2"))) std::size_t LastVector(
    const Code* codes, std::size_t first, std::size_t end) const
  {
    constexpr std::size_t lanes = 32 / sizeof(Code);
    for (std::size_t i = end; i >= first + lanes; i -= lanes)
    {
      const int hits = this->Hits(codes + i - lanes);
      if (hits != 0)
      {
        return i - lanes +
               static_cast<std::size_t>(31 - __builtin_clz(static_cast<unsigned>(hits))) /
                 sizeof(Code);
      }
    }
    return static_cast<std::size_t>(-1);
  }
#endif
};

// A stored ray composited without lighting, gradient opacity or second codes: as Walk feeds
// SampleStream and CompositeBlendT<false>, but with each interior sample's interval known from
// its rank among the offsets (`tables[s]`: the premultiplied table for the interval of rank s,
// or null when it has none), so that a sample costs a lookup and a composite without branches.
// In three steps, so that the rows between the first and the last can also be walked for
// several rays at once: Begin (the first row), the rows between, End (the last row).
// Rows at either end whose every code is transparent (below `scan`'s threshold) are passed over:
// a transparent sample multiplies the transmittance by exactly 1 and adds exactly 0, so the
// pixel keeps every bit. (In front of and behind most data lie such rows: air, background.)
template <typename Code>
class PlainWalk
{
public:
  PlainWalk(const RayLayout<Code>& ray, const TransferFunctionTable& tf, const AlphaCache& alphas,
    const double* const* tables, const RowScan<Code>* scan, double termination)
    : Ray(ray)
    , TF(tf)
    , Alphas(alphas)
    , Tables(tables)
    , Termination(termination)
  {
    // The last valid sample: only the last row can reach past the exit.
    this->LastRow = ray.samplesPerFrame - 1;
    this->LastRank = ray.frames - 1;
    while (this->LastRow >= 0 && !(this->Position(this->LastRow, this->LastRank) < ray.length))
    {
      if (--this->LastRank < 0)
      {
        this->LastRank = ray.frames - 1;
        --this->LastRow;
      }
    }
    this->AllTabled = true;
    for (int s = 0; s < ray.frames; ++s)
    {
      this->AllTabled = this->AllTabled && tables[s];
    }
    // The first and the last row with a code that may not be transparent (every slot in use
    // is looked at, even past the last sample: that can only keep more rows).
    this->Lead = 0;
    this->Tail = this->LastRow;
    if (scan && scan->Threshold > 0 && scan->Capacity == ray.capacity)
    {
      this->Lead = scan->First(ray.codes, this->LastRow + 1);
      if (this->Lead <= this->LastRow)
      {
        this->Tail = scan->Last(ray.codes, this->Lead, this->LastRow + 1);
      }
    }
    this->Done = this->Lead > this->LastRow;
  }

  /// Composites the first row; false when the ray is done (empty, transparent or opaque
  /// already).
  bool Begin()
  {
    this->Done = this->Done || (this->Lead == 0 && this->Row(0));
    return !this->Done;
  }
  /// Composites rows [From(), To()), between the first and the last; false when the ray is done.
  bool Rows()
  {
    if (this->Done)
    {
      return false;
    }
    const int begin = this->From();
    const int end = this->To();
    if (this->AllTabled)
    {
      this->Done =
        CompositeRowsOf(this->Ray, this->Tables, begin, end, this->C, this->T, this->Termination);
    }
    else
    {
      for (int j = begin; j < end && !this->Done; ++j)
      {
        this->Done = this->Row(j);
      }
    }
    return !this->Done;
  }
  /// Composites the last row (when it is not the first) and gives the pixel.
  Pixel End()
  {
    if (!this->Done && this->LastRow > 0 && this->Tail == this->LastRow)
    {
      this->Row(this->LastRow);
    }
    return this->LastRow < 0 ? Pixel::Zero() : detail::FrontToBack(this->C, this->T);
  }
  /// Rows [From(), To()) lie between the first and the last, and hold every row there that
  /// is not transparent.
  int From() const { return std::max(1, this->Lead); }
  int To() const { return std::min(this->LastRow, this->Tail + 1); }
  Pixel Walk()
  {
    if (this->Begin())
    {
      this->Rows();
    }
    return this->End();
  }

  const RayLayout<Code>& Ray;
  const TransferFunctionTable& TF;
  const AlphaCache& Alphas;
  const double* const* Tables;
  const double Termination;
  int LastRow = 0;
  int LastRank = 0;
  int Lead = 0; // rows before it are transparent
  int Tail = 0; // rows after it are transparent
  bool AllTabled = true;
  bool Done = false;
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();

private:
  double Position(int j, int s) const
  {
    return (j + this->Ray.u[this->Ray.order[s]]) * this->Ray.dt;
  }

  // A sample whose interval is computed from its neighbours' positions (ray ends, and
  // intervals without a table).
  void General(int j, int s, std::uint32_t code)
  {
    if (this->TF.Extinction(code) == 0.0)
    {
      return;
    }
    const int frames = this->Ray.frames;
    const double here = this->Position(j, s);
    const bool first = j == 0 && s == 0;
    const bool last = j == this->LastRow && s == this->LastRank;
    const double before = s > 0 ? this->Position(j, s - 1) : this->Position(j - 1, frames - 1);
    const double after = s + 1 < frames ? this->Position(j, s + 1) : this->Position(j + 1, 0);
    const double lo = first ? 0.0 : 0.5 * (before + here);
    const double hi = last ? this->Ray.length : 0.5 * (here + after);
    const double a = this->Alphas.Alpha(this->TF, code, hi - lo);
    const float* rgb = this->TF.Color(code);
    this->C += (this->T * a) * Eigen::Array3d(rgb[0], rgb[1], rgb[2]);
    this->T *= 1.0 - a;
  }

  // A row sample by sample: its ranks' tables where they have one, except at the ray's ends.
  // Returns whether the ray reached the termination transmittance.
  bool Row(int j)
  {
    const Code* codes = this->Ray.codes + static_cast<std::size_t>(j) * this->Ray.capacity;
    const int ranks = j == this->LastRow ? this->LastRank + 1 : this->Ray.frames;
    const bool edge = j == 0 || j == this->LastRow;
    for (int s = 0; s < ranks; ++s)
    {
      const std::uint32_t code = codes[this->Ray.order[s]];
      const double* table = this->Tables[s];
      if (table && !(edge && ((j == 0 && s == 0) || (j == this->LastRow && s == this->LastRank))))
      {
        CompositeEntry(table + 4 * static_cast<std::size_t>(code), this->C, this->T);
      }
      else
      {
        this->General(j, s, code);
      }
      if (this->T < this->Termination)
      {
        return true;
      }
    }
    return false;
  }
};

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
// Rows [From(), To()) of four rays at once, every rank of each with a table, after their first
// rows: each lane computes exactly what CompositeRows computes for its ray (the same products
// and sums in the same order), and stops where that would or at its To().
template <int F, typename Code>
__attribute__((target("avx2"))) void CompositeRowsFour(PlainWalk<Code>* const walks[4])
{
  constexpr int frames = F;
  const double termination = walks[0]->Termination;
  double t[4];
  double c[3][4];
  double rows[4];  // rows each lane walks
  int lastStep[4]; // the last of them, counted from its first (0 for none)
  int steps = 0;
  // Per lane and rank: where its codes start (its From() row) and its table.
  const Code* first[frames][4];
  const double* table[frames][4];
  std::size_t capacity[4];
  for (int i = 0; i < 4; ++i)
  {
    const PlainWalk<Code>& w = *walks[i];
    t[i] = w.T;
    for (int k = 0; k < 3; ++k)
    {
      c[k][i] = w.C[k];
    }
    // Every lane reads a row of its own ray at every step, and adds nothing once it rests:
    // a lane with no rows to walk (a ray done already: opaque in its first row, transparent,
    // or with no valid sample) reads its row 0 again and again, and one past its rows its
    // last row.
    const int count = w.Done ? 0 : std::max(0, w.To() - w.From());
    rows[i] = count;
    lastStep[i] = std::max(count - 1, 0);
    steps = std::max(steps, count);
    capacity[i] = count > 0 ? static_cast<std::size_t>(w.Ray.capacity) : 0;
    const std::size_t from = count > 0 ? static_cast<std::size_t>(w.From()) * capacity[i] : 0;
    for (int s = 0; s < frames; ++s)
    {
      first[s][i] = w.Ray.codes + from + w.Ray.order[s];
      table[s][i] = w.Tables[s];
    }
  }
  __m256d T = _mm256_loadu_pd(t);
  __m256d R = _mm256_loadu_pd(c[0]);
  __m256d G = _mm256_loadu_pd(c[1]);
  __m256d B = _mm256_loadu_pd(c[2]);
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d limit = _mm256_set1_pd(termination);
  const __m256d rowsV = _mm256_loadu_pd(rows);
  __m256d jV = _mm256_setzero_pd();
  // Lanes still compositing: all bits set.
  __m256d active = _mm256_castsi256_pd(_mm256_set_epi64x(walks[3]->Done ? 0 : -1,
    walks[2]->Done ? 0 : -1, walks[1]->Done ? 0 : -1, walks[0]->Done ? 0 : -1));
  for (int j = 0; j < steps; ++j)
  {
    // Lanes past their last row rest.
    active = _mm256_and_pd(active, _mm256_cmp_pd(jV, rowsV, _CMP_LT_OQ));
    if (_mm256_movemask_pd(active) == 0)
    {
      break;
    }
    jV = _mm256_add_pd(jV, one);
    const std::size_t row[4] = { std::min(j, lastStep[0]) * capacity[0],
      std::min(j, lastStep[1]) * capacity[1], std::min(j, lastStep[2]) * capacity[2],
      std::min(j, lastStep[3]) * capacity[3] };
    for (int s = 0; s < frames; ++s)
    {
      // Each lane's entry (opacity, then colour times it), transposed into four vectors.
      const __m256d e0 =
        _mm256_loadu_pd(table[s][0] + 4 * static_cast<std::size_t>(first[s][0][row[0]]));
      const __m256d e1 =
        _mm256_loadu_pd(table[s][1] + 4 * static_cast<std::size_t>(first[s][1][row[1]]));
      const __m256d e2 =
        _mm256_loadu_pd(table[s][2] + 4 * static_cast<std::size_t>(first[s][2][row[2]]));
      const __m256d e3 =
        _mm256_loadu_pd(table[s][3] + 4 * static_cast<std::size_t>(first[s][3][row[3]]));
      const __m256d lo01 = _mm256_unpacklo_pd(e0, e1); // a0 a1 g0 g1
      const __m256d hi01 = _mm256_unpackhi_pd(e0, e1); // r0 r1 b0 b1
      const __m256d lo23 = _mm256_unpacklo_pd(e2, e3);
      const __m256d hi23 = _mm256_unpackhi_pd(e2, e3);
      const __m256d alpha = _mm256_permute2f128_pd(lo01, lo23, 0x20);
      const __m256d red = _mm256_permute2f128_pd(hi01, hi23, 0x20);
      const __m256d green = _mm256_permute2f128_pd(lo01, lo23, 0x31);
      const __m256d blue = _mm256_permute2f128_pd(hi01, hi23, 0x31);
      // As CompositeEntry: C += T * colour; T *= 1 - alpha; in active lanes only (the others
      // add T = 0 times their colour and multiply by 1, which changes no bit).
      const __m256d weight = _mm256_and_pd(T, active);
      R = _mm256_add_pd(R, _mm256_mul_pd(weight, red));
      G = _mm256_add_pd(G, _mm256_mul_pd(weight, green));
      B = _mm256_add_pd(B, _mm256_mul_pd(weight, blue));
      T = _mm256_mul_pd(T, _mm256_blendv_pd(one, _mm256_sub_pd(one, alpha), active));
      active = _mm256_andnot_pd(_mm256_cmp_pd(T, limit, _CMP_LT_OQ), active);
    }
  }
  // Lanes that reached the termination transmittance stopped where CompositeRows would have:
  // done. Others have walked all their rows between the first and the last.
  _mm256_storeu_pd(t, T);
  _mm256_storeu_pd(c[0], R);
  _mm256_storeu_pd(c[1], G);
  _mm256_storeu_pd(c[2], B);
  for (int i = 0; i < 4; ++i)
  {
    walks[i]->T = t[i];
    walks[i]->C = Eigen::Array3d(c[0][i], c[1][i], c[2][i]);
    walks[i]->Done = walks[i]->Done || t[i] < termination;
  }
}
#endif

// Byte codes (`codes`, below 256) into slot `slot` of rows of four bytes each, eight rows at a
// time: each row's word keeps its other bytes and takes the code in its slot's. Slot 0 holds
// the first frame, written when the rows hold nothing else: its words are written whole
// (zeros in the other slots) without being read first. (A fresh page that is read first maps
// the shared zero page, and the write after it then costs a copy-on-write fault and a TLB
// flush on every core.)
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
__attribute__((target("avx2"))) void FileInSlotOfFour(
  std::uint8_t* rows, int slot, const std::uint32_t* codes, int count)
{
  const __m128i shift = _mm_cvtsi32_si128(8 * slot);
  const __m256i mask = _mm256_sll_epi32(_mm256_set1_epi32(0xFF), shift);
  int j = 0;
  for (; j + 8 <= count; j += 8)
  {
    const __m256i code = _mm256_sll_epi32(
      _mm256_and_si256(
        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(codes + j)), _mm256_set1_epi32(0xFF)),
      shift);
    __m256i* words = reinterpret_cast<__m256i*>(rows + 4 * static_cast<std::size_t>(j));
    _mm256_storeu_si256(words,
      slot == 0 ? code
                : _mm256_or_si256(_mm256_andnot_si256(mask, _mm256_loadu_si256(words)), code));
  }
  for (; j < count; ++j)
  {
    if (slot == 0)
    {
      std::memset(rows + 4 * static_cast<std::size_t>(j), 0, 4);
    }
    rows[4 * static_cast<std::size_t>(j) + slot] = static_cast<std::uint8_t>(codes[j]);
  }
}
#else
void FileInSlotOfFour(std::uint8_t* rows, int slot, const std::uint32_t* codes, int count)
{
  for (int j = 0; j < count; ++j)
  {
    if (slot == 0)
    {
      std::memset(rows + 4 * static_cast<std::size_t>(j), 0, 4);
    }
    rows[4 * static_cast<std::size_t>(j) + slot] = static_cast<std::uint8_t>(codes[j]);
  }
}
#endif

// Four plain stored rays (`layouts`, each rank's table from `tablesOf(g)`), walked with their
// rows between the first and the last composited together where the CPU can, into `pixels`.
// The same pixels as walking each alone.
template <typename Code, typename TablesOf>
void WalkFour(const RayLayout<Code> layouts[4], const TablesOf& tablesOf, const RowScan<Code>* scan,
  const TransferFunctionTable& tf, const AlphaCache& alphas, float* pixels, const int pixelOf[4])
{
  PlainWalk<Code> w0(layouts[0], tf, alphas, tablesOf(0), scan, kNegligibleTransmittance);
  PlainWalk<Code> w1(layouts[1], tf, alphas, tablesOf(1), scan, kNegligibleTransmittance);
  PlainWalk<Code> w2(layouts[2], tf, alphas, tablesOf(2), scan, kNegligibleTransmittance);
  PlainWalk<Code> w3(layouts[3], tf, alphas, tablesOf(3), scan, kNegligibleTransmittance);
  PlainWalk<Code>* const walks[4] = { &w0, &w1, &w2, &w3 };
  // The rows between each ray's first and last together, where the CPU can.
  bool going = false;
  for (PlainWalk<Code>* w : walks)
  {
    going = w->Begin() || going;
  }
  bool together = false;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  const int frames = layouts[0].frames;
  if (going && frames <= 4)
  {
    switch (frames)
    {
      case 1:
        CompositeRowsFour<1>(walks);
        break;
      case 2:
        CompositeRowsFour<2>(walks);
        break;
      case 3:
        CompositeRowsFour<3>(walks);
        break;
      default:
        CompositeRowsFour<4>(walks);
        break;
    }
    together = true;
  }
#endif
  for (int i = 0; i < 4; ++i)
  {
    if (!together)
    {
      walks[i]->Rows();
    }
    const Pixel p = walks[i]->End();
    std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(pixelOf[i]));
  }
}

struct Buffers
{
  std::vector<float> Values;
  std::vector<float> Gradients;
  std::vector<std::uint16_t> Seconds;
  std::vector<double> U;
  std::vector<int> Order;
  std::vector<const double*> Tables;
  std::vector<std::uint32_t> Codes;
};
} // namespace

struct FrameLoop::Scratch
{
  tbb::enumerable_thread_specific<Buffers> Local;
};

struct FrameLoop::Tile
{
  // What a ray keeps between frames; its direction and rotation are recomputed from the pixel
  // (cheaply, and identically) so that large images do not pay for them in memory.
  struct RayInfo
  {
    int Pixel;
    int SamplesPerFrame;
    double TEnter;
    double Length;
    std::size_t FirstRow;
  };
  int X0 = 0, Y0 = 0, X1 = 0, Y1 = 0;
  std::vector<RayInfo> Rays;
  SampleStore Store;
  SampleStore Normals;    // used only when shading
  SampleStore Magnitudes; // used only with gradient opacity
  SampleStore Seconds;    // used only when the sampler has second codes
};

FrameLoop::FrameLoop()
  : ThreadScratch(new Scratch)
{
}

FrameLoop::~FrameLoop() = default;

template <typename Work>
void FrameLoop::InArena(Work&& work)
{
  if (this->Settings.Threads > 0)
  {
    tbb::task_arena arena(this->Settings.Threads);
    arena.execute(work);
  }
  else
  {
    work();
  }
}

template <typename Body>
void FrameLoop::ForEachTile(Body&& body)
{
  this->InArena(
    [&]()
    {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, this->Tiles.size(), 1),
        [&](const tbb::blocked_range<std::size_t>& range)
        {
          Buffers& buffers = this->ThreadScratch->Local.local();
          for (std::size_t t = range.begin(); t != range.end(); ++t)
          {
            body(this->Tiles[t], buffers);
          }
        });
    });
}

namespace
{
// Narrows the pixels [x0, y0] to [x1, y1) (`pixels`) to those whose rays can meet the data:
// around the image of the sampler's hull, when all of it lies in front of the eye (the image of
// a convex set then holds every point of it, and each of its points lies on the ray of the
// pixel centre it projects to). One pixel more on every side covers round-off.
void HullPixels(const View& view, const Sampler& source, int pixels[4])
{
  std::array<Eigen::Vector3d, 8> corners;
  if (!source.HullCorners(corners))
  {
    return;
  }
  const Eigen::Matrix4d toNDC = view.NDCToWorld.inverse();
  if (!toNDC.allFinite())
  {
    return;
  }
  double lo[2] = { std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  double hi[2] = { -lo[0], -lo[1] };
  for (const Eigen::Vector3d& c : corners)
  {
    const Eigen::Vector4d p = toNDC * Eigen::Vector4d(c[0], c[1], c[2], 1.0);
    if (!(p[3] > 0.0) || !p.allFinite())
    {
      return; // a corner behind the eye: any pixel may see the data
    }
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::min(lo[a], p[a] / p[3]);
      hi[a] = std::max(hi[a], p[a] / p[3]);
    }
  }
  // Pixel centre x + 0.5 is at NDC 2 (x + 0.5) / width - 1.
  const int size[2] = { view.Width, view.Height };
  for (int a = 0; a < 2; ++a)
  {
    const double first = std::floor(0.5 * (lo[a] + 1.0) * size[a] - 0.5) - 1.0;
    const double last = std::ceil(0.5 * (hi[a] + 1.0) * size[a] - 0.5) + 1.0;
    pixels[a] = static_cast<int>(std::min(std::max(first, 0.0), static_cast<double>(size[a])));
    pixels[2 + a] =
      static_cast<int>(std::min(std::max(last + 1.0, 0.0), static_cast<double>(size[a])));
  }
}
} // namespace

void FrameLoop::Reset(
  const View& view, std::shared_ptr<const Sampler> sampler, const FrameSettings& settings)
{
  this->CurrentViewData = view;
  this->CurrentViewData.Prepare();
  this->Source = std::move(sampler);
  this->Settings = settings;
  this->Settings.TileSize = std::max(1, settings.TileSize);
  // Second codes take the attributes' upper half, where magnitudes would go.
  const bool seconds = this->Source && this->Source->HasSecondCode();
  if (seconds)
  {
    this->Settings.GradientMagnitudes = false;
  }
  this->FrameCount = 0;
  this->Capacity = 0;
  this->ShowingSinglePass = false;
  this->Snapshot.clear();
  this->SnapshotFrames = 0;
  this->SnapshotGeneration = 0;
  this->Estimate = -1.0;
  this->Pixels.assign(
    static_cast<std::size_t>(std::max(view.Width, 0)) * std::max(view.Height, 0) * 4, 0.0f);
  this->TotalSamplesPerFrame = 0;
  this->Limit = 0;
  std::fill(this->Rectangle, this->Rectangle + 4, 0);
  if (!this->Source || view.Width <= 0 || view.Height <= 0 || !(settings.SampleDistance > 0.0))
  {
    this->Tiles.clear();
    return;
  }
  this->Code = SampleEncoding::ForSampler(*this->Source);

  // Tiles keep their ray tables' memory across resets of the same image size: while the camera
  // moves, every frame is a reset.
  const int ts = this->Settings.TileSize;
  const std::size_t tilesX = (view.Width + ts - 1) / ts;
  const std::size_t tilesY = (view.Height + ts - 1) / ts;
  this->Tiles.resize(tilesX * tilesY);
  for (std::size_t t = 0; t < this->Tiles.size(); ++t)
  {
    Tile& tile = this->Tiles[t];
    tile.X0 = static_cast<int>(t % tilesX) * ts;
    tile.Y0 = static_cast<int>(t / tilesX) * ts;
    tile.X1 = std::min(tile.X0 + ts, view.Width);
    tile.Y1 = std::min(tile.Y0 + ts, view.Height);
    tile.Rays.clear();
  }

  const double dt = this->Settings.SampleDistance;
  const Sampler& source = *this->Source;
  const View& prepared = this->CurrentViewData;
  int pixels[4] = { 0, 0, view.Width, view.Height };
  HullPixels(prepared, source, pixels);
  std::copy(pixels, pixels + 4, this->Rectangle);
  this->ForEachTile(
    [&](Tile& tile, Buffers&)
    {
      std::size_t rows = 0;
      for (int y = std::max(tile.Y0, pixels[1]); y < std::min(tile.Y1, pixels[3]); ++y)
      {
        for (int x = std::max(tile.X0, pixels[0]); x < std::min(tile.X1, pixels[2]); ++x)
        {
          Ray ray;
          double tEnter = 0.0;
          double tExit = 0.0;
          if (!prepared.Segment(source, x, y, ray, tEnter, tExit))
          {
            continue;
          }
          const double length = std::min(tExit - tEnter, kMaxSamplesPerRay * dt);
          const int n = static_cast<int>(std::ceil(length / dt));
          tile.Rays.push_back({ y * view.Width + x, n, tEnter, length, rows });
          rows += n;
        }
      }
      tile.Store.Reset(rows, this->Code.Bytes);
      tile.Normals.Reset(this->Settings.Shade ? rows : 0, 2);
      tile.Magnitudes.Reset(this->Settings.GradientMagnitudes ? rows : 0, 1);
      tile.Seconds.Reset(seconds ? rows : 0, 2);
    });

  for (const Tile& tile : this->Tiles)
  {
    for (const Tile::RayInfo& ray : tile.Rays)
    {
      this->TotalSamplesPerFrame += ray.SamplesPerFrame;
    }
  }
  const std::size_t bytesPerFrame =
    this->TotalSamplesPerFrame * (this->Code.Bytes + (this->Settings.Shade ? 2 : 0) +
                                   (this->Settings.GradientMagnitudes ? 1 : 0) + (seconds ? 2 : 0));
  std::size_t fit = bytesPerFrame > 0 ? this->Settings.MemoryBudget / bytesPerFrame
                                      : static_cast<std::size_t>(this->Settings.MaximumFrames);
  this->Limit =
    static_cast<int>(std::min<std::size_t>(fit, std::max(this->Settings.MaximumFrames, 1)));
}

void FrameLoop::ImageBytes(std::vector<std::uint8_t>& bytes)
{
  bytes.resize(this->Pixels.size());
  const std::size_t rowFloats = static_cast<std::size_t>(this->CurrentViewData.Width) * 4;
  const std::size_t rows = rowFloats > 0 ? this->Pixels.size() / rowFloats : 0;
  // Plain pointers: through the vectors, each byte stored (which may alias anything) would
  // make the compiler read their data pointers again.
  const float* in = this->Pixels.data();
  std::uint8_t* out = bytes.data();
  // Only the rectangle can hold pixels that are not zero.
  const std::size_t x0 = 4 * static_cast<std::size_t>(this->Rectangle[0]);
  const std::size_t x1 = 4 * static_cast<std::size_t>(this->Rectangle[2]);
  const std::size_t y0 = static_cast<std::size_t>(this->Rectangle[1]);
  const std::size_t y1 = static_cast<std::size_t>(this->Rectangle[3]);
  this->InArena(
    [&]()
    {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 16),
        [=](const tbb::blocked_range<std::size_t>& range)
        {
          for (std::size_t y = range.begin(); y < range.end(); ++y)
          {
            std::uint8_t* row = out + y * rowFloats;
            if (y < y0 || y >= y1 || x1 <= x0)
            {
              std::fill(row, row + rowFloats, std::uint8_t(0));
              continue;
            }
            std::fill(row, row + x0, std::uint8_t(0));
            std::fill(row + x1, row + rowFloats, std::uint8_t(0));
            const float* source = in + y * rowFloats;
            for (std::size_t i = x0; i < x1; ++i)
            {
              const float v = std::min(std::max(source[i], 0.0f), 1.0f);
              row[i] = static_cast<std::uint8_t>(v * 255.0f + 0.5f);
            }
          }
        });
    });
}

FrameLoop::Attributes FrameLoop::CurrentAttributes() const
{
  Attributes a;
  a.Normals = this->Settings.Shade;
  a.Magnitudes = this->Settings.GradientMagnitudes;
  a.MagnitudeScale = this->Settings.MagnitudeScale;
  a.Shading = a.Normals ? this->Shading : nullptr;
  a.GradientOpacity = a.Magnitudes ? this->GradientOpacity : nullptr;
  a.Isos = this->Isos;
  return a;
}

double FrameLoop::RotationOf(int pixel) const
{
  const int width = this->CurrentViewData.Width;
  return this->RotationOf(pixel % width, pixel / width);
}

double FrameLoop::RotationOf(int x, int y) const
{
  return this->Settings.RotateOffsets ? PixelRotation(x, y) : 0.0;
}

std::size_t FrameLoop::MemoryInUse() const
{
  std::size_t bytes = 0;
  for (const Tile& tile : this->Tiles)
  {
    bytes += tile.Store.MemoryInUse() + tile.Normals.MemoryInUse() + tile.Magnitudes.MemoryInUse() +
             tile.Seconds.MemoryInUse();
  }
  return bytes;
}

void FrameLoop::Grow(int capacity)
{
  const int frames = this->FrameCount;
  this->ForEachTile(
    [&](Tile& tile, Buffers&)
    {
      tile.Store.Grow(capacity, frames);
      tile.Normals.Grow(capacity, frames);
      tile.Magnitudes.Grow(capacity, frames);
      tile.Seconds.Grow(capacity, frames);
    });
  this->Capacity = capacity;
}

void FrameLoop::AccumulateFrame(const TransferFunctionTable& tf, BlendMode mode)
{
  if (this->Filled() || this->Tiles.empty())
  {
    return;
  }
  if (this->Limit == 0)
  {
    // Not even one frame fits the budget: draw plain ray casting and call it final.
    this->RenderSinglePass(tf, mode, this->Settings.SampleDistance, 0.0);
    this->FrameCount = 1;
    this->ShowingSinglePass = false;
    return;
  }
  if (this->FrameCount + 1 > this->Capacity)
  {
    // Room for four times the frames (never past the limit), the first time for four: growing
    // copies every sample kept, so it should happen seldom.
    this->Grow(std::min(std::max(4, 4 * this->Capacity), this->Limit));
  }
  this->Blend(tf, mode, true, this->FrameCount + 1, this->Pixels.data());
  ++this->FrameCount;
  this->ShowingSinglePass = false;
  this->UpdateErrorEstimate(tf, mode, false);
}

void FrameLoop::Blend(
  const TransferFunctionTable& tf, BlendMode mode, bool sample, int frames, float* target)
{
  if (this->Code.Bytes == 1)
  {
    this->Accumulate<std::uint8_t>(tf, mode, sample, frames, target);
  }
  else
  {
    this->Accumulate<std::uint16_t>(tf, mode, sample, frames, target);
  }
}

void FrameLoop::UpdateErrorEstimate(const TransferFunctionTable& tf, BlendMode mode, bool reblended)
{
  const int frames = this->FrameCount;
  if (frames >= 2)
  {
    // Compare with the largest power of two of frames below the count, blended the same way:
    // the stored samples hold every prefix of the frames, so it can be blended again when the
    // one at hand is not that image.
    int earlier = 1;
    while (2 * earlier < frames)
    {
      earlier *= 2;
    }
    const std::uint64_t shading = this->AttributeGeneration();
    if (this->SnapshotFrames != earlier || this->SnapshotGeneration != tf.Generation() ||
        this->SnapshotMode != mode || this->SnapshotShading != shading)
    {
      this->Snapshot.assign(this->Pixels.size(), 0.0f);
      this->Blend(tf, mode, false, earlier, this->Snapshot.data());
      this->SnapshotFrames = earlier;
      this->SnapshotGeneration = tf.Generation();
      this->SnapshotMode = mode;
      this->SnapshotShading = shading;
    }
    // Row by row in parallel over the rectangle (both images are zero outside it), the rows'
    // sums then added in order: the same bits whatever the thread count.
    const std::size_t width = static_cast<std::size_t>(this->CurrentViewData.Width);
    const std::size_t x0 = 4 * static_cast<std::size_t>(this->Rectangle[0]);
    const std::size_t x1 = 4 * static_cast<std::size_t>(this->Rectangle[2]);
    const int y0 = this->Rectangle[1];
    const int y1 = std::max(this->Rectangle[3], y0);
    std::vector<double> rowSums(static_cast<std::size_t>(y1 - y0), 0.0);
    const float* now = this->Pixels.data();
    const float* then = this->Snapshot.data();
    this->InArena(
      [&]()
      {
        tbb::parallel_for(tbb::blocked_range<int>(y0, y1, 8),
          [&](const tbb::blocked_range<int>& range)
          {
            for (int y = range.begin(); y < range.end(); ++y)
            {
              const std::size_t row = static_cast<std::size_t>(y) * 4 * width;
              double sum = 0.0;
              for (std::size_t i = row + x0; i < row + x1; ++i)
              {
                const double d = static_cast<double>(now[i]) - then[i];
                sum += d * d;
              }
              rowSums[static_cast<std::size_t>(y - y0)] = sum;
            }
          });
      });
    double sum = 0.0;
    for (const double s : rowSums)
    {
      sum += s;
    }
    this->Estimate = std::sqrt(sum / std::max<std::size_t>(this->Pixels.size(), 1));
  }
  if (!reblended && (frames & (frames - 1)) == 0)
  {
    // The next frames compare with this one.
    this->Snapshot = this->Pixels;
    this->SnapshotFrames = frames;
    this->SnapshotGeneration = tf.Generation();
    this->SnapshotMode = mode;
    this->SnapshotShading = this->AttributeGeneration();
  }
}

void FrameLoop::Reblend(const TransferFunctionTable& tf, BlendMode mode)
{
  if (this->FrameCount == 0 || this->Tiles.empty())
  {
    return;
  }
  if (this->Limit == 0)
  {
    // Nothing is stored: the plain pass is the image.
    this->RenderSinglePass(tf, mode, this->Settings.SampleDistance, 0.0);
    this->ShowingSinglePass = false;
    return;
  }
  this->Blend(tf, mode, false, this->FrameCount, this->Pixels.data());
  this->ShowingSinglePass = false;
  this->UpdateErrorEstimate(tf, mode, true);
}

template <typename Code>
void FrameLoop::Accumulate(
  const TransferFunctionTable& tf, BlendMode mode, bool sample, int frames, float* target)
{
  const int newSlot = this->FrameCount;
  if (this->Offsets.Frames() != frames)
  {
    this->Offsets.Resize(frames);
  }
  const double dt = this->Settings.SampleDistance;
  const double gap = OffsetSequence::SmallestGap(frames) * dt;
  this->Alphas.Prepare(tf, gap, 2.0 * gap);

  const Sampler& source = *this->Source;
  const SampleEncoding& encoding = this->Code;
  const OffsetSequence& offsets = this->Offsets;
  const AlphaCache& alphas = this->Alphas;
  const View& view = this->CurrentViewData;
  const Attributes attributes = this->CurrentAttributes();
  const bool hasSeconds = source.HasSecondCode();
  float* pixels = target;
  // Samples are encoded eight at a time where the CPU can (the same codes as Encode).
  const bool vectorEncode = this->Settings.Vectorize && detail::HaveAVX2();
  const std::uint32_t nonFinite = encoding.HasNaNCode ? encoding.NaNCode : 0u;
  // Composite without lighting, gradient opacity or second codes: interior intervals are one of
  // three lengths (the gaps between offsets take two), each with its table.
  const bool plain = mode == BlendMode::Composite && !attributes.Shading &&
                     !attributes.GradientOpacity && !hasSeconds && !tf.HasComponentTerms();
  if (plain)
  {
    const double lengths[3] = { gap, 1.5 * gap, 2.0 * gap };
    for (int k = 0; k < 3; ++k)
    {
      if (this->IntervalGeneration != tf.Generation() || this->IntervalLengths[k] != lengths[k])
      {
        PremultipliedTable(tf, lengths[k], this->IntervalTables[k]);
        this->IntervalLengths[k] = lengths[k];
      }
    }
    this->IntervalGeneration = tf.Generation();
  }
  // Codes below `transparent` are (codes past the table's are not looked at).
  std::uint32_t transparent = 0;
  while (plain && this->Settings.PassOverTransparentRows && transparent < tf.Size() &&
         tf.Extinction(transparent) == 0.0)
  {
    ++transparent;
  }
  const RowScan<Code> scan(
    transparent, this->Capacity, frames, this->Settings.Vectorize && detail::HaveAVX2());

  // Each offset's interval, halfway to the offsets either side (across rows at the ends), and
  // its table (null when none). A rotation shifts which rank an offset has, not the gaps.
  std::vector<const double*> sortedTables(frames, nullptr);
  bool allTabled = true;
  for (int p = 0; plain && p < frames; ++p)
  {
    const auto base = [&](int q) { return offsets.Offset(offsets.SortedFrame(q)); };
    const double before = p > 0 ? base(p - 1) : base(frames - 1) - 1.0;
    const double after = p + 1 < frames ? base(p + 1) : base(0) + 1.0;
    const double h = 0.5 * (after - before) * dt;
    for (int k = 0; k < 3; ++k)
    {
      if (std::abs(h - this->IntervalLengths[k]) <= 1e-9 * this->IntervalLengths[k])
      {
        sortedTables[p] = this->IntervalTables[k].data();
      }
    }
    allTabled = allTabled && sortedTables[p];
  }

  // Four plain rays at a time where the CPU has AVX2.
  const bool walkFour = plain && vectorEncode;
  this->ForEachTile(
    [&](Tile& tile, Buffers& buffers)
    {
      // Room for four rays' offsets and tables: plain rays are walked four at a time.
      buffers.U.resize(4 * static_cast<std::size_t>(frames));
      buffers.Order.resize(4 * static_cast<std::size_t>(frames));
      buffers.Tables.resize(4 * static_cast<std::size_t>(frames));
      RayLayout<Code> group[4];
      int groupPixels[4] = { 0, 0, 0, 0 };
      int pending = 0;
      const auto walkOne = [&](const RayLayout<Code>& layout, const double* const* tables) {
        return PlainWalk<Code>(layout, tf, alphas, tables, &scan, kNegligibleTransmittance).Walk();
      };
      const auto tablesOf = [&](int g) { return buffers.Tables.data() + g * frames; };
      for (const Tile::RayInfo& ray : tile.Rays)
      {
        const std::size_t g = static_cast<std::size_t>(pending) * frames;
        double* const u = buffers.U.data() + g;
        int* const order = buffers.Order.data() + g;
        const double** const tables = buffers.Tables.data() + g;
        // The pixel's column and row, once.
        const int px = ray.Pixel % view.Width;
        const int py = ray.Pixel / view.Width;
        const int shift = offsets.Rotate(this->RotationOf(px, py), u, order);
        Code* codes = tile.Store.template Row<Code>(ray.FirstRow);
        const int capacity = tile.Store.SlotCapacity();
        std::uint16_t* normals =
          attributes.Normals ? tile.Normals.template Row<std::uint16_t>(ray.FirstRow) : nullptr;
        std::uint8_t* magnitudes = attributes.Magnitudes
                                     ? tile.Magnitudes.template Row<std::uint8_t>(ray.FirstRow)
                                     : nullptr;
        std::uint16_t* seconds =
          hasSeconds ? tile.Seconds.template Row<std::uint16_t>(ray.FirstRow) : nullptr;
        if (sample)
        {
#if defined(__GNUC__)
          // The ray's stored rows are about to be written, one byte of each line at a time:
          // ask for them now, so that fetching them overlaps the sampling.
          const char* rows = reinterpret_cast<const char*>(codes);
          const std::size_t rowBytes =
            static_cast<std::size_t>(ray.SamplesPerFrame) * capacity * sizeof(Code);
          for (std::size_t b = 0; b < rowBytes; b += 64)
          {
            __builtin_prefetch(rows + b, 1, 3);
          }
#endif
          const Ray r = view.PixelRay(px, py);
          const double start = ray.TEnter + u[newSlot] * dt;
          // Room for whole groups of four: values are encoded four at a time, and the codes of
          // the values past the ray's (whatever they hold) are not used.
          const std::size_t padded =
            (static_cast<std::size_t>(ray.SamplesPerFrame) + 3) & ~std::size_t(3);
          buffers.Values.resize(padded);
          if (attributes.Any())
          {
            buffers.Gradients.resize(3 * static_cast<std::size_t>(ray.SamplesPerFrame));
            source.SampleRayGradients(
              r, start, dt, ray.SamplesPerFrame, buffers.Values.data(), buffers.Gradients.data());
            for (int j = 0; j < ray.SamplesPerFrame; ++j)
            {
              const std::uint32_t a =
                attributes.Encode(&buffers.Gradients[3 * static_cast<std::size_t>(j)]);
              const std::size_t k = static_cast<std::size_t>(j) * capacity + newSlot;
              if (normals)
              {
                normals[k] = NormalOf(a);
              }
              if (magnitudes)
              {
                magnitudes[k] = static_cast<std::uint8_t>(MagnitudeOf(a));
              }
            }
          }
          else
          {
            source.SampleRay(r, start, dt, ray.SamplesPerFrame, buffers.Values.data());
          }
          if (seconds)
          {
            buffers.Seconds.resize(ray.SamplesPerFrame);
            source.SampleRaySecond(r, start, dt, ray.SamplesPerFrame, buffers.Seconds.data());
            for (int j = 0; j < ray.SamplesPerFrame; ++j)
            {
              const std::uint16_t second = buffers.Seconds[j];
              seconds[static_cast<std::size_t>(j) * capacity + newSlot] = second;
              if (second == kNoSecondCode)
              {
                buffers.Values[j] = std::numeric_limits<float>::quiet_NaN();
              }
            }
          }
          // Into the new slot of every row. (Locals, so that the byte stores, which may alias
          // anything, do not make the compiler read these again each time.)
          const int count = ray.SamplesPerFrame;
          const std::size_t stride = static_cast<std::size_t>(capacity);
          Code* slot = codes + newSlot;
          if (vectorEncode)
          {
            buffers.Codes.resize(padded);
            const std::uint32_t* encoded = buffers.Codes.data();
            detail::EncodeAVX2(encoding.Offset, encoding.Scale, encoding.Levels, nonFinite,
              nonFinite, buffers.Values.data(), static_cast<int>(padded), buffers.Codes.data());
            if (sizeof(Code) == 1 && capacity == 4)
            {
              FileInSlotOfFour(reinterpret_cast<std::uint8_t*>(codes), newSlot, encoded, count);
            }
            else if (capacity == 1)
            {
              // One slot per row: the rows are the codes, narrowed (a loop the compiler
              // vectorizes).
              for (int j = 0; j < count; ++j)
              {
                codes[j] = static_cast<Code>(encoded[j]);
              }
            }
            else
            {
              for (int j = 0; j < count; ++j)
              {
                slot[j * stride] = static_cast<Code>(encoded[j]);
              }
            }
          }
          else
          {
            const float* values = buffers.Values.data();
            for (int j = 0; j < count; ++j)
            {
              slot[j * stride] = static_cast<Code>(encoding.Encode(values[j]));
            }
          }
        }
        RayLayout<Code> layout;
        layout.codes = codes;
        layout.normals = normals;
        layout.magnitudes = magnitudes;
        layout.seconds = seconds;
        layout.samplesPerFrame = ray.SamplesPerFrame;
        layout.capacity = capacity;
        layout.frames = frames;
        layout.u = u;
        layout.order = order;
        layout.dt = dt;
        layout.length = ray.Length;
        Pixel p;
        if (plain)
        {
          // Rank s is the offset sortedTables[s + shift] stands for, rotated.
          for (int s = 0; s < frames; ++s)
          {
            tables[s] = sortedTables[s + shift < frames ? s + shift : s + shift - frames];
          }
          if (allTabled && walkFour)
          {
            group[pending] = layout;
            groupPixels[pending] = ray.Pixel;
            if (++pending == 4)
            {
              WalkFour(group, tablesOf, &scan, tf, alphas, pixels, groupPixels);
              pending = 0;
            }
            continue;
          }
          p = walkOne(layout, tables);
        }
        else
        {
          p = BlendRay(layout, tf, alphas, mode, kNegligibleTransmittance, attributes.Shading,
            attributes.GradientOpacity, attributes.Isos);
        }
        std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(ray.Pixel));
      }
      for (int g = 0; g < pending; ++g)
      {
        const Pixel p = walkOne(group[g], tablesOf(g));
        std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(groupPixels[g]));
      }
    });
  if (sample)
  {
    this->Taken += this->TotalSamplesPerFrame;
  }
}

bool FrameLoop::TransparentBlocks(
  const TransferFunctionTable& tf, std::vector<std::uint8_t>& skip, std::uint32_t& nanCode) const
{
  const std::vector<float>& ranges = this->Source->BlockRanges();
  const std::uint32_t levels = this->Code.Levels;
  // nextVisible[c]: the first code at or after c that is not transparent.
  std::vector<std::uint32_t> nextVisible(levels + 1, levels);
  for (std::uint32_t c = levels; c-- > 0;)
  {
    nextVisible[c] = tf.Extinction(c) > 0.0 ? c : nextVisible[c + 1];
  }
  std::uint32_t transparent = 0;
  while (transparent < levels && tf.Extinction(transparent) > 0.0)
  {
    ++transparent;
  }
  if (ranges.empty() || transparent == levels)
  {
    return false; // no blocks, or nothing is transparent
  }
  if (!this->Code.HasNaNCode)
  {
    nanCode = transparent; // skipped samples need a transparent code of their own
  }
  const std::size_t blocks = ranges.size() / 2;
  skip.assign(blocks, 0);
  for (std::size_t b = 0; b < blocks; ++b)
  {
    const float lo = ranges[2 * b];
    const float hi = ranges[2 * b + 1];
    skip[b] = !(lo <= hi) || nextVisible[this->Code.Encode(lo)] > this->Code.Encode(hi);
  }
  this->Source->SkipDistances(skip);
  return true;
}

void FrameLoop::RenderSinglePass(const TransferFunctionTable& tf, BlendMode mode, double step,
  double offset, const PassOptions& options)
{
  if (this->Tiles.empty() || !(step > 0.0))
  {
    return;
  }
  // Blocks the transfer function makes transparent read as NaN, which blends as transparent.
  std::vector<std::uint8_t> skip;
  std::uint32_t nanCode = this->Code.HasNaNCode ? this->Code.NaNCode : 0u;
  const bool skipping = options.SkipTransparent &&
                        (mode == BlendMode::Composite || mode == BlendMode::Additive) &&
                        this->TransparentBlocks(tf, skip, nanCode);
  this->ShowingSinglePass = true;
  SkipMask mask;
  mask.Skip = &skip;
  const SkipMask* skipMask = skipping ? &mask : nullptr;
  this->Alphas.Prepare(tf, step, 2.0 * step);
  // A pixel's rotation is measured in base steps, so a pass at dt / K sees the same rotated
  // lattice as K accumulated frames.
  const double stepsPerBase = this->Settings.SampleDistance / step;
  const Sampler& source = *this->Source;
  const SampleEncoding& encoding = this->Code;
  const AlphaCache& alphas = this->Alphas;
  const View& view = this->CurrentViewData;
  const Attributes attributes = this->CurrentAttributes();
  const bool hasSeconds = source.HasSecondCode();
  float* pixels = this->Pixels.data();
  std::atomic<std::uint64_t> taken{ 0 };
  // Composite without lighting, gradient opacity or second codes: the lean loop.
  const bool plain = mode == BlendMode::Composite && !attributes.Shading &&
                     !attributes.GradientOpacity && !hasSeconds && !tf.HasComponentTerms();
  // Its table: per code, the opacity of one step and the colour times it.
  const double* premultiplied = nullptr;
  if (plain)
  {
    if (this->PremultipliedGeneration != tf.Generation() || this->PremultipliedStep != step)
    {
      PremultipliedTable(tf, step, this->Premultiplied);
      this->PremultipliedGeneration = tf.Generation();
      this->PremultipliedStep = step;
    }
    premultiplied = this->Premultiplied.data();
  }

  this->ForEachTile(
    [&](Tile& tile, Buffers& buffers)
    {
      std::uint64_t tileTaken = 0;
      buffers.Values.resize(kChunk);
      buffers.Seconds.resize(kChunk);
      buffers.Codes.resize(kChunk);
      for (const Tile::RayInfo& ray : tile.Rays)
      {
        const double rotation = this->RotationOf(ray.Pixel) * stepsPerBase;
        const Ray r = view.PixelRay(ray.Pixel % view.Width, ray.Pixel / view.Width);
        double u = offset + (rotation - std::floor(rotation));
        u -= std::floor(u);
        const int n = static_cast<int>(std::min(std::ceil(ray.Length / step), kMaxSamplesPerRay));
        if (plain)
        {
          const Pixel p = PlainComposite(source, encoding, tf, alphas, r, ray.TEnter, ray.Length,
            step, u, n, options.Termination, skipMask, nanCode, premultiplied, buffers.Values,
            buffers.Codes, tileTaken);
          std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(ray.Pixel));
          continue;
        }
        // Sampled a chunk at a time so that a ray the blend has given up on stops sampling.
        auto feed = [&](auto& stream)
        {
          for (int j0 = 0; j0 < n; j0 += kChunk)
          {
            const int count = std::min(kChunk, n - j0);
            tileTaken += count;
            source.SampleRay(
              r, ray.TEnter + (j0 + u) * step, step, count, buffers.Values.data(), skipMask);
            if (hasSeconds)
            {
              source.SampleRaySecond(
                r, ray.TEnter + (j0 + u) * step, step, count, buffers.Seconds.data());
            }
            for (int i = 0; i < count; ++i)
            {
              const double pos = (j0 + i + u) * step;
              if (pos >= ray.Length)
              {
                stream.Finish(ray.Length);
                return;
              }
              const float v = buffers.Values[i];
              const std::uint32_t second = hasSeconds ? buffers.Seconds[i] : 0u;
              const std::uint32_t code =
                v == v && second != kNoSecondCode ? encoding.Encode(v) : nanCode;
              // Gradients only where the sample is seen: nothing of this pass is kept.
              std::uint32_t a = kNoNormal;
              if (attributes.Any() &&
                  (mode == BlendMode::Isosurface || hasSeconds || tf.Extinction(code) > 0.0))
              {
                float g[3];
                source.GradientAt(r, ray.TEnter + pos, g);
                a = attributes.Encode(g);
              }
              a |= second << 16;
              if (!stream.Push(pos, code, a))
              {
                return;
              }
            }
          }
          stream.Finish(ray.Length);
        };
        const Pixel p = BlendSamples(feed, tf, alphas, mode, options.Termination,
          attributes.Shading, attributes.GradientOpacity, attributes.Isos);
        std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(ray.Pixel));
      }
      taken += tileTaken;
    });
  this->Taken += taken;
}

} // namespace savr

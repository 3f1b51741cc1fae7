#pragma once
// The AVX2 kernels of the stored blends, as GridArrays holds the grid sampler's: finding the
// rows of a stored ray that are not transparent, compositing four plain stored rays at once,
// and filing a frame's codes into their slots. Each computes exactly what its scalar path
// computes, so that images do not depend on which path ran.

#include "blend/Integrator.h"

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#include <immintrin.h>
#endif

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace savr
{
namespace detail
{

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

template <typename Code>
class PlainComposite;

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
// Rows [From(), To()) of four rays at once, every rank of each with a table, after their first
// rows: each lane computes exactly what CompositeRows computes for its ray (the same products
// and sums in the same order), and stops where that would or at its To().
template <int F, typename Code>
__attribute__((target("avx2"))) void CompositeRowsFour(PlainComposite<Code>* const composites[4])
{
  constexpr int frames = F;
  const double termination = composites[0]->Termination;
  double t[4];
  double c[3][4];
  double rows[4];  // rows each lane composites
  int lastStep[4]; // the last of them, counted from its first (0 for none)
  int steps = 0;
  // Per lane and rank: where its codes start (its From() row) and its table.
  const Code* first[frames][4];
  const double* table[frames][4];
  std::size_t capacity[4];
  for (int i = 0; i < 4; ++i)
  {
    const PlainComposite<Code>& w = *composites[i];
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
    capacity[i] = count > 0 ? static_cast<std::size_t>(w.Ray.Capacity) : 0;
    const std::size_t from = count > 0 ? static_cast<std::size_t>(w.From()) * capacity[i] : 0;
    for (int s = 0; s < frames; ++s)
    {
      first[s][i] = w.Ray.Codes + from + w.Ray.Order[s];
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
  __m256d active = _mm256_castsi256_pd(_mm256_set_epi64x(composites[3]->Done ? 0 : -1,
    composites[2]->Done ? 0 : -1, composites[1]->Done ? 0 : -1, composites[0]->Done ? 0 : -1));
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
    composites[i]->T = t[i];
    composites[i]->C = Eigen::Array3d(c[0][i], c[1][i], c[2][i]);
    composites[i]->Done = composites[i]->Done || t[i] < termination;
  }
}
#endif

// Byte codes (`codes`, below 256) into slot `slot` of rows of four bytes each, eight rows at a
// time: each row's word keeps its other bytes and takes the code in its slot's. Slot 0 holds
// the first frame, written when the rows hold nothing else: its words are written whole
// (zeros in the other slots) without being read first. (A fresh page that is read first maps
// the shared zero page, and the write after it then costs a copy-on-write fault and a TLB
// flush on every core.)
void FileInSlotOfFour(std::uint8_t* rows, int slot, const std::uint32_t* codes, int count);

} // namespace detail
} // namespace savr

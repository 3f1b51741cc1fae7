#include "image/GridAVX2.h"

#include "encoding/NormalCodesAVX2.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace savr
{
namespace detail
{

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))

namespace
{
// Values at element offsets `offsets` (8 lanes) as floats. Narrow types are read as the 4 bytes
// holding them, never past either end of the array: the read starts at most 4 bytes before
// the end, and the value is shifted out of wherever it lies in the word.
__attribute__((target("avx2"))) inline __m256 Load(
  const GridArrays& k, __m256i offsets, __m256i lastWord)
{
  const auto* base = static_cast<const int*>(k.Values);
  if (k.Type == GridValueType::Float32)
  {
    return _mm256_i32gather_ps(static_cast<const float*>(k.Values), offsets, 4);
  }
  const int size = k.Type == GridValueType::UInt8 ? 1 : 2;
  const __m256i bytes = size == 1 ? offsets : _mm256_add_epi32(offsets, offsets);
  const __m256i start = _mm256_min_epi32(bytes, lastWord);
  const __m256i words = _mm256_i32gather_epi32(base, start, 1);
  const __m256i shift = _mm256_slli_epi32(_mm256_sub_epi32(bytes, start), 3);
  const __m256i mask = _mm256_set1_epi32(size == 1 ? 0xFF : 0xFFFF);
  return _mm256_cvtepi32_ps(_mm256_and_si256(_mm256_srlv_epi32(words, shift), mask));
}

// Value-grid coordinate along one axis for four samples: clamped as ClampToValueGrid does.
__attribute__((target("avx2"))) inline __m256d Coordinate(
  double o, double d, double shift, double top, __m256d t)
{
  const __m256d c = _mm256_add_pd(_mm256_set1_pd(o), _mm256_mul_pd(t, _mm256_set1_pd(d)));
  const __m256d v = _mm256_sub_pd(c, _mm256_set1_pd(shift));
  // v < 0 ? 0 : (v > top ? top : v)
  const __m256d zero = _mm256_setzero_pd();
  const __m256d topV = _mm256_set1_pd(top);
  const __m256d upper = _mm256_blendv_pd(v, topV, _mm256_cmp_pd(v, topV, _CMP_GT_OQ));
  return _mm256_blendv_pd(upper, zero, _mm256_cmp_pd(v, zero, _CMP_LT_OQ));
}

// Lower corner and weight along one axis for eight samples (two halves of four), as
// LowerCorner computes them.
__attribute__((target("avx2"))) inline void Corner(
  __m256d lo, __m256d hi, int lastCell, __m256i& index, __m256& weight)
{
  const __m128i fLo = _mm_min_epi32(_mm256_cvttpd_epi32(lo), _mm_set1_epi32(lastCell));
  const __m128i fHi = _mm_min_epi32(_mm256_cvttpd_epi32(hi), _mm_set1_epi32(lastCell));
  const __m128 wLo = _mm256_cvtpd_ps(_mm256_sub_pd(lo, _mm256_cvtepi32_pd(fLo)));
  const __m128 wHi = _mm256_cvtpd_ps(_mm256_sub_pd(hi, _mm256_cvtepi32_pd(fHi)));
  index = _mm256_set_m128i(fHi, fLo);
  weight = _mm256_set_m128(wHi, wLo);
}

// `v` with its 16-bit lane J set to the two bytes at `at` (little-endian: the first low).
template <int J>
__attribute__((target("avx2"))) inline __m128i WithPair(__m128i v, const unsigned char* at)
{
  std::uint16_t two;
  std::memcpy(&two, at, sizeof(two));
  return _mm_insert_epi16(v, two, J);
}

// The 4-byte words at byte offsets `at` from `base` (8 lanes) and the words after them (inside
// the array), from one 8-byte read per lane: eight scalar reads cost less than two gathers on
// the CPUs measured.
__attribute__((target("avx2"))) inline void LoadWordPairs(
  const void* base, __m256i at, __m256i& first, __m256i& second)
{
  alignas(32) int lane[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lane), at);
  const auto* bytes = static_cast<const unsigned char*>(base);
  __m128i pairs[4];
  for (int h = 0; h < 4; ++h)
  {
    long long low, high;
    std::memcpy(&low, bytes + lane[2 * h], sizeof(low));
    std::memcpy(&high, bytes + lane[2 * h + 1], sizeof(high));
    pairs[h] = _mm_set_epi64x(high, low);
  }
  // Words (lane, x): (0,0) (0,1) (1,0) (1,1) | (2,0) (2,1) (3,0) (3,1), and lanes 4 to 7 alike.
  const __m256 a = _mm256_castsi256_ps(_mm256_set_m128i(pairs[1], pairs[0]));
  const __m256 b = _mm256_castsi256_ps(_mm256_set_m128i(pairs[3], pairs[2]));
  // Even words are the lanes' own, odd ones the next, in lane order 0 1 4 5 | 2 3 6 7.
  const __m256i even = _mm256_castps_si256(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0)));
  const __m256i odd = _mm256_castps_si256(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1)));
  first = _mm256_permute4x64_epi64(even, _MM_SHUFFLE(3, 1, 2, 0));
  second = _mm256_permute4x64_epi64(odd, _MM_SHUFFLE(3, 1, 2, 0));
}

// The values at element offsets `offsets` and one element further (the x neighbours of
// single-component data), never past the end (the neighbour is inside the array).
__attribute__((target("avx2"))) inline void LoadPair(
  const GridArrays& k, __m256i offsets, __m256& first, __m256& second)
{
  if (k.Type == GridValueType::Float32)
  {
    __m256i a, b;
    LoadWordPairs(k.Values, _mm256_slli_epi32(offsets, 2), a, b);
    first = _mm256_castsi256_ps(a);
    second = _mm256_castsi256_ps(b);
    return;
  }
  if (k.Type == GridValueType::UInt16)
  {
    // Both 16-bit values lie in the word at the first one: one 4-byte read per lane (as a
    // gather: eight scalar reads measured no faster here).
    const __m256i words = _mm256_i32gather_epi32(
      static_cast<const int*>(k.Values), _mm256_add_epi32(offsets, offsets), 1);
    const __m256i mask = _mm256_set1_epi32(0xFFFF);
    first = _mm256_cvtepi32_ps(_mm256_and_si256(words, mask));
    second = _mm256_cvtepi32_ps(_mm256_srli_epi32(words, 16));
    return;
  }
  // Bytes: the two of each lane from one scalar read (the neighbour is inside the array), put
  // together in a vector. Eight such reads cost less than a gather on the CPUs measured.
  alignas(32) int at[8];
  _mm256_store_si256(reinterpret_cast<__m256i*>(at), offsets);
  const auto* bytes = static_cast<const unsigned char*>(k.Values);
  __m128i both = _mm_setzero_si128();
  both = WithPair<0>(both, bytes + at[0]);
  both = WithPair<1>(both, bytes + at[1]);
  both = WithPair<2>(both, bytes + at[2]);
  both = WithPair<3>(both, bytes + at[3]);
  both = WithPair<4>(both, bytes + at[4]);
  both = WithPair<5>(both, bytes + at[5]);
  both = WithPair<6>(both, bytes + at[6]);
  both = WithPair<7>(both, bytes + at[7]);
  first = _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_and_si128(both, _mm_set1_epi16(0xFF))));
  second = _mm256_cvtepi32_ps(_mm256_cvtepu16_epi32(_mm_srli_epi16(both, 8)));
}

// The block every lane of a group lies in when its first and last lanes share one, else -1:
// each index coordinate is monotone along a group (the clamped positions included).
__attribute__((target("avx2"))) inline int SharedBlock(__m256i block)
{
  const int first = _mm256_extract_epi32(block, 0);
  return first == _mm256_extract_epi32(block, 7) ? first : -1;
}

__attribute__((target("avx2"))) inline __m256 Lerp(__m256 a, __m256 b, __m256 w)
{
  return _mm256_add_ps(a, _mm256_mul_ps(w, _mm256_sub_ps(b, a)));
}

// The group helpers below are inlined into each kernel's loop (always: called, a group's
// cells would pass through memory).
// What the kernels need of a group of eight samples at t0 + (i + lane) dt: each lane's cell
// (its lower corner and weights along each axis, as LowerCorner computes them), the block it
// lies in, and the block every lane lies in (SharedBlock) or -1.
struct Cells
{
  __m256i Index[3];
  __m256 W[3];
  __m256i Block;
  int Shared;
};

__attribute__((target("avx2"), always_inline)) inline Cells LocateGroup(
  const GridArrays& k, const double o[3], const double d[3], double t0, double dt, int i)
{
  const __m256d t0v = _mm256_set1_pd(t0);
  const __m256d dtv = _mm256_set1_pd(dt);
  // t = t0 + i dt for the eight samples, in two halves.
  const __m256d iLo = _mm256_set_pd(i + 3, i + 2, i + 1, i);
  const __m256d iHi = _mm256_set_pd(i + 7, i + 6, i + 5, i + 4);
  const __m256d tLo = _mm256_add_pd(t0v, _mm256_mul_pd(iLo, dtv));
  const __m256d tHi = _mm256_add_pd(t0v, _mm256_mul_pd(iHi, dtv));
  Cells c;
  for (int a = 0; a < 3; ++a)
  {
    Corner(Coordinate(o[a], d[a], k.CellShift, k.MaxValueIndex[a], tLo),
      Coordinate(o[a], d[a], k.CellShift, k.MaxValueIndex[a], tHi), k.LastCell[a], c.Index[a],
      c.W[a]);
  }
  // Blocks of 2^BlockShift cells per edge.
  c.Block = _mm256_add_epi32(_mm256_srli_epi32(c.Index[0], k.BlockShift),
    _mm256_mullo_epi32(
      _mm256_set1_epi32(k.Blocks[0]), _mm256_add_epi32(_mm256_srli_epi32(c.Index[1], k.BlockShift),
                                        _mm256_mullo_epi32(_mm256_set1_epi32(k.Blocks[1]),
                                          _mm256_srli_epi32(c.Index[2], k.BlockShift)))));
  c.Shared = SharedBlock(c.Block);
  return c;
}

// The interpolated values of a group's cells (skipped blocks are the caller's).
__attribute__((target("avx2"), always_inline)) inline __m256 GroupValues(
  const GridArrays& k, const Cells& c)
{
  const __m256 nan = _mm256_set1_ps(std::numeric_limits<float>::quiet_NaN());
  // Blocks whose points all hold one value give that value; a group that lies in them
  // entirely reads nothing else. Integers interpolate to exactly that value from the points
  // (a + w (a - a) is a), so only a group in one block needs to look; float lanes in several
  // blocks each take their block's (-0.0 would not survive the arithmetic).
  __m256 constant = nan;
  __m256 isConstant = _mm256_setzero_ps();
  if (k.AnyConstant && c.Shared >= 0)
  {
    const float value = k.BlockConstant[c.Shared];
    if (value == value)
    {
      return _mm256_set1_ps(value);
    }
  }
  else if (k.AnyConstant && k.Type == GridValueType::Float32)
  {
    constant = _mm256_i32gather_ps(k.BlockConstant, c.Block, 4);
    isConstant = _mm256_cmp_ps(constant, constant, _CMP_ORD_Q);
    if (_mm256_movemask_ps(isConstant) == 0xFF)
    {
      return constant;
    }
  }
  const __m256i offset =
    _mm256_add_epi32(_mm256_mullo_epi32(c.Index[0], _mm256_set1_epi32(k.Step[0])),
      _mm256_add_epi32(_mm256_mullo_epi32(c.Index[1], _mm256_set1_epi32(k.Step[1])),
        _mm256_mullo_epi32(c.Index[2], _mm256_set1_epi32(k.Step[2]))));
  const __m256i sx = _mm256_set1_epi32(k.Neighbour[0]);
  const __m256i offsetY = _mm256_add_epi32(offset, _mm256_set1_epi32(k.Neighbour[1]));
  const __m256i offsetZ = _mm256_add_epi32(offset, _mm256_set1_epi32(k.Neighbour[2]));
  const __m256i offsetYZ = _mm256_add_epi32(offsetY, _mm256_set1_epi32(k.Neighbour[2]));
  __m256 v000, v100, v010, v110, v001, v101, v011, v111;
  if (k.Neighbour[0] == 1)
  {
    // Single-component data: x neighbours share one read.
    LoadPair(k, offset, v000, v100);
    LoadPair(k, offsetY, v010, v110);
    LoadPair(k, offsetZ, v001, v101);
    LoadPair(k, offsetYZ, v011, v111);
  }
  else
  {
    const __m256i lastWord = _mm256_set1_epi32(static_cast<int>(k.Bytes) - 4);
    v000 = Load(k, offset, lastWord);
    v100 = Load(k, _mm256_add_epi32(offset, sx), lastWord);
    v010 = Load(k, offsetY, lastWord);
    v110 = Load(k, _mm256_add_epi32(offsetY, sx), lastWord);
    v001 = Load(k, offsetZ, lastWord);
    v101 = Load(k, _mm256_add_epi32(offsetZ, sx), lastWord);
    v011 = Load(k, offsetYZ, lastWord);
    v111 = Load(k, _mm256_add_epi32(offsetYZ, sx), lastWord);
  }
  const __m256 c00 = Lerp(v000, v100, c.W[0]);
  const __m256 c10 = Lerp(v010, v110, c.W[0]);
  const __m256 c01 = Lerp(v001, v101, c.W[0]);
  const __m256 c11 = Lerp(v011, v111, c.W[0]);
  const __m256 c0 = Lerp(c00, c10, c.W[1]);
  const __m256 c1 = Lerp(c01, c11, c.W[1]);
  const __m256 value = Lerp(c0, c1, c.W[2]);
  return _mm256_blendv_ps(value, constant, isConstant);
}

// Lanes [0, lanes) set, as a store mask.
__attribute__((target("avx2"))) inline __m256i LaneMask(int lanes)
{
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(lanes), _mm256_set_epi32(7, 6, 5, 4, 3, 2, 1, 0));
}
} // namespace

__attribute__((target("avx2"))) int SampleLinearAVX2(const GridArrays& k, const double o[3],
  const double d[3], double t0, double dt, int first, int last, float* out,
  const std::uint8_t* skipped)
{
  const __m256i lastFlagWord = _mm256_set1_epi32(k.NumberOfBlocks - 4);
  const __m256i allOnes = _mm256_set1_epi32(-1);
  const __m256 nan = _mm256_set1_ps(std::numeric_limits<float>::quiet_NaN());
  // Samples per cell along the axis the ray moves fastest on.
  const double fastest = std::max({ std::abs(d[0]), std::abs(d[1]), std::abs(d[2]) }) * dt;
  const double samplesPerCell = fastest > 0.0 ? 1.0 / fastest : 0.0;
  int i = first;
  for (; i <= last; i += 8)
  {
    // Lanes past `last` compute at clamped (valid) positions and are not stored.
    const __m256i store = LaneMask(last - i + 1);
    const Cells c = LocateGroup(k, o, d, t0, dt, i);
    // Samples in skipped blocks are NaN; a group that lies in them entirely reads nothing.
    __m256 skip = _mm256_setzero_ps();
    if (skipped)
    {
      __m256i flags;
      if (c.Shared >= 0)
      {
        flags = _mm256_set1_epi32(skipped[c.Shared]);
      }
      else
      {
        // Each lane's flag byte, read as the 4 bytes holding it, never past either end.
        const __m256i start = _mm256_min_epi32(c.Block, lastFlagWord);
        const __m256i words =
          _mm256_i32gather_epi32(reinterpret_cast<const int*>(skipped), start, 1);
        flags = _mm256_and_si256(
          _mm256_srlv_epi32(words, _mm256_slli_epi32(_mm256_sub_epi32(c.Block, start), 3)),
          _mm256_set1_epi32(0xFF));
      }
      skip = _mm256_castsi256_ps(
        _mm256_xor_si256(_mm256_cmpeq_epi32(flags, _mm256_setzero_si256()), allOnes));
      const int lanes = _mm256_movemask_ps(skip);
      if (lanes == 0xFF)
      {
        _mm256_maskstore_ps(out + i, store, nan);
        // The blocks around the last lane's are skipped too, as far as its distance says: the
        // samples that stay within them are NaN without a look at their blocks.
        const double reach = SkipReach(_mm256_extract_epi32(flags, 7), k.BlockShift);
        const int after = last - (i + 7); // samples left after the last lane
        if (reach > 0.0 && after > 0)
        {
          const int jump = static_cast<int>(std::min(reach * samplesPerCell, double(after)));
          for (int j = i + 8; j < i + 8 + jump; ++j)
          {
            out[j] = std::numeric_limits<float>::quiet_NaN();
          }
          i += jump;
        }
        continue;
      }
    }
    _mm256_maskstore_ps(out + i, store, _mm256_blendv_ps(GroupValues(k, c), nan, skip));
  }
  return last + 1;
}

namespace
{
// Three 16-bit codes per lane, at byte offsets `bytes`, as floats (one 8-byte read per lane;
// the codes are padded so that it stays inside).
__attribute__((target("avx2"))) inline void LoadCodes(
  const GradientArrays& g, __m256i bytes, __m256 codes[3])
{
  __m256i xy, z;
  LoadWordPairs(g.Codes, bytes, xy, z);
  codes[0] = _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(xy, 16), 16));
  codes[1] = _mm256_cvtepi32_ps(_mm256_srai_epi32(xy, 16));
  codes[2] = _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(z, 16), 16));
}

// The three 10-bit codes of each lane's packed word, as floats.
__attribute__((target("avx2"))) inline void Unpack(__m256i words, __m256 codes[3])
{
  codes[0] = _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(words, 22), 22));
  codes[1] = _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(words, 12), 22));
  codes[2] = _mm256_cvtepi32_ps(_mm256_srai_epi32(_mm256_slli_epi32(words, 2), 22));
}

// The three 10-bit codes of each lane's packed word at point `points`, as floats.
__attribute__((target("avx2"))) inline void LoadPacked(
  const GradientArrays& g, __m256i points, __m256 codes[3])
{
  Unpack(_mm256_i32gather_epi32(reinterpret_cast<const int*>(g.Packed), points, 4), codes);
}

// The codes of each lane's point `points` and of the next point along x (the word after it).
__attribute__((target("avx2"))) inline void LoadPackedPair(
  const GradientArrays& g, __m256i points, __m256 first[3], __m256 second[3])
{
  __m256i a, b;
  LoadWordPairs(g.Packed, _mm256_slli_epi32(points, 2), a, b);
  Unpack(a, first);
  Unpack(b, second);
}

// The codes of a cell's eight corners (x fastest, then y, then z) from the lower corners of its
// four x rows (`b000` .. `b011`) and the x neighbour's offset `sx`, as packed words or as three
// 16-bit codes.
template <bool Packed>
__attribute__((target("avx2"))) inline void LoadCorners(const GradientArrays& g, __m256i b000,
  __m256i b010, __m256i b001, __m256i b011, __m256i sx, __m256 corners[8][3])
{
  const __m256i rows[4] = { b000, b010, b001, b011 };
  for (int q = 0; q < 4; ++q)
  {
    if (Packed && g.Neighbour[0] == 1)
    {
      LoadPackedPair(g, rows[q], corners[2 * q], corners[2 * q + 1]);
      continue;
    }
    for (int x = 0; x < 2; ++x)
    {
      const __m256i at = x ? _mm256_add_epi32(rows[q], sx) : rows[q];
      if (Packed)
      {
        LoadPacked(g, at, corners[2 * q + x]);
      }
      else
      {
        LoadCodes(g, at, corners[2 * q + x]);
      }
    }
  }
}

// The low (h = 0) or high four floats of v.
__attribute__((target("avx2"))) inline __m128 Half(__m256 v, int h)
{
  return h == 0 ? _mm256_castps256_ps128(v) : _mm256_extractf128_ps(v, 1);
}

// The world gradients of a group's cells (three vectors: x, y and z of each lane), as
// GradientGrid::Interpolate gives them.
__attribute__((target("avx2"), always_inline)) inline void GroupGradients(
  const GradientArrays& g, const Cells& c, __m256 result[3])
{
  const __m256i zero = c.Shared >= 0 ? _mm256_set1_epi32(g.ZeroBlocks[c.Shared])
                                     : _mm256_i32gather_epi32(g.ZeroBlocks, c.Block, 4);
  if (_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(zero, _mm256_setzero_si256()))) ==
      0)
  {
    // Every lane's cell has zero codes at all its corners.
    result[0] = result[1] = result[2] = _mm256_setzero_ps();
    return;
  }
  // Corners as byte offsets of three 16-bit codes, or as points of packed words.
  const bool packed = g.Packed != nullptr;
  const int unit = packed ? 1 : 6;
  const __m256i point =
    _mm256_add_epi32(_mm256_mullo_epi32(c.Index[0], _mm256_set1_epi32(g.Step[0])),
      _mm256_add_epi32(_mm256_mullo_epi32(c.Index[1], _mm256_set1_epi32(g.Step[1])),
        _mm256_mullo_epi32(c.Index[2], _mm256_set1_epi32(g.Step[2]))));
  const __m256i sx = _mm256_set1_epi32(unit * g.Neighbour[0]);
  const __m256i sy = _mm256_set1_epi32(unit * g.Neighbour[1]);
  const __m256i sz = _mm256_set1_epi32(unit * g.Neighbour[2]);
  const __m256i b000 = _mm256_mullo_epi32(point, _mm256_set1_epi32(unit));
  const __m256i b010 = _mm256_add_epi32(b000, sy);
  const __m256i b001 = _mm256_add_epi32(b000, sz);
  const __m256i b011 = _mm256_add_epi32(b010, sz);
  // Per corner (x fastest, then y, then z), its three codes.
  __m256 corners[8][3];
  const auto& v000 = corners[0];
  const auto& v100 = corners[1];
  const auto& v010 = corners[2];
  const auto& v110 = corners[3];
  const auto& v001 = corners[4];
  const auto& v101 = corners[5];
  const auto& v011 = corners[6];
  const auto& v111 = corners[7];
  if (packed)
  {
    LoadCorners<true>(g, b000, b010, b001, b011, sx, corners);
  }
  else
  {
    LoadCorners<false>(g, b000, b010, b001, b011, sx, corners);
  }
  __m256 index3[3];
  for (int a = 0; a < 3; ++a)
  {
    const __m256 c00 = Lerp(v000[a], v100[a], c.W[0]);
    const __m256 c10 = Lerp(v010[a], v110[a], c.W[0]);
    const __m256 c01 = Lerp(v001[a], v101[a], c.W[0]);
    const __m256 c11 = Lerp(v011[a], v111[a], c.W[0]);
    index3[a] = Lerp(Lerp(c00, c10, c.W[1]), Lerp(c01, c11, c.W[1]), c.W[2]);
  }
  for (int r = 0; r < 3; ++r)
  {
    // As GradientGrid::World: ((m0 x + m1 y) + m2 z) + 0.
    const __m256 m0 = _mm256_set1_ps(g.ToWorld[3 * r]);
    const __m256 m1 = _mm256_set1_ps(g.ToWorld[3 * r + 1]);
    const __m256 m2 = _mm256_set1_ps(g.ToWorld[3 * r + 2]);
    result[r] = _mm256_add_ps(
      _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(m0, index3[0]), _mm256_mul_ps(m1, index3[1])),
        _mm256_mul_ps(m2, index3[2])),
      _mm256_setzero_ps());
  }
}

// EncodeNormal's codes of a group's gradients, lanes [0, lanes) into `normals`.
__attribute__((target("avx2"), always_inline)) inline void StoreNormalCodes(
  const __m256 gradient[3], int lanes, std::uint16_t* normals)
{
  __m128i half[2];
  for (int h = 0; h < 2; ++h)
  {
    half[h] = NormalCodes(_mm256_cvtps_pd(Half(gradient[0], h)),
      _mm256_cvtps_pd(Half(gradient[1], h)), _mm256_cvtps_pd(Half(gradient[2], h)));
  }
  // Eight codes below 2^16, as 16-bit words in lane order.
  alignas(16) std::uint16_t codes[8];
  _mm_store_si128(reinterpret_cast<__m128i*>(codes), _mm_packus_epi32(half[0], half[1]));
  std::memcpy(normals, codes, sizeof(std::uint16_t) * static_cast<std::size_t>(lanes));
}
} // namespace

__attribute__((target("avx2"))) void SampleGradientsAVX2(const GridArrays& k,
  const GradientArrays& g, const double o[3], const double d[3], double t0, double dt, int first,
  int last, float* gradients)
{
  alignas(32) float world[3][8];
  for (int i = first; i <= last; i += 8)
  {
    __m256 result[3];
    GroupGradients(g, LocateGroup(k, o, d, t0, dt, i), result);
    for (int r = 0; r < 3; ++r)
    {
      _mm256_store_ps(world[r], result[r]);
    }
    float* out = gradients + 3 * static_cast<std::ptrdiff_t>(i);
    for (int l = 0, lanes = std::min(8, last - i + 1); l < lanes; ++l)
    {
      out[3 * l] = world[0][l];
      out[3 * l + 1] = world[1][l];
      out[3 * l + 2] = world[2][l];
    }
  }
}

__attribute__((target("avx2"))) void SampleValuesAndNormalsAVX2(const GridArrays& k,
  const GradientArrays& g, const double o[3], const double d[3], double t0, double dt, int first,
  int last, float* out, std::uint16_t* normals)
{
  for (int i = first; i <= last; i += 8)
  {
    const int lanes = std::min(8, last - i + 1);
    const Cells c = LocateGroup(k, o, d, t0, dt, i);
    _mm256_maskstore_ps(out + i, LaneMask(lanes), GroupValues(k, c));
    __m256 gradient[3];
    GroupGradients(g, c, gradient);
    StoreNormalCodes(gradient, lanes, normals + i);
  }
}

#else

int SampleLinearAVX2(const GridArrays&, const double*, const double*, double, double, int first,
  int, float*, const std::uint8_t*)
{
  return first;
}

void SampleGradientsAVX2(const GridArrays&, const GradientArrays&, const double*, const double*,
  double, double, int, int, float*)
{
}

void SampleValuesAndNormalsAVX2(const GridArrays&, const GradientArrays&, const double*,
  const double*, double, double, int, int, float*, std::uint16_t*)
{
}

#endif

} // namespace detail
} // namespace savr

#pragma once
// The plain stored composite: a stored ray blended without lighting, gradient opacity or second
// codes, each sample's interval opacity and colour looked up in a table per interval length.

#include "blend/Integrator.h"
#include "blend/StoredAVX2.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace savr
{
namespace detail
{

// Composites a tabulated sample (its opacity, then its colour times it) front to back.
inline void CompositeEntry(const double* entry, Eigen::Array3d& C, double& T)
{
  composite::OverPremultiplied(C, T, entry[0], Eigen::Array3d(entry[1], entry[2], entry[3]));
}

// Composites a tabulated sample lit by shading factors `f` (ShadingTable::FactorsOf).
inline void CompositeLitEntry(const double* entry, const float* f, Eigen::Array3d& C, double& T)
{
  composite::OverPremultiplied(C, T, entry[0], composite::ShadedPremultiplied(entry, f));
}

// Per code, the opacity of an interval of length h and the colour times it.
inline void PremultipliedTable(
  const TransferFunctionTable& tf, double h, std::vector<double>& table)
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

// Rows ahead of the one blended whose shading factors CompositeLitRows asks for.
constexpr int kFactorsAhead = 2;

// CompositeRows, each sample lit by its stored normal.
template <int F, typename Code>
bool CompositeLitRows(const RayLayout<Code>& ray, const double* const* tables, int begin, int end,
  Eigen::Array3d& C, double& T, double termination, const ShadingTable& shading)
{
  const int frames = F > 0 ? F : ray.Frames;
  const int* order = ray.Order;
  const std::size_t capacity = static_cast<std::size_t>(ray.Capacity);
  Eigen::Array3d c = C;
  double t = T;
  bool stopped = false;
  for (int j = begin; j < end && !stopped; ++j)
  {
    const std::size_t rowStart = static_cast<std::size_t>(j) * capacity;
    const Code* row = ray.Codes + rowStart;
    const std::uint16_t* normals = ray.Normals + rowStart;
    if (j + kFactorsAhead < end)
    {
      // The factors are a table of 1.5 MiB read at random: asked for a few rows ahead, their
      // reads overlap the blend's chain of transmittances.
      const std::uint16_t* ahead = normals + kFactorsAhead * capacity;
      for (int s = 0; s < frames; ++s)
      {
        __builtin_prefetch(shading.FactorsOf(ahead[order[s]]));
      }
    }
    for (int s = 0; s < frames; ++s)
    {
      const int slot = order[s];
      const double* entry = tables[s] + 4 * static_cast<std::size_t>(row[slot]);
      if (entry[0] == 0.0)
      {
        continue; // transparent: adds nothing, absorbs nothing
      }
      CompositeLitEntry(entry, shading.FactorsOf(normals[slot]), c, t);
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

// Rows [begin, end) of a stored ray whose every rank has a table (`tables[s]`: the premultiplied
// table of rank s's interval), composited front to back; `F` frames when above 0, else
// `ray.Frames` (a known count lets the compiler unroll the row). Returns whether the ray
// reached the termination transmittance.
// With `shading`, each sample is lit by its stored normal.
template <int F, typename Code>
bool CompositeRows(const RayLayout<Code>& ray, const double* const* tables, int begin, int end,
  Eigen::Array3d& C, double& T, double termination, const ShadingTable* shading = nullptr)
{
  if (shading)
  {
    return CompositeLitRows<F>(ray, tables, begin, end, C, T, termination, *shading);
  }
  const int frames = F > 0 ? F : ray.Frames;
  const int* order = ray.Order;
  const std::size_t capacity = static_cast<std::size_t>(ray.Capacity);
  // Locals, which stay in registers: through the references, every sample would store them
  // (a table read might alias them).
  Eigen::Array3d c = C;
  double t = T;
  bool stopped = false;
  for (int j = begin; j < end && !stopped; ++j)
  {
    const Code* row = ray.Codes + static_cast<std::size_t>(j) * capacity;
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
  Eigen::Array3d& C, double& T, double termination, const ShadingTable* shading = nullptr)
{
  switch (ray.Frames)
  {
    case 1:
      return CompositeRows<1>(ray, tables, begin, end, C, T, termination, shading);
    case 2:
      return CompositeRows<2>(ray, tables, begin, end, C, T, termination, shading);
    case 3:
      return CompositeRows<3>(ray, tables, begin, end, C, T, termination, shading);
    case 4:
      return CompositeRows<4>(ray, tables, begin, end, C, T, termination, shading);
    default:
      return CompositeRows<0>(ray, tables, begin, end, C, T, termination, shading);
  }
}

// A stored ray composited without gradient opacity or second codes, lit by its stored normals
// when `shading` is given: as StreamInDepthOrder feeds
// SampleStream and CompositeBlendT<false>, but with each interior sample's interval known from
// its rank among the offsets (`tables[s]`: the premultiplied table for the interval of rank s,
// or null when it has none), so that a sample costs a lookup and a composite without branches.
// In three steps, so that the rows between the first and the last can also be walked for
// several rays at once: Begin (the first row), the rows between, End (the last row).
// Rows at either end whose every code is transparent (below `scan`'s threshold) are passed over:
// a transparent sample multiplies the transmittance by exactly 1 and adds exactly 0, so the
// pixel keeps every bit. (In front of and behind most data lie such rows: air, background.)
template <typename Code>
class PlainComposite
{
public:
  PlainComposite(const RayLayout<Code>& ray, const TransferFunctionTable& tf,
    const AlphaCache& alphas, const double* const* tables, const RowScan<Code>* scan,
    double termination, const ShadingTable* shading = nullptr)
    : Ray(ray)
    , TF(tf)
    , Alphas(alphas)
    , Tables(tables)
    , Termination(termination)
    , Shading(ray.Normals ? shading : nullptr)
  {
    // The last valid sample: only the last row can reach past the exit.
    this->LastRow = ray.SamplesPerFrame - 1;
    this->LastRank = ray.Frames - 1;
    while (this->LastRow >= 0 && !(this->Position(this->LastRow, this->LastRank) < ray.Length))
    {
      if (--this->LastRank < 0)
      {
        this->LastRank = ray.Frames - 1;
        --this->LastRow;
      }
    }
    this->AllTabled = true;
    for (int s = 0; s < ray.Frames; ++s)
    {
      this->AllTabled = this->AllTabled && tables[s];
    }
    // The first and the last row with a code that may not be transparent (every slot in use
    // is looked at, even past the last sample: that can only keep more rows).
    this->Lead = std::max(ray.FirstRow, 0);
    this->Tail = this->LastRow;
    if (scan && scan->Threshold > 0 && scan->Capacity == ray.Capacity &&
        this->Lead <= this->LastRow)
    {
      const std::size_t skipped = static_cast<std::size_t>(this->Lead) * ray.Capacity;
      this->Lead += scan->First(ray.Codes + skipped, this->LastRow + 1 - this->Lead);
      if (this->Lead <= this->LastRow)
      {
        this->Tail = scan->Last(ray.Codes, this->Lead, this->LastRow + 1);
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
      this->Done = CompositeRowsOf(
        this->Ray, this->Tables, begin, end, this->C, this->T, this->Termination, this->Shading);
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
    return this->LastRow < 0 ? Pixel::Zero() : composite::FrontToBack(this->C, this->T);
  }
  /// Rows [From(), To()) lie between the first and the last, and hold every row there that
  /// is not transparent.
  int From() const { return std::max(1, this->Lead); }
  int To() const { return std::min(this->LastRow, this->Tail + 1); }
  Pixel Blend()
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
  const ShadingTable* Shading; // null: unlit
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
    return (j + this->Ray.U[this->Ray.Order[s]]) * this->Ray.Dt;
  }

  // A sample whose interval is computed from its neighbours' positions (ray ends, and
  // intervals without a table).
  void General(int j, int s, std::uint32_t code)
  {
    if (this->TF.Extinction(code) == 0.0)
    {
      return;
    }
    const int frames = this->Ray.Frames;
    const double here = this->Position(j, s);
    const bool first = j == 0 && s == 0;
    const bool last = j == this->LastRow && s == this->LastRank;
    const double before = s > 0 ? this->Position(j, s - 1) : this->Position(j - 1, frames - 1);
    const double after = s + 1 < frames ? this->Position(j, s + 1) : this->Position(j + 1, 0);
    const double h = SampleInterval::Length(before, here, after, first, last, this->Ray.Length);
    const double a = this->Alphas.Alpha(this->TF, code, h);
    const float* rgb = this->TF.Color(code);
    composite::Over(this->C, this->T, a,
      this->Shading ? this->Shading->Shade(rgb, this->NormalAt(j, s))
                    : Eigen::Array3d(rgb[0], rgb[1], rgb[2]));
  }

  std::uint16_t NormalAt(int j, int s) const
  {
    return this->Ray.Normals[static_cast<std::size_t>(j) * this->Ray.Capacity + this->Ray.Order[s]];
  }

  // A row sample by sample: its ranks' tables where they have one, except at the ray's ends.
  // Returns whether the ray reached the termination transmittance.
  bool Row(int j)
  {
    const Code* codes = this->Ray.Codes + static_cast<std::size_t>(j) * this->Ray.Capacity;
    const int ranks = j == this->LastRow ? this->LastRank + 1 : this->Ray.Frames;
    const bool edge = j == 0 || j == this->LastRow;
    for (int s = 0; s < ranks; ++s)
    {
      const std::uint32_t code = codes[this->Ray.Order[s]];
      const double* table = this->Tables[s];
      if (table && !(edge && ((j == 0 && s == 0) || (j == this->LastRow && s == this->LastRank))))
      {
        const double* entry = table + 4 * static_cast<std::size_t>(code);
        if (this->Shading)
        {
          CompositeLitEntry(
            entry, this->Shading->FactorsOf(this->NormalAt(j, s)), this->C, this->T);
        }
        else
        {
          CompositeEntry(entry, this->C, this->T);
        }
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

// Four plain stored rays (`layouts`, each rank's table from `tablesOf(g)`), composited with their
// rows between the first and the last composited together where the CPU can, into `pixels`.
// The same pixels as compositing each alone.
template <typename Code, typename TablesOf>
void CompositeFour(const RayLayout<Code> layouts[4], const TablesOf& tablesOf,
  const RowScan<Code>* scan, const TransferFunctionTable& tf, const AlphaCache& alphas,
  double termination, float* pixels, const int pixelOf[4])
{
  PlainComposite<Code> w0(layouts[0], tf, alphas, tablesOf(0), scan, termination);
  PlainComposite<Code> w1(layouts[1], tf, alphas, tablesOf(1), scan, termination);
  PlainComposite<Code> w2(layouts[2], tf, alphas, tablesOf(2), scan, termination);
  PlainComposite<Code> w3(layouts[3], tf, alphas, tablesOf(3), scan, termination);
  PlainComposite<Code>* const composites[4] = { &w0, &w1, &w2, &w3 };
  // The rows between each ray's first and last together, where the CPU can.
  bool going = false;
  for (PlainComposite<Code>* w : composites)
  {
    going = w->Begin() || going;
  }
  bool together = false;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  const int frames = layouts[0].Frames;
  if (going && frames <= 4)
  {
    switch (frames)
    {
      case 1:
        CompositeRowsFour<1>(composites);
        break;
      case 2:
        CompositeRowsFour<2>(composites);
        break;
      case 3:
        CompositeRowsFour<3>(composites);
        break;
      default:
        CompositeRowsFour<4>(composites);
        break;
    }
    together = true;
  }
#endif
  for (int i = 0; i < 4; ++i)
  {
    if (!together)
    {
      composites[i]->Rows();
    }
    const Pixel p = composites[i]->End();
    std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(pixelOf[i]));
  }
}

} // namespace detail
} // namespace savr

#include "frame/CompositeTables.h"

#include "blend/PlainComposite.h"
#include "frame/OffsetSequence.h"

#include <cmath>

namespace savr
{

const std::vector<double>& CompositeTables::Table::Of(
  const TransferFunctionTable& tf, double length)
{
  if (this->Generation != tf.Generation() || this->Length != length || this->Entries.empty())
  {
    detail::PremultipliedTable(tf, length, this->Entries);
    this->Generation = tf.Generation();
    this->Length = length;
  }
  return this->Entries;
}

const std::vector<double>& CompositeTables::Step(const TransferFunctionTable& tf, double step)
{
  return this->StepTable.Of(tf, step);
}

void CompositeTables::Intervals(const TransferFunctionTable& tf, const OffsetSequence& offsets,
  int frames, double dt, std::vector<const double*>& sorted)
{
  // Interior intervals are one of three lengths (the gaps between offsets take two).
  const double gap = OffsetSequence::SmallestGap(frames) * dt;
  const double lengths[3] = { gap, 1.5 * gap, 2.0 * gap };
  for (int k = 0; k < 3; ++k)
  {
    this->IntervalTables[k].Of(tf, lengths[k]);
  }
  // A rotation shifts which rank an offset has, not the gaps.
  sorted.assign(frames, nullptr);
  for (int p = 0; p < frames; ++p)
  {
    const auto base = [&](int q) { return offsets.Offset(offsets.SortedFrame(q)); };
    const double before = p > 0 ? base(p - 1) : base(frames - 1) - 1.0;
    const double after = p + 1 < frames ? base(p + 1) : base(0) + 1.0;
    const double h = 0.5 * (after - before) * dt;
    for (const Table& table : this->IntervalTables)
    {
      if (std::abs(h - table.Length) <= 1e-9 * table.Length)
      {
        sorted[p] = table.Entries.data();
      }
    }
  }
}

} // namespace savr

#pragma once
// The per-code tables the composite's fast paths read: for an interval length, each code's
// opacity over it and its colour times that opacity (PremultipliedTable). A single pass needs
// the table of its step; stored rays, those of the three lengths an interior interval between
// interleaved frames can take. Each is rebuilt only when the transfer function or the length
// changes.

#include "blend/TransferFunctionTable.h"

#include <cstdint>
#include <vector>

namespace savr
{

class OffsetSequence;

class CompositeTables
{
public:
  /// The table of one step of length `step`, for a single pass.
  const std::vector<double>& Step(const TransferFunctionTable& tf, double step);

  /// For stored rays at base step `dt` and the first `frames` of `offsets`: into `sorted`, each
  /// sorted offset's table, for the interval halfway to the offsets either side (across rows at
  /// the ends), or null where that interval is not one of the three tabulated lengths.
  void Intervals(const TransferFunctionTable& tf, const OffsetSequence& offsets, int frames,
    double dt, std::vector<const double*>& sorted);

private:
  struct Table
  {
    std::vector<double> Entries;
    double Length = 0.0;
    std::uint64_t Generation = 0; // of the transfer function
    const std::vector<double>& Of(const TransferFunctionTable& tf, double length);
  };
  Table StepTable;
  Table IntervalTables[3]; // the smallest gap, 1.5 times it and twice it
};

} // namespace savr

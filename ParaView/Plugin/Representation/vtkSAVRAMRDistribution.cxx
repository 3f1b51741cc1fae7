#include "vtkSAVRAMRDistribution.h"

#include "vtkAMRBox.h"
#include "vtkCellData.h"
#include "vtkImageData.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkUniformGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace vtkSAVRAMRDistribution
{
namespace
{
constexpr int kBlockTag = 48213;

struct Block
{
  unsigned int Level = 0;
  unsigned int Id = 0;
  Box Bounds{};            // in the hierarchy's coordinates
  double CellVolume = 1.0; // of its level
};

std::vector<Block> Blocks(vtkOverlappingAMR* amr)
{
  std::vector<Block> blocks;
  const double* origin = amr->GetOrigin();
  for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
  {
    double h[3];
    amr->GetSpacing(level, h);
    for (unsigned int id = 0; id < amr->GetNumberOfDataSets(level); ++id)
    {
      const vtkAMRBox& box = amr->GetAMRBox(level, id);
      if (box.IsInvalid())
      {
        continue;
      }
      Block b;
      b.Level = level;
      b.Id = id;
      b.CellVolume = h[0] * h[1] * h[2];
      for (int a = 0; a < 3; ++a)
      {
        b.Bounds[2 * a] = origin[a] + box.GetLoCorner()[a] * h[a];
        b.Bounds[2 * a + 1] = origin[a] + (box.GetHiCorner()[a] + 1) * h[a];
      }
      blocks.push_back(b);
    }
  }
  return blocks;
}

double Overlap(const Box& a, const Box& b)
{
  double volume = 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double lo = std::max(a[2 * axis], b[2 * axis]);
    const double hi = std::min(a[2 * axis + 1], b[2 * axis + 1]);
    if (hi <= lo)
    {
      return 0.0;
    }
    volume *= hi - lo;
  }
  return volume;
}

// Level-0 cells as integer boxes [lo, hi) per axis; world = origin + index * h0.
struct Split
{
  const std::vector<Block>& Blocks;
  const double* Origin;
  double H0[3];
  std::vector<Box>& Out;

  Box World(const long long lo[3], const long long hi[3]) const
  {
    Box box;
    for (int a = 0; a < 3; ++a)
    {
      box[2 * a] = this->Origin[a] + lo[a] * this->H0[a];
      box[2 * a + 1] = this->Origin[a] + hi[a] * this->H0[a];
    }
    return box;
  }

  // Cuts [lo, hi) among `count` ranks starting at `first`.
  void Cut(long long lo[3], long long hi[3], int first, int count) const
  {
    if (count == 1)
    {
      this->Out[first] = this->World(lo, hi);
      return;
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if ((hi[a] - lo[a]) * this->H0[a] > (hi[axis] - lo[axis]) * this->H0[axis])
      {
        axis = a;
      }
    }
    // The cells of every level in each level-0 slab across the axis.
    const long long slabs = hi[axis] - lo[axis];
    std::vector<double> weight(static_cast<std::size_t>(std::max(slabs, 0LL)), 0.0);
    for (long long k = 0; k < slabs; ++k)
    {
      long long slabLo[3] = { lo[0], lo[1], lo[2] };
      long long slabHi[3] = { hi[0], hi[1], hi[2] };
      slabLo[axis] = lo[axis] + k;
      slabHi[axis] = lo[axis] + k + 1;
      const Box slab = this->World(slabLo, slabHi);
      for (const Block& b : this->Blocks)
      {
        weight[k] += Overlap(slab, b.Bounds) / b.CellVolume;
      }
    }
    const int left = count / 2;
    const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
    const double target = total * left / count;
    // The cut whose left side's cells come closest to its share, with a slab at least on either
    // side; with a single slab the left side is empty (more ranks than level-0 cells across).
    long long cut = lo[axis];
    if (slabs >= 2)
    {
      double sum = 0.0;
      double best = std::numeric_limits<double>::infinity();
      for (long long k = 1; k < slabs; ++k)
      {
        sum += weight[k - 1];
        if (std::abs(sum - target) < best)
        {
          best = std::abs(sum - target);
          cut = lo[axis] + k;
        }
      }
    }
    long long leftHi[3] = { hi[0], hi[1], hi[2] };
    long long rightLo[3] = { lo[0], lo[1], lo[2] };
    leftHi[axis] = cut;
    rightLo[axis] = cut;
    this->Cut(lo, leftHi, first, left);
    this->Cut(rightLo, hi, first + left, count - left);
  }
};

Box Grown(const Box& box, const double h[3])
{
  Box grown = box;
  for (int a = 0; a < 3; ++a)
  {
    grown[2 * a] -= h[a];
    grown[2 * a + 1] += h[a];
  }
  return grown;
}
} // namespace

std::vector<Box> Regions(vtkOverlappingAMR* amr, int count)
{
  std::vector<Box> regions;
  if (!amr || amr->GetNumberOfLevels() == 0 || count < 1)
  {
    return regions;
  }
  long long lo[3] = { 0, 0, 0 };
  long long hi[3] = { 0, 0, 0 };
  bool any = false;
  for (unsigned int id = 0; id < amr->GetNumberOfDataSets(0); ++id)
  {
    const vtkAMRBox& box = amr->GetAMRBox(0, id);
    if (box.IsInvalid())
    {
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      const long long l = box.GetLoCorner()[a];
      const long long h = box.GetHiCorner()[a] + 1;
      lo[a] = any ? std::min(lo[a], l) : l;
      hi[a] = any ? std::max(hi[a], h) : h;
    }
    any = true;
  }
  if (!any)
  {
    return regions;
  }
  const std::vector<Block> blocks = Blocks(amr);
  regions.resize(static_cast<std::size_t>(count));
  double h0[3];
  amr->GetSpacing(0, h0);
  Split split{ blocks, amr->GetOrigin(), { h0[0], h0[1], h0[2] }, regions };
  split.Cut(lo, hi, 0, count);
  return regions;
}

bool Distribute(vtkOverlappingAMR* local, vtkMultiProcessController* controller, bool gather,
  Result& result, std::string& error)
{
  const int ranks = controller->GetNumberOfProcesses();
  const int me = controller->GetLocalProcessId();
  const std::vector<Block> blocks = Blocks(local);
  const int count = static_cast<int>(blocks.size());
  // Every rank must see the same metadata; checked on what every rank receives, so that all
  // ranks agree whether to go on (a rank that gave up alone would leave the others waiting).
  std::vector<int> counts(static_cast<std::size_t>(ranks), 0);
  controller->AllGather(&count, counts.data(), 1);
  if (std::any_of(counts.begin(), counts.end(), [&](int c) { return c != count; }))
  {
    error = "the ranks' AMR metadata differ (block counts " + std::to_string(counts.front()) +
            " and " + std::to_string(count) + "): it cannot be spread over the ranks";
    return false;
  }
  std::vector<Box> regions = Regions(local, gather ? 1 : ranks);
  if (regions.empty() || count == 0)
  {
    error = "the AMR hierarchy has no level-0 block";
    return false;
  }
  // Gathering: the other ranks' regions are empty boxes at the domain's corner.
  const Box corner = { regions[0][0], regions[0][0], regions[0][2], regions[0][2], regions[0][4],
    regions[0][4] };
  regions.resize(static_cast<std::size_t>(ranks), corner);
  result.Empty = gather && me != 0;
  // Who holds what.
  std::vector<int> held(static_cast<std::size_t>(count), 0);
  for (int b = 0; b < count; ++b)
  {
    held[b] = local->GetDataSet(blocks[b].Level, blocks[b].Id) != nullptr ? 1 : 0;
  }
  std::vector<int> heldBy(static_cast<std::size_t>(count) * ranks, 0);
  controller->AllGather(held.data(), heldBy.data(), count);
  const auto holds = [&](int rank, int b)
  { return heldBy[static_cast<std::size_t>(rank) * count + b] != 0; };
  std::vector<int> owner(static_cast<std::size_t>(count), -1);
  for (int b = 0; b < count; ++b)
  {
    for (int r = 0; r < ranks && owner[b] < 0; ++r)
    {
      owner[b] = holds(r, b) ? r : -1;
    }
  }
  double h0[3];
  local->GetSpacing(0, h0);
  const auto needs = [&](int rank, int b)
  { return (!gather || rank == 0) && Overlap(Grown(regions[rank], h0), blocks[b].Bounds) > 0.0; };

  result.Hierarchy = vtkSmartPointer<vtkOverlappingAMR>::New();
  result.Hierarchy->ShallowCopy(local);
  result.Region = regions[me];
  result.BlocksReceived = 0;
  // One round per sender, in rank order; within a round the sender sends to each rank in order
  // the blocks it owns and that rank needs and lacks, in block order, which is the order the
  // receivers expect them in.
  for (int sender = 0; sender < ranks; ++sender)
  {
    for (int b = 0; b < count; ++b)
    {
      if (owner[b] != sender)
      {
        continue;
      }
      if (me == sender)
      {
        // Communicators marshal image data, not uniform grids: the same structure and arrays
        // (blanking is in the cell data's ghost array).
        vtkUniformGrid* grid = local->GetDataSet(blocks[b].Level, blocks[b].Id);
        vtkNew<vtkImageData> image;
        image->CopyStructure(grid);
        image->GetPointData()->ShallowCopy(grid->GetPointData());
        image->GetCellData()->ShallowCopy(grid->GetCellData());
        for (int r = 0; r < ranks; ++r)
        {
          if (r != me && needs(r, b) && !holds(r, b))
          {
            controller->Send(image, r, kBlockTag);
          }
        }
      }
      else if (needs(me, b) && !holds(me, b))
      {
        vtkNew<vtkImageData> image;
        controller->Receive(image, sender, kBlockTag);
        vtkNew<vtkUniformGrid> grid;
        grid->CopyStructure(image);
        grid->GetPointData()->ShallowCopy(image->GetPointData());
        grid->GetCellData()->ShallowCopy(image->GetCellData());
        result.Hierarchy->SetDataSet(blocks[b].Level, blocks[b].Id, grid);
        ++result.BlocksReceived;
      }
    }
  }
  // What the region does not need is not kept.
  result.BlocksHeld = 0;
  for (int b = 0; b < count; ++b)
  {
    if (!needs(me, b))
    {
      result.Hierarchy->SetDataSet(blocks[b].Level, blocks[b].Id, nullptr);
    }
    else if (result.Hierarchy->GetDataSet(blocks[b].Level, blocks[b].Id))
    {
      ++result.BlocksHeld;
    }
  }
  return true;
}
} // namespace vtkSAVRAMRDistribution

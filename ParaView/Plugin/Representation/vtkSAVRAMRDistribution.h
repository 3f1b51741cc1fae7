#pragma once
// How "SAVR Volume" draws an overlapping AMR hierarchy on several ranks.
//
// Blocks of different ranks interleave in depth, so their images cannot be composited in order.
// Instead every rank draws one convex region of the domain: the level-0 domain is cut into as
// many boxes as there are ranks by a kd-tree (each cut on a level-0 cell boundary, across the
// longest edge, balancing the cells of all levels on either side), each rank receives from the
// others the blocks that reach into its region or into one level-0 cell around it (enough for
// trilinear interpolation at the region's faces, on every level), samples inside its region only,
// and declares the region to the view for ordered compositing. Blocks that no rank holds stay
// holes, as in one process. Every rank computes the same regions from the hierarchy's metadata,
// which every rank has in full.
//
// Blend modes other than composite (maximum, minimum and average intensity, additive) do not
// composite front to back, which is how the view combines the ranks' images; for them every block
// is gathered on the first rank, which draws the whole domain, and the other ranks draw nothing.

#include "vtkSmartPointer.h"

#include <array>
#include <string>
#include <vector>

class vtkMultiProcessController;
class vtkOverlappingAMR;

namespace vtkSAVRAMRDistribution
{
using Box = std::array<double, 6>; // xmin, xmax, ymin, ymax, zmin, zmax

/// `count` convex boxes that tile the level-0 domain of `amr` (in its coordinates), balanced by
/// the cells of every level; box i is rank i's region. Empty when the hierarchy has no level-0
/// block.
std::vector<Box> Regions(vtkOverlappingAMR* amr, int count);

struct Result
{
  /// The hierarchy's metadata in full, with the data of the blocks this rank's region needs.
  vtkSmartPointer<vtkOverlappingAMR> Hierarchy;
  Box Region{};           // this rank's region
  bool Empty = false;     // this rank draws nothing (every block gathered on another rank)
  int BlocksReceived = 0; // from other ranks
  int BlocksHeld = 0;     // in Hierarchy
};

/// Collective over `controller`: every rank calls it with its own part of the same hierarchy
/// (the blocks it holds; metadata for all). False, with `error` set, when the hierarchy cannot be
/// spread (no level-0 block, or metadata that differs between ranks).
/// With `gather`, rank 0's region is the whole domain and the other ranks' regions are empty
/// (they hold no blocks).
bool Distribute(vtkOverlappingAMR* local, vtkMultiProcessController* controller, bool gather,
  Result& result, std::string& error);
} // namespace vtkSAVRAMRDistribution

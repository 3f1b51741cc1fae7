#pragma once
// The buffers a thread's passes work in, and how a pass runs over the tiles with them: what
// the files of the frame's passes share.

#include "frame/FrameState.h"
#include "frame/RayStores.h"

#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace savr
{

struct ThreadBuffers
{
  std::vector<float> Values;
  std::vector<float> Gradients;
  std::vector<std::uint16_t> SecondCodes;
  std::vector<std::uint16_t> Normals;
  std::vector<double> U;
  std::vector<int> Order;
  std::vector<const double*> Tables;
  std::vector<std::uint32_t> Codes;
  std::vector<float> ComponentGradients;    // each component's, with their gradient opacity
  std::vector<SampleAttributes> Attributes; // a single pass's chunk: normal and magnitude codes
  std::vector<PathPiece> Path;              // a ray's path as it is traced
  std::size_t Sampled = 0;                  // samples the tile at hand took
  // A tile's stores while its rays' rows are laid out anew: its first frame, sampled here
  // with whole rows of one slot, and the stores a resumption lays out (SamplingPass).
  RayStores Relaid;
  std::vector<char> Flags; // per ray of the tile at hand
};

struct ThreadScratch
{
  tbb::enumerable_thread_specific<ThreadBuffers> Local;
};

template <typename Body>
std::size_t FrameState::ForEachTile(
  Body&& body, std::size_t first, double seconds, const std::vector<std::size_t>* tiles)
{
  return this->Schedule.ForEach(
    [&](Tile& tile) { body(tile, this->Scratch->Local.local()); }, first, seconds, tiles);
}

} // namespace savr

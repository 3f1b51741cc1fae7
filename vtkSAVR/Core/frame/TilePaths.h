#pragma once
// What a tile of the frame loop keeps of its rays' paths (Sampler::TracePath) while a view
// accumulates: traced by the first frame, read by the later ones, within the tile's share of the
// memory budget. Each tile is worked on by one thread at a time, in the order of its rays, so
// which rays have paths does not depend on the thread count.

#include "sampler/Sampler.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

namespace savr
{

class TilePaths
{
public:
  /// Forgets every path; the tile may hold `quotaBytes` of paths for its `rays` rays (none
  /// when 0).
  void Reset(std::size_t rays, std::size_t quotaBytes)
  {
    this->Release();
    this->Rays = rays;
    this->Quota = quotaBytes;
  }

  /// Frees every path and keeps none from now on.
  void Release()
  {
    std::vector<std::unique_ptr<PathPiece[]>>().swap(this->Chunks);
    std::vector<const PathPiece*>().swap(this->Starts);
    std::vector<std::uint32_t>().swap(this->Counts);
    this->ChunkRoom = 0;
    this->Traced = 0;
    this->Pieces = 0;
    this->Held = 0;
    this->Quota = 0;
  }

  bool Active() const { return this->Quota > 0; }
  std::size_t Bytes() const { return this->Held; }

  /// Whether ray `r` (its index in the tile) has not been traced since Reset.
  bool Untraced(std::size_t r) const
  {
    return this->Counts.empty() || this->Counts[r] == kUntraced;
  }

  /// The pieces of ray `r`'s path, or null when it has none.
  const PathPiece* Path(std::size_t r, std::size_t& pieces) const
  {
    if (this->Counts.empty() || this->Counts[r] >= kNoPath)
    {
      pieces = 0;
      return nullptr;
    }
    pieces = this->Counts[r];
    return this->Starts[r];
  }

  /// Keeps `traced` as ray `r`'s path if it fits the quota (ok: false marks the ray as having
  /// none, and later frames sample the data).
  void Keep(std::size_t r, const std::vector<PathPiece>& traced, bool ok)
  {
    if (this->Counts.empty())
    {
      const std::size_t table = this->Rays * (sizeof(const PathPiece*) + sizeof(std::uint32_t));
      if (table > this->Quota)
      {
        this->Quota = 0;
        return;
      }
      this->Starts.assign(this->Rays, nullptr);
      this->Counts.assign(this->Rays, kUntraced);
      this->Held += table;
    }
    this->Counts[r] = kNoPath;
    const std::size_t n = traced.size();
    ++this->Traced;
    this->Pieces += n;
    if (!ok || n >= kNoPath)
    {
      return;
    }
    if (n > this->ChunkRoom && !this->AddChunk(n, this->Rays - r))
    {
      return;
    }
    PathPiece* destination = this->Chunks.back().get() + (this->ChunkSize - this->ChunkRoom);
    std::copy(traced.begin(), traced.end(), destination);
    this->ChunkRoom -= n;
    this->Starts[r] = destination;
    this->Counts[r] = static_cast<std::uint32_t>(n);
  }

  /// Pieces a ray may trace at most (its path must fit one chunk).
  static constexpr std::size_t kMaxPieces = std::size_t(1) << 16;

private:
  static constexpr std::uint32_t kUntraced = 0xFFFFFFFFu;
  static constexpr std::uint32_t kNoPath = 0xFFFFFFFEu;
  // The smallest chunk: tiles whose rays cross little hold little.
  static constexpr std::size_t kSmallestChunk = 1024;

  // A chunk for the `rays` rays left (this one included), sized by the pieces per ray so far, so
  // that what a tile holds beyond its paths is a small part of them.
  bool AddChunk(std::size_t least, std::size_t rays)
  {
    const double perRay = static_cast<double>(this->Pieces) / static_cast<double>(this->Traced);
    const std::size_t estimate =
      static_cast<std::size_t>(1.125 * perRay * static_cast<double>(rays));
    const std::size_t size = std::max({ least, estimate, kSmallestChunk });
    const std::size_t bytes = size * sizeof(PathPiece);
    if (this->Held + bytes > this->Quota)
    {
      return false;
    }
    std::unique_ptr<PathPiece[]> chunk(new (std::nothrow) PathPiece[size]);
    if (!chunk)
    {
      this->Quota = this->Held; // no more: the system refused
      return false;
    }
    this->Chunks.push_back(std::move(chunk));
    this->ChunkSize = size;
    this->ChunkRoom = size;
    this->Held += bytes;
    return true;
  }

  std::vector<std::unique_ptr<PathPiece[]>> Chunks;
  std::vector<const PathPiece*> Starts; // per ray of the tile, once one is traced
  std::vector<std::uint32_t> Counts;    // pieces, kUntraced or kNoPath
  std::size_t Rays = 0;
  std::size_t ChunkSize = 0;
  std::size_t ChunkRoom = 0;
  std::size_t Traced = 0; // rays traced since Reset
  std::size_t Pieces = 0; // their pieces
  std::size_t Held = 0;
  std::size_t Quota = 0;
};

} // namespace savr

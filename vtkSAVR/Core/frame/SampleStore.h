#pragma once
// One tile's stored samples, slot-major: a ray's samples form rows j (one per base step) of
// `Capacity` frame slots, so the depth of a sample is implied by (j, slot) and blending walks
// memory in order. Rows of all the tile's rays are concatenated; a ray knows its first row.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace savr
{

class SampleStore
{
public:
  /// Sets the number of rows (sum of the rays' samples per frame) and the bytes per code; frees
  /// everything.
  void Reset(std::size_t rows, int bytesPerCode)
  {
    this->Rows = rows;
    this->BytesPerCode = bytesPerCode;
    this->Capacity = 0;
    this->Data.reset();
    this->Bytes = 0;
  }

  /// Makes room for `capacity` slots per row, keeping the first `frames` slots of every row.
  void Grow(int capacity, int frames)
  {
    if (capacity <= this->Capacity || this->Rows == 0)
    {
      this->Capacity = std::max(capacity, this->Capacity);
      return;
    }
    // Not zeroed: every slot is written by its frame before any blend reads it.
    std::unique_ptr<std::uint8_t[]> grown(
      new std::uint8_t[this->Rows * capacity * this->BytesPerCode]);
    const std::size_t keep = static_cast<std::size_t>(frames) * this->BytesPerCode;
    for (std::size_t r = 0; r < this->Rows && keep > 0; ++r)
    {
      std::memcpy(grown.get() + r * capacity * this->BytesPerCode,
        this->Data.get() + r * this->Capacity * this->BytesPerCode, keep);
    }
    this->Data = std::move(grown);
    this->Bytes = this->Rows * capacity * this->BytesPerCode;
    this->Capacity = capacity;
  }

  template <typename Code>
  Code* Row(std::size_t row)
  {
    return reinterpret_cast<Code*>(this->Data.get()) + row * this->Capacity;
  }
  template <typename Code>
  const Code* Row(std::size_t row) const
  {
    return reinterpret_cast<const Code*>(this->Data.get()) + row * this->Capacity;
  }

  int SlotCapacity() const { return this->Capacity; }
  std::size_t MemoryInUse() const { return this->Bytes; }

private:
  std::unique_ptr<std::uint8_t[]> Data;
  std::size_t Bytes = 0;
  std::size_t Rows = 0;
  int BytesPerCode = 1;
  int Capacity = 0;
};

} // namespace savr

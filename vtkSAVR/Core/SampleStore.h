#pragma once
// One tile's stored samples, slot-major: a ray's samples form rows j (one per base step) of
// `Capacity` frame slots, so the depth of a sample is implied by (j, slot) and blending walks
// memory in order. Rows of all the tile's rays are concatenated; a ray knows its first row.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
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
    this->Data.clear();
    this->Data.shrink_to_fit();
  }

  /// Makes room for `capacity` slots per row, keeping the first `frames` slots of every row.
  void Grow(int capacity, int frames)
  {
    if (capacity <= this->Capacity || this->Rows == 0)
    {
      this->Capacity = std::max(capacity, this->Capacity);
      return;
    }
    std::vector<std::uint8_t> grown(this->Rows * capacity * this->BytesPerCode);
    const std::size_t keep = static_cast<std::size_t>(frames) * this->BytesPerCode;
    for (std::size_t r = 0; r < this->Rows && keep > 0; ++r)
    {
      std::memcpy(grown.data() + r * capacity * this->BytesPerCode,
        this->Data.data() + r * this->Capacity * this->BytesPerCode, keep);
    }
    this->Data.swap(grown);
    this->Capacity = capacity;
  }

  template <typename Code>
  Code* Row(std::size_t row)
  {
    return reinterpret_cast<Code*>(this->Data.data()) + row * this->Capacity;
  }
  template <typename Code>
  const Code* Row(std::size_t row) const
  {
    return reinterpret_cast<const Code*>(this->Data.data()) + row * this->Capacity;
  }

  int SlotCapacity() const { return this->Capacity; }
  std::size_t MemoryInUse() const { return this->Data.capacity(); }

private:
  std::vector<std::uint8_t> Data;
  std::size_t Rows = 0;
  int BytesPerCode = 1;
  int Capacity = 0;
};

} // namespace savr

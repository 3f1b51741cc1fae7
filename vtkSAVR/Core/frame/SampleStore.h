#pragma once
// One tile's stored samples, slot-major: a ray's samples form rows j (one per base step) of
// `Capacity` frame slots, so the depth of a sample is implied by (j, slot) and blending walks
// memory in order. Rows of all the tile's rays are concatenated; a ray knows its first row.
// A store is allocated by Grow; until then it has its rows and no memory.

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
    this->Allocated = 0;
  }

  /// Sets the rows, bytes per code and slots per row at once, allocated, keeping the memory it
  /// has where that is enough (for scratch stores laid out again and again); the codes it held
  /// are not kept.
  void Lay(std::size_t rows, int bytesPerCode, int capacity)
  {
    const std::size_t bytes = rows * static_cast<std::size_t>(capacity) * bytesPerCode;
    if (bytes > this->Allocated)
    {
      this->Data.reset(new std::uint8_t[bytes]);
      this->Allocated = bytes;
    }
    this->Rows = rows;
    this->BytesPerCode = bytesPerCode;
    this->Capacity = capacity;
    this->Bytes = bytes;
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
    this->Allocated = this->Bytes;
    this->Capacity = capacity;
  }

  /// Copies the first `slots` slots of rows [fromRow, fromRow + count) of `from` (whose codes
  /// are as wide) to rows toRow on (both allocated, with at least that many slots).
  void CopyRows(
    const SampleStore& from, std::size_t fromRow, std::size_t toRow, std::size_t count, int slots)
  {
    const std::size_t bytes = static_cast<std::size_t>(slots) * this->BytesPerCode;
    const std::size_t toStride = static_cast<std::size_t>(this->Capacity) * this->BytesPerCode;
    const std::size_t fromStride = static_cast<std::size_t>(from.Capacity) * from.BytesPerCode;
    std::uint8_t* to = this->Data.get() + toRow * toStride;
    const std::uint8_t* source = from.Data.get() + fromRow * fromStride;
    if (bytes == toStride && bytes == fromStride)
    {
      std::memcpy(to, source, count * bytes);
      return;
    }
    switch (bytes)
    {
      case 1:
        return CopyStrided<1>(to, toStride, source, fromStride, count);
      case 2:
        return CopyStrided<2>(to, toStride, source, fromStride, count);
      case 4:
        return CopyStrided<4>(to, toStride, source, fromStride, count);
      case 8:
        return CopyStrided<8>(to, toStride, source, fromStride, count);
      default:
        for (std::size_t r = 0; r < count; ++r)
        {
          std::memcpy(to + r * toStride, source + r * fromStride, bytes);
        }
    }
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
  std::size_t RowCount() const { return this->Rows; }
  std::size_t MemoryInUse() const { return this->Bytes; }

private:
  // `count` runs of N bytes (a size the compiler copies inline), at the strides given.
  template <std::size_t N>
  static void CopyStrided(std::uint8_t* to, std::size_t toStride, const std::uint8_t* from,
    std::size_t fromStride, std::size_t count)
  {
    for (std::size_t r = 0; r < count; ++r)
    {
      std::memcpy(to + r * toStride, from + r * fromStride, N);
    }
  }

  std::unique_ptr<std::uint8_t[]> Data;
  std::size_t Bytes = 0;
  std::size_t Allocated = 0;
  std::size_t Rows = 0;
  int BytesPerCode = 1;
  int Capacity = 0;
};

} // namespace savr

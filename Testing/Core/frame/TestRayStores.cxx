// A tile's stores alone: laid out per ray, grown with their frames kept, rows kept from a ray's
// front to its horizon, rays laid out whole again, and the memory all of that costs.

#include "frame/RayStores.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace
{
savr::RayInfo RayOf(int samples, std::size_t firstRow)
{
  savr::RayInfo ray{};
  ray.SamplesPerFrame = samples;
  ray.Horizon = samples;
  ray.Front = 0;
  ray.Back = samples;
  ray.FirstRow = firstRow;
  return ray;
}

// A code that names its ray, row and slot.
std::uint16_t CodeOf(std::size_t ray, int row, int slot)
{
  return static_cast<std::uint16_t>(1000 * ray + 10 * row + slot);
}
} // namespace

TEST(RayStores, LayOutGrowAndCount)
{
  savr::StoreLayout layout;
  layout.CodeBytes = 2;
  layout.Normals = true;
  EXPECT_EQ(layout.BytesPerSample(), 4u);
  layout.Magnitudes = true;
  layout.SecondCodes = true;
  EXPECT_EQ(layout.BytesPerSample(), 7u);
  layout.Magnitudes = false;
  layout.SecondCodes = false;

  savr::RayStores stores;
  stores.Lay(layout, 10, 0);
  EXPECT_EQ(stores.RowCount(), 10u);
  EXPECT_EQ(stores.MemoryInUse(), 0u); // no slots yet
  stores.Grow(1, 0);
  EXPECT_EQ(stores.MemoryInUse(), 10u * 4u);
  for (int row = 0; row < 10; ++row)
  {
    stores.Codes.Row<std::uint16_t>(row)[0] = CodeOf(0, row, 0);
  }
  // Growing keeps the frames taken.
  stores.Grow(4, 1);
  EXPECT_EQ(stores.MemoryInUse(), 10u * 4u * 4u);
  EXPECT_EQ(stores.Codes.SlotCapacity(), 4);
  for (int row = 0; row < 10; ++row)
  {
    EXPECT_EQ(stores.Codes.Row<std::uint16_t>(row)[0], CodeOf(0, row, 0));
  }
  // Stores the layout does not use hold nothing.
  EXPECT_EQ(stores.Magnitudes.RowCount(), 0u);
  stores.Free();
  EXPECT_EQ(stores.MemoryInUse(), 0u);
}

TEST(RayStores, GrowthFourfoldWithinTheLimit)
{
  EXPECT_EQ(savr::RayStores::NextCapacity(0, 64), 4);
  EXPECT_EQ(savr::RayStores::NextCapacity(4, 64), 16);
  EXPECT_EQ(savr::RayStores::NextCapacity(32, 64), 64);
  EXPECT_EQ(savr::RayStores::NextCapacity(0, 2), 2);
  // While growing from 16 to 64 slots, both blocks are held.
  EXPECT_EQ(savr::RayStores::PeakSlots(64), 80u);
  EXPECT_EQ(savr::RayStores::PeakSlots(4), 4u);
  EXPECT_EQ(savr::RayStores::PeakSlots(1), 1u);
}

TEST(RayStores, KeepRowsFromFrontToHorizon)
{
  savr::StoreLayout layout;
  layout.CodeBytes = 2;
  // Two rays' first frame, whole, one slot per row.
  std::vector<savr::RayInfo> rays = { RayOf(8, 0), RayOf(6, 8) };
  savr::RayStores sampled;
  sampled.Lay(layout, 14, 1, true);
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    for (int row = 0; row < rays[r].SamplesPerFrame; ++row)
    {
      sampled.Codes.Row<std::uint16_t>(rays[r].FirstRow + row)[0] = CodeOf(r, row, 0);
    }
  }
  rays[0].Front = 2;
  rays[0].Horizon = 5;
  rays[1].Front = 0;
  rays[1].Horizon = 6;
  savr::RayStores stores;
  stores.KeepRows(rays, sampled, layout, 4);
  // Rows past the largest front (2), then 3 and 6 rows kept.
  EXPECT_EQ(stores.RowCount(), 2u + 3u + 6u);
  EXPECT_EQ(stores.Codes.SlotCapacity(), 4);
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    for (int row = rays[r].Front; row < rays[r].Horizon; ++row)
    {
      EXPECT_EQ(stores.Codes.Row<std::uint16_t>(rays[r].FirstRow + row)[0], CodeOf(r, row, 0))
        << r << " " << row;
    }
  }
}

TEST(RayStores, RelayWholeRaysKeepsTheOthers)
{
  savr::StoreLayout layout;
  layout.CodeBytes = 2;
  layout.Magnitudes = true;
  // Two rays with fronts and horizons, two frames kept of four slots.
  std::vector<savr::RayInfo> rays = { RayOf(8, 0), RayOf(6, 8) };
  rays[0].Front = 3;
  rays[0].Horizon = 6;
  rays[1].Front = 1;
  rays[1].Horizon = 4;
  savr::RayStores first;
  first.Lay(layout, 14, 1, true);
  savr::RayStores stores;
  stores.KeepRows(rays, first, layout, 4); // the second frame's codes are set below
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    for (int row = rays[r].Front; row < rays[r].Horizon; ++row)
    {
      for (int slot = 0; slot < 2; ++slot)
      {
        stores.Codes.Row<std::uint16_t>(rays[r].FirstRow + row)[slot] = CodeOf(r, row, slot);
        stores.Magnitudes.Row<std::uint8_t>(rays[r].FirstRow + row)[slot] =
          static_cast<std::uint8_t>(CodeOf(r, row, slot));
      }
    }
  }
  savr::RayStores scratch;
  stores.RelayWholeRays(rays, { 1, 0 }, scratch, layout, 4);
  // The first ray is whole now; the second keeps its rows and both frames.
  EXPECT_EQ(rays[0].Front, 0);
  EXPECT_EQ(rays[0].Back, 8);
  EXPECT_EQ(rays[1].Front, 1);
  EXPECT_EQ(stores.RowCount(), 1u + 8u + 3u);
  for (int row = rays[1].Front; row < rays[1].Horizon; ++row)
  {
    for (int slot = 0; slot < 2; ++slot)
    {
      EXPECT_EQ(
        stores.Codes.Row<std::uint16_t>(rays[1].FirstRow + row)[slot], CodeOf(1, row, slot));
      EXPECT_EQ(stores.Magnitudes.Row<std::uint8_t>(rays[1].FirstRow + row)[slot],
        static_cast<std::uint8_t>(CodeOf(1, row, slot)));
    }
  }
  // The whole ray's rows lie inside the stores, clear of the other's.
  EXPECT_LE(rays[0].FirstRow + 8, stores.RowCount());
  EXPECT_TRUE(rays[0].FirstRow + 8 <= rays[1].FirstRow + rays[1].Front ||
              rays[1].FirstRow + rays[1].Horizon <= rays[0].FirstRow);
  EXPECT_EQ(scratch.MemoryInUse(), 0u); // the old stores went
}

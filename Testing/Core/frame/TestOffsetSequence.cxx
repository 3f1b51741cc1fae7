#include "frame/OffsetSequence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

TEST(OffsetSequence, RadicalInverseMirrorsBits)
{
  EXPECT_EQ(savr::RadicalInverse2(0), 0.0);
  EXPECT_EQ(savr::RadicalInverse2(1), 0.5);
  EXPECT_EQ(savr::RadicalInverse2(2), 0.25);
  EXPECT_EQ(savr::RadicalInverse2(3), 0.75);
  EXPECT_EQ(savr::RadicalInverse2(6), 0.375);
}

TEST(OffsetSequence, PowerOfTwoPrefixIsRegularGrid)
{
  for (int m = 0; m <= 8; ++m)
  {
    const int frames = 1 << m;
    std::vector<double> offsets;
    for (int k = 0; k < frames; ++k)
    {
      offsets.push_back(savr::RadicalInverse2(k));
    }
    std::sort(offsets.begin(), offsets.end());
    for (int i = 0; i < frames; ++i)
    {
      EXPECT_EQ(offsets[i], static_cast<double>(i) / frames) << "m=" << m;
    }
  }
}

TEST(OffsetSequence, RotatedOrderIsAShiftedAscendingOrderAndGapsTakeTwoValues)
{
  for (int frames : { 1, 2, 3, 5, 7, 8, 13, 32 })
  {
    savr::OffsetSequence sequence(frames);
    for (double rotation : { 0.0, 0.1, 0.5, 0.93 })
    {
      std::vector<double> u(frames);
      std::vector<int> order(frames);
      const int shift = sequence.Rotate(rotation, u.data(), order.data());
      ASSERT_GE(shift, 0);
      ASSERT_LT(shift, frames);
      const double small = savr::OffsetSequence::SmallestGap(frames);
      for (int s = 0; s < frames; ++s)
      {
        // The rotated order is the unrotated one shifted.
        EXPECT_EQ(order[s], sequence.SortedFrame((s + shift) % frames))
          << "frames=" << frames << " rotation=" << rotation;
        EXPECT_GE(u[order[s]], 0.0);
        EXPECT_LT(u[order[s]], 1.0);
        // Gaps, cyclically, are the smallest gap or twice it.
        const double next = s + 1 < frames ? u[order[s + 1]] : u[order[0]] + 1.0;
        const double gap = next - u[order[s]];
        const bool isSmall = std::abs(gap - small) < 1e-12;
        const bool isLarge = std::abs(gap - 2 * small) < 1e-12;
        EXPECT_TRUE(isSmall || isLarge || frames == 1)
          << "frames=" << frames << " rotation=" << rotation << " gap=" << gap;
      }
    }
  }
}

// RotatedOffsets and Order (what the blends use) against the definition: each offset plus the
// rotation, less one where that reaches 1, bit for bit; the order ascending by those offsets.
// The rotations include those that put an offset exactly on 1.
TEST(OffsetSequence, RotatedOffsetsAndOrderAgreeWithTheDefinition)
{
  for (int frames : { 1, 2, 3, 4, 5, 8, 13 })
  {
    savr::OffsetSequence sequence(frames);
    std::vector<double> rotations = { 0.0, 0.1, 0.25, 0.5, 0.93, std::nextafter(1.0, 0.0) };
    for (int k = 0; k < frames; ++k)
    {
      rotations.push_back(1.0 - sequence.Offset(k)); // frame k's offset lands on 1 exactly
    }
    for (double rotation : rotations)
    {
      if (!(rotation < 1.0))
      {
        continue;
      }
      std::vector<double> u(frames);
      std::vector<int> order(frames);
      const int shift = sequence.RotatedOffsets(rotation, u.data());
      ASSERT_GE(shift, 0);
      ASSERT_LT(shift, frames);
      sequence.Order(shift, order.data());
      for (int k = 0; k < frames; ++k)
      {
        const double sum = sequence.Offset(k) + rotation;
        const double expected = sum >= 1.0 ? sum - 1.0 : sum;
        EXPECT_EQ(std::memcmp(&u[k], &expected, sizeof(double)), 0)
          << "frames=" << frames << " rotation=" << rotation << " k=" << k;
      }
      for (int s = 0; s + 1 < frames; ++s)
      {
        EXPECT_LT(u[order[s]], u[order[s + 1]])
          << "frames=" << frames << " rotation=" << rotation << " rank=" << s;
      }
      std::vector<double> u2(frames);
      std::vector<int> order2(frames);
      EXPECT_EQ(sequence.Rotate(rotation, u2.data(), order2.data()), shift);
      EXPECT_EQ(order2, order);
    }
  }
}

TEST(OffsetSequence, PixelRotationIsAFixedFunctionOfThePixel)
{
  double sum = 0.0;
  for (int y = 0; y < 64; ++y)
  {
    for (int x = 0; x < 64; ++x)
    {
      const double r = savr::PixelRotation(x, y);
      EXPECT_GE(r, 0.0);
      EXPECT_LT(r, 1.0);
      EXPECT_EQ(r, savr::PixelRotation(x, y));
      sum += r;
    }
  }
  // Well spread: the mean of 4096 rotations is close to 1/2.
  EXPECT_NEAR(sum / 4096.0, 0.5, 0.02);
}

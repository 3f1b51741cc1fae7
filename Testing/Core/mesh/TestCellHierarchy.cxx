// The cell hierarchy on its own, over random boxes standing in for cells: the first cell a line
// hits and a cell containing a point are the ones a search through every cell finds.

#include "mesh/CellHierarchy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

namespace
{

using savr::unstructured::CellHierarchy;
using savr::unstructured::Line;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Boxes
{
  std::vector<Eigen::Vector3d> Lo;
  std::vector<Eigen::Vector3d> Hi;

  Boxes(int count, unsigned seed)
  {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> centre(-1.0, 1.0);
    std::uniform_real_distribution<double> size(0.02, 0.2);
    for (int c = 0; c < count; ++c)
    {
      const Eigen::Vector3d middle(centre(random), centre(random), centre(random));
      const Eigen::Vector3d half(size(random), size(random), size(random));
      this->Lo.push_back(middle - half);
      this->Hi.push_back(middle + half);
    }
  }

  // Every seventh cell is left out of the hierarchy.
  static bool Left(std::uint32_t cell) { return cell % 7 == 3; }

  CellHierarchy Hierarchy() const
  {
    return CellHierarchy(static_cast<std::uint32_t>(this->Lo.size()), 0.0,
      [this](std::uint32_t cell, Eigen::Vector3d& lo, Eigen::Vector3d& hi)
      {
        lo = this->Lo[cell];
        hi = this->Hi[cell];
        return !Left(cell);
      });
  }

  // The line's parameter interval inside the box of `cell`.
  bool Interval(std::uint32_t cell, const Line& line, double& a, double& b) const
  {
    a = -kInfinity;
    b = kInfinity;
    for (int k = 0; k < 3; ++k)
    {
      if (line.Parallel[k])
      {
        if (line.O[k] < this->Lo[cell][k] || line.O[k] > this->Hi[cell][k])
        {
          return false;
        }
        continue;
      }
      const double ta = (this->Lo[cell][k] - line.O[k]) / line.D[k];
      const double tb = (this->Hi[cell][k] - line.O[k]) / line.D[k];
      a = std::max(a, std::min(ta, tb));
      b = std::min(b, std::max(ta, tb));
    }
    return a <= b;
  }

  bool Contains(std::uint32_t cell, const Eigen::Vector3d& p) const
  {
    return (p.array() >= this->Lo[cell].array()).all() &&
           (p.array() <= this->Hi[cell].array()).all();
  }
};

TEST(CellHierarchy, FirstHitIsTheFirstCellAlongTheLine)
{
  const Boxes boxes(2000, 1);
  const CellHierarchy hierarchy = boxes.Hierarchy();
  std::mt19937 random(2);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  int hits = 0;
  for (int n = 0; n < 400; ++n)
  {
    Eigen::Vector3d direction(u(random), u(random), u(random));
    if (n % 10 == 0)
    {
      direction[n % 3] = 0.0; // parallel to an axis's planes
    }
    const Line line(Eigen::Vector3d(u(random), u(random), u(random)), direction);
    double tMin = n % 2 ? 0.0 : -0.5;
    const double tMax = n % 3 ? kInfinity : 0.8;
    const bool strict = n % 4 == 0;
    if (strict)
    {
      // As the walk asks after leaving a cell: from where the line leaves some cell, which must
      // not be found again.
      for (std::uint32_t c = 0; c < boxes.Lo.size(); ++c)
      {
        double a;
        double b;
        if (!Boxes::Left(c) && boxes.Interval(c, line, a, b) && b > 0.0 && b < 1.0)
        {
          tMin = b;
          break;
        }
      }
    }
    // Every cell: where the first one is entered (at tMin when the line starts inside).
    bool expected = false;
    double expectedEnter = tMax;
    double expectedExit = -kInfinity;
    for (std::uint32_t c = 0; c < boxes.Lo.size(); ++c)
    {
      double a;
      double b;
      if (Boxes::Left(c) || !boxes.Interval(c, line, a, b) || (strict ? !(b > tMin) : b < tMin))
      {
        continue;
      }
      const double enter = std::max(a, tMin);
      if (enter < expectedEnter || (enter == expectedEnter && b > expectedExit))
      {
        expected = true;
        expectedEnter = enter;
        expectedExit = b;
      }
    }
    std::uint32_t cell = CellHierarchy::kNoCell;
    double tEnter = kInfinity;
    const bool found = hierarchy.FirstHit(
      line, tMin, tMax, strict,
      [&](std::uint32_t c, double& a, double& b) { return boxes.Interval(c, line, a, b); }, cell,
      tEnter);
    ASSERT_EQ(found, expected) << "line " << n;
    if (found)
    {
      ++hits;
      EXPECT_EQ(tEnter, expectedEnter) << "line " << n;
      EXPECT_FALSE(Boxes::Left(cell));
      double a;
      double b;
      ASSERT_TRUE(boxes.Interval(cell, line, a, b));
      EXPECT_EQ(std::max(a, tMin), expectedEnter) << "line " << n;
      EXPECT_TRUE(strict ? b > tMin : b >= tMin) << "line " << n;
    }
  }
  EXPECT_GT(hits, 100); // the lines mostly cross the boxes
}

TEST(CellHierarchy, FirstContainingHoldsThePoint)
{
  const Boxes boxes(2000, 3);
  const CellHierarchy hierarchy = boxes.Hierarchy();
  std::mt19937 random(4);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  int inside = 0;
  for (int n = 0; n < 2000; ++n)
  {
    const Eigen::Vector3d p(u(random), u(random), u(random));
    // Only odd cells count, as a caller's own test would decide.
    auto accepts = [&](std::uint32_t c) { return c % 2 == 1 && boxes.Contains(c, p); };
    bool any = false;
    for (std::uint32_t c = 0; c < boxes.Lo.size() && !any; ++c)
    {
      any = !Boxes::Left(c) && accepts(c);
    }
    const std::uint32_t cell = hierarchy.FirstContaining(p, accepts);
    if (!any)
    {
      EXPECT_EQ(cell, CellHierarchy::kNoCell) << "point " << n;
      continue;
    }
    ++inside;
    ASSERT_NE(cell, CellHierarchy::kNoCell) << "point " << n;
    EXPECT_TRUE(accepts(cell));
    EXPECT_FALSE(Boxes::Left(cell));
  }
  EXPECT_GT(inside, 100);
}

TEST(CellHierarchy, EmptyFindsNothing)
{
  const CellHierarchy hierarchy(
    10, 0.0, [](std::uint32_t, Eigen::Vector3d&, Eigen::Vector3d&) { return false; });
  std::uint32_t cell = 0;
  double tEnter = 0.0;
  EXPECT_FALSE(hierarchy.FirstHit(
    Line(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0)), -kInfinity, kInfinity, false,
    [](std::uint32_t, double&, double&) { return true; }, cell, tEnter));
  EXPECT_EQ(hierarchy.FirstContaining(Eigen::Vector3d::Zero(), [](std::uint32_t) { return true; }),
    CellHierarchy::kNoCell);
}

} // namespace

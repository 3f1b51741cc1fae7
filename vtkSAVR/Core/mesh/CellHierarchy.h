#pragma once
// A bounding volume hierarchy over the cells of an unstructured mesh: the first cell a line
// hits after a parameter, and a cell containing a point. What "hits" and "contains" mean is the
// caller's (the mesh's faces decide); the hierarchy only orders the cells by their boxes.

#include "mesh/MeshLine.h"

#include <Eigen/Core>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace savr
{
namespace unstructured
{

class CellHierarchy
{
public:
  static constexpr std::uint32_t kNoCell = 0xffffffffu;

  CellHierarchy() = default;

  // Over `cells` cells, each with the box that `bounds(cell, lo, hi)` gives, grown by `grow`
  // (a cell's interval along a ray, from its face planes, may stray out of its box by round-off);
  // cells for which `bounds` returns false are left out. Split at the median centre along the
  // widest axis.
  template <class Bounds>
  CellHierarchy(std::uint32_t cells, double grow, Bounds&& bounds)
  {
    std::vector<Item> items;
    items.reserve(cells);
    for (std::uint32_t c = 0; c < cells; ++c)
    {
      Eigen::Vector3d lo;
      Eigen::Vector3d hi;
      if (!bounds(c, lo, hi))
      {
        continue;
      }
      Item item;
      for (int a = 0; a < 3; ++a)
      {
        item.Lo[a] = RoundDown(lo[a] - grow);
        item.Hi[a] = RoundUp(hi[a] + grow);
        item.Centre[a] = static_cast<float>(0.5 * (lo[a] + hi[a]));
      }
      item.Cell = c;
      items.push_back(item);
    }
    this->Build(items);
  }

  // The first cell whose interval along the line, as `interval(cell, a, b)` gives it (false for
  // none), holds tMin or comes after it, up to tMax, and where the line enters it. With
  // `strict`, only cells that the line leaves after tMin (not at it) count.
  template <class Interval>
  bool FirstHit(const Line& line, double tMin, double tMax, bool strict, Interval&& interval,
    std::uint32_t& cell, double& tEnter) const
  {
    double tNear;
    if (this->Nodes.empty() || !HitBox(this->Nodes[0], line, tMin, tMax, tNear))
    {
      return false;
    }
    struct Entry
    {
      std::uint32_t Node;
      double T;
    };
    Entry stack[kStackSize];
    int top = 0;
    stack[top++] = { 0, tNear };
    bool found = false;
    double best = tMax;
    double bestExit = -std::numeric_limits<double>::infinity();
    while (top > 0)
    {
      const Entry entry = stack[--top];
      if (entry.T > best || (found && entry.T == best))
      {
        continue;
      }
      const Node& node = this->Nodes[entry.Node];
      if (node.Count > 0)
      {
        for (std::uint32_t i = node.Index; i < node.Index + node.Count; ++i)
        {
          const std::uint32_t c = this->LeafCells[i];
          double a;
          double b;
          if (!interval(c, a, b) || (strict ? !(b > tMin) : !(b >= tMin)))
          {
            continue;
          }
          const double enter = std::max(a, tMin);
          if (enter < best || (enter == best && b > bestExit))
          {
            best = enter;
            bestExit = b;
            cell = c;
            found = true;
          }
        }
        continue;
      }
      double t[2];
      const bool hit[2] = { HitBox(this->Nodes[node.Index], line, tMin, best, t[0]),
        HitBox(this->Nodes[node.Index + 1], line, tMin, best, t[1]) };
      const int nearer = hit[0] && hit[1] ? (t[1] < t[0] ? 1 : 0) : (hit[0] ? 0 : 1);
      for (int k : { 1 - nearer, nearer }) // the nearer child on top
      {
        if (hit[k] && top < kStackSize)
        {
          stack[top++] = { node.Index + static_cast<std::uint32_t>(k), t[k] };
        }
      }
    }
    tEnter = best;
    return found;
  }

  // The first cell, in the hierarchy's order, whose box holds p and for which `contains(cell)`
  // is true, or kNoCell.
  template <class Contains>
  std::uint32_t FirstContaining(const Eigen::Vector3d& p, Contains&& contains) const
  {
    if (this->Nodes.empty())
    {
      return kNoCell;
    }
    std::uint32_t stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      const Node& node = this->Nodes[stack[--top]];
      if (p[0] < node.Lo[0] || p[0] > node.Hi[0] || p[1] < node.Lo[1] || p[1] > node.Hi[1] ||
          p[2] < node.Lo[2] || p[2] > node.Hi[2])
      {
        continue;
      }
      if (node.Count > 0)
      {
        for (std::uint32_t i = node.Index; i < node.Index + node.Count; ++i)
        {
          const std::uint32_t cell = this->LeafCells[i];
          if (contains(cell))
          {
            return cell;
          }
        }
        continue;
      }
      if (top + 2 <= kStackSize)
      {
        stack[top++] = node.Index;
        stack[top++] = node.Index + 1;
      }
    }
    return kNoCell;
  }

  // Whether `past(cell)` holds for some cell whose box reaches beyond the plane n.x = d by more
  // than `slack`, looking at most at `budget` nodes: true also when the budget runs out first.
  template <class Past>
  bool AnyPast(const double n[3], double d, double slack, int budget, Past&& past) const
  {
    if (this->Nodes.empty())
    {
      return false;
    }
    std::uint32_t stack[kStackSize];
    int top = 0;
    stack[top++] = 0;
    while (top > 0)
    {
      if (--budget < 0)
      {
        return true;
      }
      const Node& node = this->Nodes[stack[--top]];
      double reach = -d;
      for (int a = 0; a < 3; ++a)
      {
        reach += n[a] * (n[a] > 0.0 ? node.Hi[a] : node.Lo[a]);
      }
      if (!(reach > slack))
      {
        continue;
      }
      if (node.Count > 0)
      {
        for (std::uint32_t i = node.Index; i < node.Index + node.Count; ++i)
        {
          if (past(this->LeafCells[i]))
          {
            return true;
          }
        }
        continue;
      }
      if (top + 2 > kStackSize)
      {
        return true;
      }
      stack[top++] = node.Index;
      stack[top++] = node.Index + 1;
    }
    return false;
  }

private:
  static constexpr int kLeafSize = 4;
  static constexpr int kStackSize = 96; // the median splits keep the depth near log2(cells)

  // A leaf when Count > 0 (cells LeafCells[Index, Index + Count)), else the parent of nodes
  // Index and Index + 1.
  struct Node
  {
    float Lo[3];
    float Hi[3];
    std::uint32_t Index;
    std::uint32_t Count;
  };

  struct Item
  {
    float Lo[3];
    float Hi[3];
    float Centre[3];
    std::uint32_t Cell;
  };

  static float RoundDown(double v);
  static float RoundUp(double v);
  void Build(std::vector<Item>& items);

  // Parameter interval [tNear, ...] of the line inside a node's box, within [tLo, tHi].
  static bool HitBox(const Node& node, const Line& line, double tLo, double tHi, double& tNear)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (line.Parallel[a])
      {
        if (line.O[a] < node.Lo[a] || line.O[a] > node.Hi[a])
        {
          return false;
        }
        continue;
      }
      double ta = (node.Lo[a] - line.O[a]) * line.Inverse[a];
      double tb = (node.Hi[a] - line.O[a]) * line.Inverse[a];
      if (ta > tb)
      {
        std::swap(ta, tb);
      }
      tLo = std::max(tLo, ta);
      tHi = std::min(tHi, tb);
    }
    tNear = tLo;
    return tLo <= tHi;
  }

  std::vector<Node> Nodes;
  std::vector<std::uint32_t> LeafCells;
};

} // namespace unstructured
} // namespace savr

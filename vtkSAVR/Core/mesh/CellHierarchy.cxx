#include "mesh/CellHierarchy.h"

#include <cmath>

namespace savr
{
namespace unstructured
{

float CellHierarchy::RoundDown(double v)
{
  float f = static_cast<float>(v);
  return static_cast<double>(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                    : f;
}

float CellHierarchy::RoundUp(double v)
{
  float f = static_cast<float>(v);
  return static_cast<double>(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

void CellHierarchy::Build(std::vector<Item>& items)
{
  if (items.empty())
  {
    return;
  }
  this->Nodes.reserve(2 * (items.size() / 2 + 1));
  this->Nodes.emplace_back();
  struct Task
  {
    std::uint32_t Node;
    std::size_t Begin;
    std::size_t End;
  };
  std::vector<Task> tasks = { { 0, 0, items.size() } };
  while (!tasks.empty())
  {
    const Task task = tasks.back();
    tasks.pop_back();
    float lo[3] = { items[task.Begin].Lo[0], items[task.Begin].Lo[1], items[task.Begin].Lo[2] };
    float hi[3] = { items[task.Begin].Hi[0], items[task.Begin].Hi[1], items[task.Begin].Hi[2] };
    float cLo[3] = { items[task.Begin].Centre[0], items[task.Begin].Centre[1],
      items[task.Begin].Centre[2] };
    float cHi[3] = { cLo[0], cLo[1], cLo[2] };
    for (std::size_t i = task.Begin; i < task.End; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], items[i].Lo[a]);
        hi[a] = std::max(hi[a], items[i].Hi[a]);
        cLo[a] = std::min(cLo[a], items[i].Centre[a]);
        cHi[a] = std::max(cHi[a], items[i].Centre[a]);
      }
    }
    Node& node = this->Nodes[task.Node];
    for (int a = 0; a < 3; ++a)
    {
      node.Lo[a] = lo[a];
      node.Hi[a] = hi[a];
    }
    const std::size_t count = task.End - task.Begin;
    if (count <= static_cast<std::size_t>(kLeafSize))
    {
      node.Index = static_cast<std::uint32_t>(task.Begin);
      node.Count = static_cast<std::uint32_t>(count);
      continue;
    }
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (cHi[a] - cLo[a] > cHi[axis] - cLo[axis])
      {
        axis = a;
      }
    }
    const std::size_t middle = task.Begin + count / 2;
    std::nth_element(items.begin() + task.Begin, items.begin() + middle, items.begin() + task.End,
      [axis](const Item& a, const Item& b) { return a.Centre[axis] < b.Centre[axis]; });
    const auto child = static_cast<std::uint32_t>(this->Nodes.size());
    node.Index = child;
    node.Count = 0;
    this->Nodes.emplace_back();
    this->Nodes.emplace_back();
    tasks.push_back({ child, task.Begin, middle });
    tasks.push_back({ child + 1, middle, task.End });
  }
  this->LeafCells.resize(items.size());
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    this->LeafCells[i] = items[i].Cell;
  }
}

} // namespace unstructured
} // namespace savr

#include "image/BlockWalk.h"

namespace savr
{
namespace detail
{

void ChessboardSkipDistances(const BlockLattice& lattice, std::vector<std::uint8_t>& skip)
{
  const long long nx = lattice.Blocks[0];
  const long long ny = lattice.Blocks[1];
  const long long nz = lattice.Blocks[2];
  const long long n = nx * ny * nz;
  if (static_cast<long long>(skip.size()) != n)
  {
    return;
  }
  for (std::uint8_t& f : skip)
  {
    f = f ? 255 : 0;
  }
  const auto sweep = [&](int direction)
  {
    for (long long s = 0; s < n; ++s)
    {
      const long long b = direction > 0 ? s : n - 1 - s;
      if (skip[b] <= 1)
      {
        continue;
      }
      const long long x = b % nx;
      const long long y = (b / nx) % ny;
      const long long z = b / (nx * ny);
      int best = skip[b];
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
          {
            // The neighbours this sweep has already passed.
            const int order = dx + 3 * (dy + 3 * dz);
            if (order * direction >= 0 || x + dx < 0 || x + dx >= nx || y + dy < 0 ||
                y + dy >= ny || z + dz < 0 || z + dz >= nz)
            {
              continue;
            }
            best = std::min(best, skip[b + dx + nx * (dy + ny * dz)] + 1);
          }
      skip[b] = static_cast<std::uint8_t>(std::min(best, 255));
    }
  };
  sweep(+1);
  sweep(-1);
}

} // namespace detail
} // namespace savr

#include "image/GridGradients.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace savr
{
namespace detail
{

void GradientGrid::ForSlices(
  long long slices, const std::function<void(long long, long long)>& body)
{
  // Isolated: a sampler may compute its gradients inside a frame's parallel loop (on the first
  // gradient asked for), and a thread waiting here must not take up another tile of that loop,
  // which could wait for these gradients in turn.
  tbb::this_task_arena::isolate(
    [&]()
    {
      tbb::parallel_for(tbb::blocked_range<long long>(0, slices, 1),
        [&](const tbb::blocked_range<long long>& range) { body(range.begin(), range.end()); });
    });
}

void GradientGrid::SetToWorld(const Eigen::Matrix3d& indexToWorld, double scale)
{
  const Eigen::Matrix3d toWorld = indexToWorld * (0.5 / scale);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      this->ToWorld[3 * r + c] = static_cast<float>(toWorld(r, c));
    }
  }
}

void GradientGrid::FinishBlocks(const GradientShape& shape)
{
  const long long size = 1LL << shape.BlockShift;
  const long long bx = shape.Blocks[0];
  const long long by = shape.Blocks[1];
  const long long bz = shape.Blocks[2];
  this->ZeroBlocks.assign(static_cast<std::size_t>(bx * by * bz), 0);
  const std::int16_t* codes = this->Codes.data();
  const std::uint32_t* words = this->Packed.data();
  const bool packed = !this->Packed.empty();
  ForSlices(bz,
    [&](long long z0, long long z1)
    {
      for (long long z = z0; z < z1; ++z)
        for (long long y = 0; y < by; ++y)
          for (long long x = 0; x < bx; ++x)
          {
            // The block's cells' corners: its points up to the next block's first.
            const long long lo[3] = { x * size, y * size, z * size };
            long long hi[3];
            for (int a = 0; a < 3; ++a)
            {
              hi[a] = std::min(lo[a] + size, shape.Dims[a] - 1);
            }
            bool zero = true;
            for (long long k = lo[2]; k <= hi[2] && zero; ++k)
              for (long long j = lo[1]; j <= hi[1] && zero; ++j)
              {
                const long long first = lo[0] + this->Step[1] * j + this->Step[2] * k;
                const long long n = hi[0] - lo[0] + 1;
                for (long long i = 0; i < n; ++i)
                {
                  zero = zero &&
                         (packed ? words[first + i] == 0u
                                 : codes[3 * (first + i)] == 0 && codes[3 * (first + i) + 1] == 0 &&
                                     codes[3 * (first + i) + 2] == 0);
                }
              }
            this->ZeroBlocks[static_cast<std::size_t>(x + bx * (y + by * z))] = zero ? 1 : 0;
          }
    });
}

} // namespace detail
} // namespace savr

#include "reference/ReferenceIntegrator.h"

#include "blend/Composite.h"
#include "blend/TransferFunctionTable.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace savr
{

std::vector<float> ReferenceImage(const View& view, const Sampler& sampler,
  const ReferenceTransferFunction& tf, double step, int minimumSteps)
{
  std::vector<float> image(static_cast<std::size_t>(view.Width) * view.Height * 4, 0.0f);
  // As the engine's tables: a unit distance that is not positive and finite counts as 1.
  const double unit =
    tf.UnitDistance > 0.0 && std::isfinite(tf.UnitDistance) ? tf.UnitDistance : 1.0;
  const double maxDepth = TransferFunctionTable::kMaxOpticalDepth / unit;
  tbb::parallel_for(tbb::blocked_range<int>(0, view.Height),
    [&](const tbb::blocked_range<int>& rows)
    {
      constexpr int kBatch = 4096;
      std::vector<float> values(kBatch);
      for (int y = rows.begin(); y != rows.end(); ++y)
      {
        for (int x = 0; x < view.Width; ++x)
        {
          Ray ray;
          double t0 = 0.0;
          double t1 = 0.0;
          if (!view.Segment(sampler, x, y, ray, t0, t1))
          {
            continue;
          }
          const double length = t1 - t0;
          const long long steps =
            std::max<long long>(minimumSteps, static_cast<long long>(std::ceil(length / step)));
          const double h = length / static_cast<double>(steps);
          double T = 1.0;
          Eigen::Array3d C = Eigen::Array3d::Zero();
          for (long long i0 = 0; i0 < steps && T > 1e-15; i0 += kBatch)
          {
            const int count = static_cast<int>(std::min<long long>(kBatch, steps - i0));
            sampler.SampleRay(
              ray, t0 + (static_cast<double>(i0) + 0.5) * h, h, count, values.data());
            for (int i = 0; i < count; ++i)
            {
              const double v = values[i];
              if (!std::isfinite(v))
              {
                continue;
              }
              const double given = tf.Opacity(v);
              const double alpha = std::isfinite(given) ? std::min(std::max(given, 0.0), 1.0) : 0.0;
              const double sigma =
                std::min(alpha < 1.0 ? -std::log1p(-alpha) / unit : maxDepth, maxDepth);
              const double a = composite::IntervalOpacity(sigma, h);
              if (a > 0.0)
              {
                composite::Over(C, T, a, tf.Color(v).array());
              }
            }
          }
          const Pixel p = composite::FrontToBack(C, T);
          std::copy(
            p.data(), p.data() + 4, &image[4 * (static_cast<std::size_t>(y) * view.Width + x)]);
        }
      }
    });
  return image;
}

} // namespace savr

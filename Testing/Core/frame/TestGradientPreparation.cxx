// Gradients that a sampler builds on first use (the unstructured sampler's point gradients): the
// frame loop has them built before its tiles start, and they are the same bits whoever builds
// them, with however many threads.
#include "frame/FrameLoop.h"
#include "blend/ShadingTable.h"
#include "mesh/UnstructuredTestMeshes.h"

#include <gtest/gtest.h>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <thread>

using namespace savr_test;

namespace
{
// Mixed cells of every kind, jittered, under a field whose gradient varies: about 20,000 cells,
// more than the sampler builds point gradients for at a time.
Lattice MixedLattice()
{
  Lattice lattice({ 22, 20, 18 }, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1),
    Split::Mixed, nullptr, 0.2);
  lattice.M.SetPointValues([](const Eigen::Vector3d& p)
    { return std::sin(3 * p.x()) * std::cos(2 * p.y()) + p.z() * p.z(); });
  return lattice;
}

// Gradients at points spread over the mesh, asked for from the tasks of a loop in an arena of
// `threads` threads, after PrepareGradients in that arena when `prepare`.
std::vector<float> GradientsFromWorkers(const savr::Sampler& sampler, int threads, bool prepare)
{
  const int points = 20000;
  std::vector<float> gradients(3 * static_cast<std::size_t>(points));
  tbb::task_arena arena(threads);
  arena.execute(
    [&]
    {
      if (prepare)
      {
        sampler.PrepareGradients();
      }
      tbb::parallel_for(tbb::blocked_range<int>(0, points, 16),
        [&](const tbb::blocked_range<int>& range)
        {
          for (int i = range.begin(); i < range.end(); ++i)
          {
            const Eigen::Vector3d p(std::sin(1.3 * i), std::cos(0.7 * i), std::sin(2.9 * i + 1));
            const savr::Ray ray = MakeRay(p - Eigen::Vector3d(0.3, 0.2, 0.1), p);
            sampler.GradientAt(ray, std::sqrt(0.14), &gradients[3 * static_cast<std::size_t>(i)]);
          }
        });
    });
  return gradients;
}

// Records when gradients are prepared and asked for.
class RecordingSampler final : public ForwardingSampler
{
public:
  using ForwardingSampler::ForwardingSampler;
  void PrepareGradients() const override
  {
    this->Preparations.push_back(std::this_thread::get_id());
    ForwardingSampler::PrepareGradients();
    this->Prepared = true;
  }
  void GradientAt(const savr::Ray& ray, double t, float gradient[3]) const override
  {
    this->Record();
    ForwardingSampler::GradientAt(ray, t, gradient);
  }
  void SampleRayGradients(const savr::Ray& ray, double t0, double dt, int count, float* out,
    float* gradients) const override
  {
    this->Record();
    ForwardingSampler::SampleRayGradients(ray, t0, dt, count, out, gradients);
  }

  // Threads that called PrepareGradients, in order (it is called outside parallel loops).
  mutable std::vector<std::thread::id> Preparations;
  // Gradient requests before and after the first PrepareGradients.
  mutable std::atomic<int> Early{ 0 };
  mutable std::atomic<int> Late{ 0 };

private:
  void Record() const { ++(this->Prepared ? this->Late : this->Early); }

  mutable std::atomic<bool> Prepared{ false };
};
} // namespace

// Built lazily by workers racing for them, or prepared first, with 1, 2 or 7 threads: the same
// bits. (Built lazily on a worker, the building runs parallel code inside call_once; without
// isolation that worker could take another task that waits for the same call_once: a hang.)
TEST(GradientPreparation, PointGradientsDoNotDependOnTheThreadCount)
{
  // Seven threads even on a machine with fewer cores.
  const tbb::global_control allowThreads(tbb::global_control::max_allowed_parallelism, 7);
  const Lattice lattice = MixedLattice();
  ASSERT_GT(lattice.M.Cells(), 16384u);
  const auto serial = GradientsFromWorkers(*lattice.M.Sampler(), 1, false);
  int nonZero = 0;
  for (float g : serial)
  {
    ASSERT_TRUE(std::isfinite(g));
    nonZero += g != 0.0f;
  }
  EXPECT_GT(nonZero, 10000);
  for (int threads : { 1, 2, 7 })
  {
    for (bool prepare : { false, true })
    {
      SCOPED_TRACE(std::to_string(threads) + " threads, " + (prepare ? "prepared" : "lazy"));
      EXPECT_TRUE(SameBits(serial, GradientsFromWorkers(*lattice.M.Sampler(), threads, prepare)));
    }
  }
}

// Shaded frames, single passes and gradient opacity: the frame loop prepares the gradients on
// its own thread before any tile asks for one; frames without gradients do not prepare them.
TEST(GradientPreparation, FramesPrepareGradientsBeforeTheirTiles)
{
  const Lattice lattice = MixedLattice();
  const auto mesh = lattice.M.Sampler();
  const savr::View view = PerspectiveView(Eigen::Vector3d(0.8, -1.2, 3.5), Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(0, 1, 0), 40.0, 48, 48, 0.5, 10.0);
  savr::ShadingTable shading;
  shading.Build({ savr::Light() }, Eigen::Vector3d::UnitZ(), 0.3, 0.7, 0.2, 10.0);
  const std::thread::id caller = std::this_thread::get_id();
  struct Case
  {
    const char* Name;
    bool Shade;
    bool Magnitudes;
    bool SinglePass;
  };
  for (const Case& c :
    { Case{ "shaded frame", true, false, false }, Case{ "shaded single pass", true, false, true },
      Case{ "gradient opacity", false, true, false }, Case{ "no gradients", false, false, false } })
  {
    SCOPED_TRACE(c.Name);
    const auto recording = std::make_shared<RecordingSampler>(mesh);
    savr::FrameSettings settings;
    settings.SampleDistance = 0.05;
    settings.MaximumFrames = 2;
    settings.Threads = 2;
    settings.Shade = c.Shade;
    settings.GradientMagnitudes = c.Magnitudes;
    savr::FrameLoop loop;
    loop.Reset(view, recording, settings);
    loop.SetShading(&shading);
    const auto table = MakeTable(
      loop.Encoding(), [](double) { return Eigen::Vector3d(0.8, 0.5, 0.3); },
      [](double v) { return std::min(1.0, std::max(0.0, 0.5 * (v + 1.0))); }, 0.3);
    for (int k = 0; k < 2; ++k)
    {
      if (c.SinglePass)
      {
        loop.RenderSinglePass(table, savr::BlendMode::Composite, 0.05, 0.0);
      }
      else
      {
        loop.AccumulateFrame(table, savr::BlendMode::Composite);
      }
    }
    EXPECT_GT(MaxValue(loop.Image()), 0.1);
    EXPECT_EQ(recording->Early.load(), 0);
    if (!c.Shade && !c.Magnitudes)
    {
      EXPECT_TRUE(recording->Preparations.empty());
      EXPECT_EQ(recording->Late.load(), 0);
      continue;
    }
    EXPECT_GT(recording->Late.load(), 0);
    ASSERT_EQ(recording->Preparations.size(), 2u) << "once per frame";
    EXPECT_EQ(recording->Preparations[0], caller);
    EXPECT_EQ(recording->Preparations[1], caller);
  }
}

// Per-voxel gradients that do not fit the memory budget give way to gradients computed where
// they are asked for: the same bits (8-bit data, whose codes are exact differences, and 16-bit
// data, whose codes are scaled and rounded), linear and nearest, vectorized or not, and the
// budget that could not hold the kept ones now draws the image.
TEST(GradientPreparation, GradientsOnDemandWhenTheKeptOnesDoNotFit)
{
  // A grid whose kept gradients outweigh the view's samples.
  constexpr int n = 64;
  std::vector<std::uint8_t> bytes(n * n * n);
  std::vector<std::uint16_t> shorts(n * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double x = (i - 31.5) / 16.0, y = (j - 29.0) / 14.0, z = (k - 33.0) / 17.0;
        const double v = std::exp(-(x * x + y * y + z * z)) + 0.1 * std::sin(i * 0.7 + j * 0.3);
        bytes[i + n * (j + n * k)] = static_cast<std::uint8_t>(std::lround(200.0 * v + 20.0));
        shorts[i + n * (j + n * k)] = static_cast<std::uint16_t>(std::lround(40000.0 * v + 900.0));
      }
  const savr::View view = PerspectiveView(Eigen::Vector3d(110, -60, 140),
    Eigen::Vector3d(32, 32, 32), Eigen::Vector3d(0, 0, 1), 35.0, 40, 36, 1.0, 600.0);
  savr::Light light;
  light.Direction = Eigen::Vector3d(0.3, -0.4, 0.8).normalized();
  savr::ShadingTable shading;
  shading.Build({ light }, Eigen::Vector3d(0.6, -0.3, 0.7).normalized(), 0.2, 0.7, 0.3, 12.0);
  for (const bool eight : { true, false })
    for (const bool linear : { true, false })
      for (const bool vectorize : { true, false })
      {
        SCOPED_TRACE(std::string(eight ? "8-bit" : "16-bit") + (linear ? ", linear" : ", nearest") +
                     (vectorize ? ", vectorized" : ""));
        savr::GridDescription grid;
        grid.Data = eight ? static_cast<const void*>(bytes.data()) : shorts.data();
        grid.Type = eight ? savr::ScalarType::UInt8 : savr::ScalarType::UInt16;
        grid.Dims = { n, n, n };
        grid.Interpolation = linear ? savr::Interpolation::Linear : savr::Interpolation::Nearest;
        grid.Vectorize = vectorize;
        std::string error;
        std::size_t needed = 0; // what the roomy run held at its end
        const auto image = [&](std::size_t budget, bool& drawn, std::size_t& gradientBytes)
        {
          const auto sampler = savr::MakeGridSampler(grid, error);
          EXPECT_TRUE(sampler) << error;
          savr::FrameSettings settings;
          settings.SampleDistance = 1.1;
          settings.MaximumFrames = 3;
          settings.Shade = true;
          settings.MemoryBudget = budget;
          savr::FrameLoop loop;
          loop.Reset(view, sampler, settings);
          drawn = !loop.OverBudget();
          gradientBytes = sampler->GradientBytes();
          if (!drawn)
          {
            return std::vector<float>();
          }
          loop.SetShading(&shading);
          const auto table = MakeTable(
            loop.Encoding(), [](double) { return Eigen::Vector3d(0.9, 0.6, 0.4); },
            [&](double v) { return std::min(1.0, std::max(0.0, (v - (eight ? 60 : 9000)) /
                                                                   (eight ? 150.0 : 30000.0))); },
            1.0);
          for (int k = 0; k < 3; ++k)
          {
            loop.AccumulateFrame(table, savr::BlendMode::Composite);
          }
          EXPECT_EQ(loop.FrameLimit(), 3);
          std::vector<float> result = loop.Image();
          loop.RenderSinglePass(table, savr::BlendMode::Composite, 1.1, 0.0);
          result.insert(result.end(), loop.Image().begin(), loop.Image().end());
          needed = std::max(needed, loop.MemoryInUse() + loop.FixedBytes());
          return result;
        };
        bool drawn = false;
        std::size_t kept = 0;
        const std::vector<float> roomy = image(std::size_t(1) << 28, drawn, kept);
        ASSERT_TRUE(drawn);
        ASSERT_GT(kept, std::size_t(n * n * n)) << "the roomy budget keeps per-voxel gradients";
        EXPECT_GT(MaxValue(roomy), 0.1);
        // A budget that holds the view and every frame's samples but not the kept gradients.
        std::size_t onDemand = 1;
        const std::vector<float> tight = image(needed - kept / 2, drawn, onDemand);
        ASSERT_TRUE(drawn) << "drawn without kept gradients";
        EXPECT_EQ(onDemand, std::size_t(0));
        EXPECT_TRUE(SameBits(roomy, tight));
      }
}

// Gradients that a sampler builds on first use (the unstructured sampler's point gradients): the
// frame loop has them built before its tiles start, and they are the same bits whoever builds
// them, with however many threads.
#include "frame/FrameLoop.h"
#include "blend/ShadingTable.h"
#include "UnstructuredTestMeshes.h"

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

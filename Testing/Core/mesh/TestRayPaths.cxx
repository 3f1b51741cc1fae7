// Ray paths (Sampler::TracePath): what a ray crosses in an unstructured mesh, recorded by the
// first frame so that later frames read it instead of walking from cell to cell. Samples along a
// path must equal the walk's up to float rounding, frames must read paths and not walk, the paths
// must stay within the memory budget, and images must not depend on the thread count.

#include "TestHelpers.h"
#include "mesh/UnstructuredTestMeshes.h"

#include "frame/TilePaths.h"
#include "mesh/UnstructuredDescription.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

using namespace savr_test;

namespace
{

double Wave(const Eigen::Vector3d& p)
{
  return std::sin(3 * p.x()) * std::cos(2 * p.y()) + p.z() * p.z();
}

// Every cell kind, cells missing (holes and concavities), points moved.
Lattice HoledLattice(Split split)
{
  Lattice lattice(
    { 7, 6, 5 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2), split,
    [](int i, int j, int k) { return (i * 7 + j * 3 + k) % 11 != 0; }, 0.2);
  lattice.M.SetPointValues(Wave);
  return lattice;
}

// Samples [t0, t0 + count dt) of `ray` along its path and by the walk, for the `frames` offsets
// of a lattice of spacing dt / frames; counts the samples that differ by more than rounding
// (values) or at all (NaN or not).
void CompareAlongPath(const savr::Sampler& sampler, const savr::Ray& ray, double t0, double dt,
  int count, int frames, int& compared, int& failures)
{
  std::vector<savr::PathPiece> path;
  ASSERT_TRUE(sampler.TracePath(ray, t0, t0 + count * dt, dt / frames, std::size_t(1) << 16, path));
  std::vector<float> along(count);
  std::vector<float> walked(count);
  for (int k = 0; k < frames; ++k)
  {
    const double start = t0 + k * dt / frames;
    sampler.SampleAlongPath(ray, path.data(), path.size(), t0, start, dt, count, along.data());
    sampler.SampleRay(ray, start, dt, count, walked.data());
    for (int i = 0; i < count; ++i)
    {
      const float a = along[i];
      const float w = walked[i];
      if (std::isnan(a) != std::isnan(w) ||
          (!std::isnan(w) && !(std::abs(a - w) <= 2e-5f * (1.0f + std::abs(w)))))
      {
        if (failures++ < 5)
        {
          ADD_FAILURE() << "sample " << i << " of offset " << k << ": " << a << " along the path, "
                        << w << " walked";
        }
      }
      compared += !std::isnan(w);
    }
  }
}

} // namespace

TEST(RayPaths, SamplesAlongPathsEqualTheWalk)
{
  for (Split split : kAllSplits)
  {
    for (bool cellData : { false, true })
    {
      SCOPED_TRACE(std::string(Name(split)) + (cellData ? ", cell data" : ", point data"));
      Lattice lattice = HoledLattice(split);
      if (cellData)
      {
        lattice.M.Values.assign(lattice.M.Cells(), 0.0f);
        for (std::size_t c = 0; c < lattice.M.Cells(); ++c)
        {
          lattice.M.Values[c] = static_cast<float>(std::sin(0.37 * c));
        }
      }
      auto sampler = lattice.M.Sampler(cellData);
      ASSERT_TRUE(sampler);
      ASSERT_TRUE(sampler->TracesPaths());
      double length;
      const auto rays = RandomRays(lattice.Lo, lattice.Hi, 300, 17, length);
      int compared = 0;
      int failures = 0;
      for (const savr::Ray& ray : rays)
      {
        CompareAlongPath(*sampler, ray, 0.0, length / 97, 97, 4, compared, failures);
      }
      EXPECT_EQ(failures, 0);
      EXPECT_GT(compared, 3000) << "the rays must cross the mesh";
    }
  }
}

// A lattice of samples coarser than the cells leaves out the pieces that hold none of them; a
// path that would need more pieces than allowed is refused and leaves the path as it was.
TEST(RayPaths, PiecesWithoutSamplesAreLeftOutAndLongPathsRefused)
{
  Lattice lattice({ 12, 12, 12 }, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 2),
    Split::Tetrahedra6, nullptr, 0.1);
  lattice.M.SetPointValues(Wave);
  auto sampler = lattice.M.Sampler();
  ASSERT_TRUE(sampler);
  const savr::Ray ray = MakeRay(Eigen::Vector3d(-1, 0.31, 0.27), Eigen::Vector3d(3, 1.73, 1.81));
  double t0;
  double t1;
  ASSERT_TRUE(sampler->Clip(ray, t0, t1));
  std::vector<savr::PathPiece> every;
  std::vector<savr::PathPiece> coarse;
  ASSERT_TRUE(sampler->TracePath(ray, t0, t1, 0.0, 100000, every));
  ASSERT_TRUE(sampler->TracePath(ray, t0, t1, 0.25, 100000, coarse));
  EXPECT_GT(every.size(), 30u) << "the ray crosses many tetrahedra";
  EXPECT_LT(coarse.size(), every.size() / 2);
  std::vector<savr::PathPiece> refused = { savr::PathPiece{ 1.0f, 2.0f, 3.0f } };
  EXPECT_FALSE(sampler->TracePath(ray, t0, t1, 0.0, every.size() - 1, refused));
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0].End, 1.0f);
  // Samples on the coarse lattice read the same from either path.
  int compared = 0;
  int failures = 0;
  CompareAlongPath(
    *sampler, ray, t0, 0.25, static_cast<int>((t1 - t0) / 0.25), 1, compared, failures);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(compared, 4);
}

namespace
{

// Counts the calls the frame loop makes.
class CountingSampler final : public ForwardingSampler
{
public:
  explicit CountingSampler(std::shared_ptr<const savr::Sampler> inner)
    : ForwardingSampler(inner)
    , Mesh(std::move(inner))
  {
  }
  void SampleRay(const savr::Ray& ray, double t0, double dt, int count, float* out,
    const savr::SkipMask* skip) const override
  {
    ++this->Walks;
    ForwardingSampler::SampleRay(ray, t0, dt, count, out, skip);
  }
  bool TracesPaths() const override { return true; }
  bool TracePath(const savr::Ray& ray, double t0, double t1, double spacing, std::size_t maxPieces,
    std::vector<savr::PathPiece>& path) const override
  {
    ++this->Traces;
    return this->Mesh->TracePath(ray, t0, t1, spacing, maxPieces, path);
  }
  void SampleAlongPath(const savr::Ray& ray, const savr::PathPiece* path, std::size_t pieces,
    double traceStart, double t0, double dt, int count, float* out) const override
  {
    ++this->Reads;
    this->Mesh->SampleAlongPath(ray, path, pieces, traceStart, t0, dt, count, out);
  }

  mutable std::atomic<int> Walks{ 0 };
  mutable std::atomic<int> Traces{ 0 };
  mutable std::atomic<int> Reads{ 0 };

private:
  std::shared_ptr<const savr::Sampler> Mesh;
};

struct PathRun
{
  std::vector<float> Image;
  std::vector<int> Walks; // per frame
  std::vector<int> Reads;
  int Traces = 0;
  std::size_t Covered = 0;
  std::size_t PeakMemory = 0;
  std::size_t FinalMemory = 0;
  std::size_t Fixed = 0;
  int Frames = 0;
};

PathRun RunFrames(const std::shared_ptr<const savr::Sampler>& mesh, bool paths, int threads,
  std::size_t budget = std::size_t(1) << 30)
{
  auto counting = std::make_shared<CountingSampler>(mesh);
  const savr::View view = PerspectiveView(Eigen::Vector3d(4.1, -3.3, 3.7), Eigen::Vector3d(1, 1, 1),
    Eigen::Vector3d(0, 0, 1), 30.0, 48, 40, 0.1, 20.0);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.15;
  settings.MaximumFrames = 4;
  settings.TracePaths = paths;
  settings.Threads = threads;
  settings.MemoryBudget = budget;
  savr::FrameLoop loop;
  loop.Reset(view, counting, settings);
  const savr::TransferFunctionTable table = MakeTable(
    loop.Encoding(), [](double v) { return Eigen::Vector3d(0.5 + 0.3 * v, 0.4, 0.9 - 0.2 * v); },
    [](double v) { return 0.3 + 0.2 * std::sin(4 * v); });
  PathRun run;
  for (int k = 0; k < 4; ++k)
  {
    counting->Walks = 0;
    counting->Reads = 0;
    loop.AccumulateFrame(table, savr::BlendMode::Composite);
    run.Walks.push_back(counting->Walks);
    run.Reads.push_back(counting->Reads);
    if (k + 1 < 4)
    {
      run.PeakMemory = std::max(run.PeakMemory, loop.MemoryInUse());
    }
  }
  EXPECT_EQ(loop.CurrentPhase(), savr::Phase::Complete);
  run.Image = loop.Image();
  run.Traces = counting->Traces;
  run.Covered = loop.PixelsCovered();
  run.FinalMemory = loop.MemoryInUse();
  run.Fixed = loop.FixedBytes();
  run.Frames = loop.Frames();
  return run;
}

} // namespace

TEST(RayPaths, LaterFramesReadPathsAndDoNotWalk)
{
  Lattice lattice = HoledLattice(Split::Mixed);
  auto mesh = lattice.M.Sampler();
  ASSERT_TRUE(mesh);
  const PathRun walked = RunFrames(mesh, false, 2);
  const PathRun traced = RunFrames(mesh, true, 2);
  const int rays = static_cast<int>(traced.Covered);
  ASSERT_GT(rays, 500);
  // Without paths every frame walks every ray; with them only the first traces, and every
  // frame reads the paths.
  EXPECT_EQ(walked.Traces, 0);
  EXPECT_EQ(walked.Walks, std::vector<int>(4, rays));
  EXPECT_EQ(traced.Traces, rays);
  EXPECT_EQ(traced.Walks, std::vector<int>(4, 0));
  EXPECT_EQ(traced.Reads, std::vector<int>(4, rays));
  // The same image up to float rounding of the pieces, and it is not blank. (Cells with faces
  // that are not flat overlap or leave slivers where the walk's flat faces meet them: a sample
  // there reads one neighbour or the other depending on where a walk started, and a frame's
  // walk starts at its first sample, a path's at the mesh.)
  EXPECT_LT(MaxAbsDifference(walked.Image, traced.Image), 3e-3);
  EXPECT_GT(MaxValue(traced.Image), 0.3);
  // Paths are held while accumulating and freed once the image is complete.
  EXPECT_GT(traced.PeakMemory, walked.PeakMemory);
  EXPECT_EQ(traced.FinalMemory, walked.FinalMemory);
  // Which rays have paths, and so the image, does not depend on the thread count.
  const PathRun serial = RunFrames(mesh, true, 1);
  EXPECT_TRUE(SameBits(serial.Image, traced.Image));
}

// Paths have only what the budget leaves after the stored samples: with little left, some rays
// walk every frame, the loop stays within the budget, and the image is the same up to rounding.
TEST(RayPaths, PathsKeepWithinTheBudget)
{
  Lattice lattice = HoledLattice(Split::Tetrahedra5);
  auto mesh = lattice.M.Sampler();
  ASSERT_TRUE(mesh);
  const PathRun ample = RunFrames(mesh, true, 2);
  const std::size_t pathBytes = ample.PeakMemory - RunFrames(mesh, false, 2).PeakMemory;
  ASSERT_GT(pathBytes, 0u);
  // A budget that leaves the paths about a third of what they take, besides the per-thread
  // scratch every thread of the machine is counted for.
  const std::size_t scratch = std::max(1u, std::thread::hardware_concurrency()) *
                              savr::TilePaths::kMaxPieces * sizeof(savr::PathPiece);
  const std::size_t budget = ample.Fixed + (ample.PeakMemory - pathBytes) + scratch + pathBytes / 3;
  const PathRun tight = RunFrames(mesh, true, 2, budget);
  EXPECT_EQ(tight.Frames, 4);
  EXPECT_LE(tight.Fixed + tight.PeakMemory + scratch, budget);
  EXPECT_LT(tight.PeakMemory, ample.PeakMemory);
  int later = 0;
  for (int k = 1; k < 4; ++k)
  {
    later += tight.Walks[k];
  }
  EXPECT_GT(later, 0) << "some rays have no path and walk";
  EXPECT_GT(tight.Reads[1], 0) << "some rays have paths";
  EXPECT_LT(MaxAbsDifference(ample.Image, tight.Image), 2e-4);
  EXPECT_TRUE(SameBits(tight.Image, RunFrames(mesh, true, 1, budget).Image));
}

// The composite's fast paths held to its definition. With FrameSettings::FastPaths off, every
// sample goes through Integrator.h's blends and Composite.h; with it on, the same frames run
// through the per-code tables (PlainComposite.h, lit and unlit), AVX2 four rays at a time
// (StoredAVX2.h) or the scalar rows, and the single pass's lean loop, alone or with its rays
// sampled in pairs. The images must agree to round-off and to where rays stop (a ray that stops
// at 1e-6 transmittance on one side and one sample later on the other).

#include "TestHelpers.h"
#include "frame/FrameLoopScenes.h"
#include "mesh/UnstructuredTestMeshes.h"

#include <gtest/gtest.h>

#include <memory>

using namespace savr_test;

namespace
{

// Round-off, and the light behind a ray's last sample when the two paths stop it one sample
// apart at FrameSettings::Termination (1e-6 here).
constexpr double kTolerance = 2e-6;

struct PathScene
{
  std::shared_ptr<const savr::Sampler> Sampler;
  bool Bytes = false; // the wave as ByteWave's bytes
  bool Shade = false;
};

std::unique_ptr<savr::FrameLoop> MakeLoop(const PathScene& scene, const savr::View& view,
  int frames, bool fast, bool vectorize, const savr::ShadingTable& shading)
{
  savr::FrameSettings settings;
  settings.SampleDistance = 0.15;
  settings.MaximumFrames = frames;
  settings.Shade = scene.Shade;
  settings.FastPaths = fast;
  settings.Vectorize = vectorize;
  settings.Termination = 1e-6;
  auto loop = std::make_unique<savr::FrameLoop>();
  loop->Reset(view, scene.Sampler, settings);
  if (scene.Shade)
  {
    loop->SetShading(&shading);
  }
  return loop;
}

// A transfer function thin enough that rays cross the data, and one so opaque that most stop.
savr::TransferFunctionTable Thin(const savr::SampleEncoding& e, const PathScene& scene)
{
  return WaveTable(e, 0.3, scene.Bytes);
}
savr::TransferFunctionTable Opaque(const savr::SampleEncoding& e, const PathScene& scene)
{
  const bool bytes = scene.Bytes;
  return MakeTable(
    e, [](double v) { return Eigen::Vector3d(0.2 + 0.05 * std::tanh(v), 0.5, 0.7); },
    [bytes](double v) { return (bytes ? v / 80.0 - 1.5 : v) > -0.3 ? 0.97 : 0.0; }, 0.5);
}

std::vector<PathScene> Scenes(const WaveGrid& wave, std::vector<std::uint8_t>& bytes)
{
  const auto byteWave = ByteWave(wave, bytes);
  return { { wave.Sampler(), false, false }, { byteWave, true, false },
    { wave.Sampler(), false, true }, { byteWave, true, true } };
}

} // namespace

// Stored frames: 1, 3 (uneven gaps), 4 and 6 frames, 16- and 8-bit codes, lit and unlit, AVX2
// and scalar rows, each frame and after re-blends that make rays stop early and then not.
TEST(CompositePaths, StoredBlendsEqualTheDefinition)
{
  WaveGrid wave(22);
  std::vector<std::uint8_t> bytes;
  const savr::View view = HeadOnView(37); // rays do not fill groups of four evenly
  savr::ShadingTable shading;
  shading.Build({ savr::Light() }, Eigen::Vector3d::UnitZ(), 0.3, 0.6, 0.4, 12.0);
  for (const PathScene& scene : Scenes(wave, bytes))
  {
    ASSERT_TRUE(scene.Sampler);
    for (const int frames : { 1, 3, 4, 6 })
      for (const bool vectorize : { true, false })
      {
        const auto definition = MakeLoop(scene, view, frames, false, vectorize, shading);
        const auto fast = MakeLoop(scene, view, frames, true, vectorize, shading);
        const auto thin = Thin(fast->Encoding(), scene);
        const auto opaque = Opaque(fast->Encoding(), scene);
        for (int k = 0; k < frames; ++k)
        {
          definition->AccumulateFrame(thin, savr::BlendMode::Composite);
          fast->AccumulateFrame(thin, savr::BlendMode::Composite);
          EXPECT_LT(MaxAbsDifference(definition->Image(), fast->Image()), kTolerance)
            << "frame " << k + 1 << " of " << frames << (scene.Bytes ? ", bytes" : "")
            << (scene.Shade ? ", lit" : "") << (vectorize ? ", vector" : ", scalar");
        }
        EXPECT_GT(MaxValue(fast->Image()), 0.1) << "the scene must not be blank";
        for (const auto* table : { &opaque, &thin })
        {
          definition->Reblend(*table, savr::BlendMode::Composite);
          fast->Reblend(*table, savr::BlendMode::Composite);
          EXPECT_LT(MaxAbsDifference(definition->Image(), fast->Image()), kTolerance)
            << "re-blend, " << frames << " frames" << (scene.Bytes ? ", bytes" : "")
            << (scene.Shade ? ", lit" : "") << (vectorize ? ", vector" : ", scalar");
        }
        // Most rays stop under the opaque function: the paths' stops are compared too.
        definition->Reblend(opaque, savr::BlendMode::Composite);
        fast->Reblend(opaque, savr::BlendMode::Composite);
        std::size_t stopped = 0;
        const std::vector<float>& image = fast->Image();
        for (std::size_t i = 3; i < image.size(); i += 4)
        {
          stopped += image[i] >= 1.0f - 1e-6f;
        }
        EXPECT_GT(stopped, image.size() / 4 / 8) << "too few rays reach the termination";
        EXPECT_LT(MaxAbsDifference(definition->Image(), fast->Image()), kTolerance);
      }
  }
}

// The single pass: the lean loop on the grids (unlit), with its rays sampled in pairs on a mesh
// (a sampler that walks its cells), against the definition's loop.
TEST(CompositePaths, SinglePassesEqualTheDefinition)
{
  WaveGrid wave(22);
  std::vector<std::uint8_t> bytes;
  const savr::View view = HeadOnView(37);
  savr::ShadingTable shading;
  std::vector<PathScene> scenes = Scenes(wave, bytes);
  scenes.resize(2); // the lean loop is unlit
  Lattice lattice({ 4, 4, 4 }, Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1),
    Split::Tetrahedra5, nullptr, 0.2);
  lattice.M.SetPointValues([](const Eigen::Vector3d& p)
    { return std::sin(3 * p.x()) * std::cos(2 * p.y()) + 0.5 * p.z() * p.z(); });
  scenes.push_back({ lattice.M.Sampler(), false, false });
  for (const PathScene& scene : scenes)
  {
    ASSERT_TRUE(scene.Sampler);
    for (const double step : { 0.31, 0.04 })
    {
      const auto definition = MakeLoop(scene, view, 1, false, true, shading);
      const auto fast = MakeLoop(scene, view, 1, true, true, shading);
      for (const bool opaque : { false, true })
      {
        const auto table = opaque ? Opaque(fast->Encoding(), scene) : Thin(fast->Encoding(), scene);
        definition->RenderSinglePass(table, savr::BlendMode::Composite, step, 0.0);
        fast->RenderSinglePass(table, savr::BlendMode::Composite, step, 0.0);
        EXPECT_GT(MaxValue(fast->Image()), 0.1) << "the scene must not be blank";
        EXPECT_LT(MaxAbsDifference(definition->Image(), fast->Image()), kTolerance)
          << "step " << step << (opaque ? ", opaque" : ", thin")
          << (scene.Sampler->TracesPaths() ? ", mesh" : (scene.Bytes ? ", bytes" : ""));
      }
    }
  }
}

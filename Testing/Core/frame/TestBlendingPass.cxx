// The blending pass alone: a frame of the slab sampled into the stores and blended, by the
// composite's fast path and by the general blend, gives the slab's closed-form composite; and
// a window over the whole ray gives the image's pixel.

#include "PassScenes.h"
#include "frame/BlendingPass.h"
#include "frame/PassScratch.h"
#include "frame/SamplingPass.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

TEST(BlendingPass, BlendsTheSlabsBeerLambertComposite)
{
  for (const bool plain : { true, false })
  {
    savr_test::SlabScene scene(0.1);
    savr::FrameState& state = scene.State;
    state.Offsets.Resize(1);
    state.Schedule.ChoosePass(state.FrameLimitCount);
    state.Grow(4, 0);
    savr::SamplingPass sampling(state);
    savr::BlendingPass blending(state);
    savr::ThreadBuffers buffers;
    const savr::StoredAttributes none;
    ASSERT_EQ(state.Encoder.Bytes, 2);
    blending.Prepare(scene.TF, 1);
    std::vector<const double*> sorted;
    ASSERT_TRUE(
      blending.PlainIntervalTables(scene.TF, savr::BlendMode::Composite, 1, none, sorted));
    const savr::detail::RowScan<std::uint16_t> scan(0, state.Capacity, 1, false);
    const savr::TileBlend<std::uint16_t> blend{ scene.TF, savr::BlendMode::Composite, 1, none,
      false, sorted, plain, false, scan, state.Pixels.data() };
    for (savr::Tile& tile : state.Tiles)
    {
      sampling.SampleTile<std::uint16_t>(tile, buffers, none, false, false, nullptr, nullptr);
      blending.BlendTile(tile, buffers, blend);
    }
    for (std::size_t p = 0; p < state.Pixels.size(); p += 4)
    {
      ASSERT_NEAR(state.Pixels[p + 3], scene.ExpectedAlpha(), 2e-6) << p / 4 << " " << plain;
      ASSERT_NEAR(state.Pixels[p], 0.2 * scene.ExpectedAlpha(), 2e-6);
    }

    // A window over the whole ray is the image's pixel; one over its first half, the slab's
    // first unit: 1 - (1 - alpha)^1 (the near plane is depth 0, the far plane depth 1, and the
    // rays run 4 units from x = -1, entering the slab at depth 1/4).
    const std::size_t pixels = state.Pixels.size() / 4;
    std::vector<float> nearDepth(pixels, 0.0f);
    std::vector<float> whole(pixels, 1.0f);
    std::vector<float> half(pixels, 0.5f);
    std::vector<float> a(4 * pixels, 0.0f);
    std::vector<float> b(4 * pixels, 0.0f);
    const savr::DepthWindow windows[2] = { { nearDepth.data(), whole.data(), a.data() },
      { nearDepth.data(), half.data(), b.data() } };
    blending.BlendWindows<std::uint16_t>(
      scene.TF, savr::BlendMode::Composite, windows, 2, 1, nullptr);
    EXPECT_TRUE(savr_test::SameBits(a, state.Pixels));
    for (std::size_t p = 0; p < b.size(); p += 4)
    {
      ASSERT_NEAR(b[p + 3], scene.Alpha, 1e-5) << p / 4;
    }
  }
}

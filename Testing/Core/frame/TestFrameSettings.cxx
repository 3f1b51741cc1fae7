#include "frame/FrameSettings.h"

#include <gtest/gtest.h>

#include <functional>
#include <vector>

// Every setting but FineCodes decides a view's samples: changing one starts the view over.
TEST(FrameSettings, EverySettingButFineCodesDecidesTheSamples)
{
  const savr::FrameSettings base;
  EXPECT_TRUE(savr::SameSampling(base, base));
  const std::vector<std::function<void(savr::FrameSettings&)>> changes = {
    [](savr::FrameSettings& s) { s.SampleDistance *= 0.5; },
    [](savr::FrameSettings& s) { s.MaximumFrames *= 2; },
    [](savr::FrameSettings& s) { s.MemoryBudget /= 2; },
    [](savr::FrameSettings& s) { s.ReservedBytes += 1; },
    [](savr::FrameSettings& s) { s.ReservedBytesPerShownPixel += 1; },
    [](savr::FrameSettings& s) { s.MaximumSamplesPerFrame += 1; },
    [](savr::FrameSettings& s) { s.RotateOffsets = !s.RotateOffsets; },
    [](savr::FrameSettings& s) { s.PhaseLength += 1.0; },
    [](savr::FrameSettings& s) { s.Shade = !s.Shade; },
    [](savr::FrameSettings& s) { s.GradientMagnitudes = !s.GradientMagnitudes; },
    [](savr::FrameSettings& s) { s.MagnitudeScale *= 2.0; },
    [](savr::FrameSettings& s) { s.ComponentNormals = !s.ComponentNormals; },
    [](savr::FrameSettings& s) { s.ComponentMagnitudes = !s.ComponentMagnitudes; },
    [](savr::FrameSettings& s) { s.ComponentMagnitudeScales[3] *= 2.0; },
    [](savr::FrameSettings& s) { s.Threads += 1; },
    [](savr::FrameSettings& s) { s.TileSize *= 2; },
    [](savr::FrameSettings& s) { s.Vectorize = !s.Vectorize; },
    [](savr::FrameSettings& s) { s.PassOverTransparentRows = !s.PassOverTransparentRows; },
    [](savr::FrameSettings& s) { s.FastPaths = !s.FastPaths; },
    [](savr::FrameSettings& s) { s.OpacityHorizons = !s.OpacityHorizons; },
    [](savr::FrameSettings& s) { s.Termination *= 0.5; },
    [](savr::FrameSettings& s) { s.TracePaths = !s.TracePaths; },
  };
  // One change per field the comparison names (the header checks that it names all but one).
  EXPECT_EQ(changes.size(), std::tuple_size<decltype(base.Sampling())>::value);
  for (std::size_t i = 0; i < changes.size(); ++i)
  {
    savr::FrameSettings changed = base;
    changes[i](changed);
    EXPECT_FALSE(savr::SameSampling(base, changed)) << "change " << i;
  }
  savr::FrameSettings fine = base;
  fine.FineCodes = !fine.FineCodes;
  EXPECT_TRUE(savr::SameSampling(base, fine)) << "FineCodes is the caller's to weigh";
}

// MaximumRenderTime: a bound so small that every Render does one tile splits each
// frame over several renders; a frame counts once its last tile is done, the renders between
// report the part done, and the refined image equals the one refined a frame per Render. The
// first Render already shows the whole first frame, coarsely: the tiles it has not reached show
// a single pass with one ray per block of pixels. A camera change while a frame is under way
// starts over as usual.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"

#include <string>

int TestSAVRRenderTimeBound(int, char*[])
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(10);
  savr_scenes::Expectations expect;

  savr_scenes::Scene whole(data, 160, 160);
  savr_scenes::WaveletProperty(whole.Property);
  whole.Window->Render();
  vtkSmartPointer<vtkImageData> firstFrame = savr_scenes::Capture(whole.Window);
  const int wholeRenders = 1 + whole.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> refined = savr_scenes::Capture(whole.Window);

  savr_scenes::Scene bounded(data, 160, 160);
  savr_scenes::WaveletProperty(bounded.Property);
  bounded.Mapper->SetMaximumRenderTime(1e-6);
  int renders = 0;
  int partial = 0;
  bool countsOnlyWholeFrames = true;
  while (!bounded.Mapper->GetRefinementComplete() && renders < 10000)
  {
    const int before = bounded.Mapper->GetNumberOfFramesAccumulated();
    bounded.Window->Render();
    ++renders;
    if (renders == 1)
    {
      const double* background = bounded.Renderer->GetBackground();
      vtkSmartPointer<vtkImageData> shown = savr_scenes::Capture(bounded.Window);
      const double covered = savr_scenes::CoveredFraction(shown, background);
      const double frameCovers = savr_scenes::CoveredFraction(firstFrame, background);
      // (The bound is so small that the blocks are the largest, 16x16 pixels: measured 6.8
      // levels off on average.)
      const auto coarse = savr_scenes::Compare(shown, firstFrame);
      expect(bounded.Mapper->GetFrameInProgress() < 0.2 && covered > 0.9 * frameCovers &&
               coarse.Mean < 10.0,
        "the first Render shows the whole first frame coarsely (covers " + std::to_string(covered) +
          " against " + std::to_string(frameCovers) + ", mean " + std::to_string(coarse.Mean) +
          " levels off, " + std::to_string(bounded.Mapper->GetFrameInProgress()) +
          " of the frame sampled)");
    }
    const int after = bounded.Mapper->GetNumberOfFramesAccumulated();
    const double part = bounded.Mapper->GetFrameInProgress();
    if (after == before)
    {
      ++partial;
      countsOnlyWholeFrames = countsOnlyWholeFrames && part > 0.0 && part < 1.0;
    }
    else
    {
      countsOnlyWholeFrames = countsOnlyWholeFrames && after == before + 1 && part == 0.0;
    }
  }
  const std::string seen = " (" + std::to_string(renders) + " renders, " + std::to_string(partial) +
                           " ended a frame's part; " + std::to_string(wholeRenders) + " unbounded)";
  expect(renders > 2 * wholeRenders, "a tiny bound splits every frame over renders" + seen);
  expect(countsOnlyWholeFrames,
    "a frame counts once its last tile is done; the renders between report the part done" + seen);
  expect(bounded.Mapper->GetRefinementComplete() &&
           bounded.Mapper->GetNumberOfFramesAccumulated() == whole.Mapper->GetFrameLimit(),
    "refinement completes with the same frame limit" + seen);
  const auto difference = savr_scenes::Compare(savr_scenes::Capture(bounded.Window), refined);
  expect(difference.Max == 0, "the refined image equals the one refined a frame per Render (max " +
                                std::to_string(difference.Max) + " levels)");

  // A camera change in the middle of a frame starts over.
  bounded.Renderer->GetActiveCamera()->Azimuth(20.0);
  bounded.Window->Render();
  bounded.Window->Render();
  expect(bounded.Mapper->GetNumberOfFramesAccumulated() == 0 &&
           bounded.Mapper->GetFrameInProgress() > 0.0,
    "after a camera change the first frame is under way");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

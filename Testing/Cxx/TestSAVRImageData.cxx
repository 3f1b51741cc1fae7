// Regression images of the wavelet and the MRI head: after one frame, after full refinement, and
// with maximum intensity. Each also checks the image is not blank and, where one exists, matches
// an expectation computed independently of the baseline.
//
// Usage: TestSAVRImageData wavelet|head first|refined|maximum -V baseline.png -T outdir

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkFixedPointVolumeRayCastMapper.h"

#include <cstring>

int TestSAVRImageData(int argc, char* argv[])
{
  if (argc < 3)
  {
    std::cerr << "usage: TestSAVRImageData wavelet|head first|refined|maximum ...\n";
    return EXIT_FAILURE;
  }
  const std::string sceneName = argv[1];
  const std::string stage = argv[2];
  const bool head = sceneName == "head";
  vtkSmartPointer<vtkImageData> data = head ? savr_scenes::Head() : savr_scenes::Wavelet();
  if (data->GetNumberOfPoints() == 0)
  {
    return EXIT_FAILURE;
  }

  savr_scenes::Scene scene(data, 300, 300);
  head ? savr_scenes::HeadProperty(scene.Property) : savr_scenes::WaveletProperty(scene.Property);
  if (stage == "maximum")
  {
    scene.Mapper->SetBlendModeToMaximumIntensity();
  }
  if (head)
  {
    savr_scenes::FaceTheHead(scene.Renderer);
  }

  int failures = 0;
  if (stage == "first")
  {
    scene.Window->Render();
    if (scene.Mapper->GetNumberOfFramesAccumulated() != 1)
    {
      std::cerr << "expected 1 frame, got " << scene.Mapper->GetNumberOfFramesAccumulated() << "\n";
      ++failures;
    }
  }
  else
  {
    const int renders = scene.RenderUntilComplete();
    const int frames = scene.Mapper->GetNumberOfFramesAccumulated();
    std::cout << "refined in " << renders << " renders to " << frames << " frames, step "
              << scene.Mapper->GetEffectiveSampleDistance() << "\n";
    if (frames < 4 || renders != frames)
    {
      std::cerr << "expected at least 4 frames in as many renders\n";
      ++failures;
    }
  }

  vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene.Window);
  const double covered = savr_scenes::CoveredFraction(image, scene.Renderer->GetBackground());
  std::cout << "covered fraction " << covered << "\n";
  if (covered < 0.1)
  {
    std::cerr << "the image is (nearly) blank\n";
    ++failures;
  }

  if (stage == "refined")
  {
    // Independent expectation: K frames at step dt equal one pass at dt / K.
    savr_scenes::Scene fine(data, 300, 300);
    head ? savr_scenes::HeadProperty(fine.Property) : savr_scenes::WaveletProperty(fine.Property);
    fine.Renderer->SetActiveCamera(scene.Renderer->GetActiveCamera());
    fine.Mapper->SetSampleDistance(
      scene.Mapper->GetEffectiveSampleDistance() / scene.Mapper->GetNumberOfFramesAccumulated());
    fine.Mapper->SetMaximumNumberOfFrames(1);
    fine.Window->Render();
    const auto d = savr_scenes::Compare(image, savr_scenes::Capture(fine.Window));
    std::cout << "refined vs one fine pass: max " << d.Max << " mean " << d.Mean << "\n";
    // The fine pass samples at another offset inside the fine step: only O(step^2) differences.
    if (d.Max > 6.0 || d.Mean > 0.3)
    {
      std::cerr << "refined image differs from one pass at the refined step\n";
      ++failures;
    }
  }
  if (stage == "maximum")
  {
    // Independent expectation: VTK's fixed-point mapper, maximum intensity at a fine step.
    savr_scenes::Scene peer(data, 300, 300);
    head ? savr_scenes::HeadProperty(peer.Property) : savr_scenes::WaveletProperty(peer.Property);
    vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
    fixedPoint->SetInputData(data);
    fixedPoint->SetBlendModeToMaximumIntensity();
    fixedPoint->AutoAdjustSampleDistancesOff();
    fixedPoint->SetSampleDistance(0.1);
    fixedPoint->SetImageSampleDistance(1.0);
    peer.Volume->SetMapper(fixedPoint);
    peer.Renderer->SetActiveCamera(scene.Renderer->GetActiveCamera());
    peer.Window->Render();
    const auto d = savr_scenes::Compare(image, savr_scenes::Capture(peer.Window));
    std::cout << "maximum intensity vs fixed point: max " << d.Max << " mean " << d.Mean << "\n";
    // Fixed point quantizes to 15 bits and interpolates differently at the edges: a few levels.
    if (d.Mean > 2.0)
    {
      std::cerr << "maximum intensity differs from the fixed-point mapper's\n";
      ++failures;
    }
  }

  if (!savr_scenes::MatchesBaseline(scene.Window, argc, argv))
  {
    ++failures;
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

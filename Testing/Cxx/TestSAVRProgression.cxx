// The phases of progressive refinement as a VTK user sees them: frames accumulate one per
// Render(); a camera move mid-refinement starts over; nothing changed after completion reuses
// the image; a transfer-function edit re-blends without new samples and equals a fresh render;
// an edit taken back before refinement completes leaves no tile showing it; single passes while
// interacting; the thread count does not change a byte.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkObject.h"
#include "vtkPiecewiseFunction.h"

namespace
{
savr_scenes::Expectations Expect;

void CountFrame(vtkObject*, unsigned long, void* clientData, void*)
{
  ++*static_cast<int*>(clientData);
}

void KeepFrameInfo(vtkObject*, unsigned long, void* clientData, void* callData)
{
  *static_cast<vtkSAVRVolumeMapper::FrameInfo*>(clientData) =
    *static_cast<vtkSAVRVolumeMapper::FrameInfo*>(callData);
}

// A fresh render, on one thread, of the wavelet with the opacity edit the test makes.
vtkSmartPointer<vtkImageData> EditedFreshRender(vtkImageData* data, vtkCamera* camera)
{
  savr_scenes::Scene fresh(data, 200, 200);
  savr_scenes::WaveletProperty(fresh.Property);
  fresh.Property->GetScalarOpacity()->AddPoint(160.0, 0.6);
  fresh.Mapper->SetMaximumNumberOfFrames(8);
  fresh.Mapper->SetNumberOfThreads(1);
  fresh.Renderer->SetActiveCamera(camera);
  fresh.RenderUntilComplete();
  return savr_scenes::Capture(fresh.Window);
}

// In a world of small units, a small change of the sample distance still starts over.
void SmallWorldStartsOver(vtkImageData* data)
{
  auto tiny = vtkSmartPointer<vtkImageData>::New();
  tiny->ShallowCopy(data);
  tiny->SetSpacing(1e-7, 1e-7, 1e-7);
  tiny->SetOrigin(0, 0, 0);
  savr_scenes::Scene small(tiny, 100, 100);
  savr_scenes::WaveletProperty(small.Property);
  small.Property->SetScalarOpacityUnitDistance(1e-7);
  small.Mapper->SetMaximumNumberOfFrames(4);
  small.Mapper->SetSampleDistance(1e-7);
  small.Window->Render();
  small.Window->Render();
  Expect(small.Mapper->GetNumberOfFramesAccumulated() == 2, "two frames in a small world");
  small.Mapper->SetSampleDistance(0.8e-7);
  small.Window->Render();
  Expect(small.Mapper->GetNumberOfFramesAccumulated() == 1, "a new sample distance starts over");
  Expect(savr_scenes::CoveredFraction(
           savr_scenes::Capture(small.Window), small.Renderer->GetBackground()) > 0.1,
    "a small world renders");
}

// An error tolerance ends refinement before the frame limit, and the event reports it.
void ToleranceEndsRefinement(vtkImageData* data)
{
  savr_scenes::Scene tolerant(data, 200, 200);
  savr_scenes::WaveletProperty(tolerant.Property);
  tolerant.Mapper->SetMaximumNumberOfFrames(256);
  tolerant.Mapper->SetErrorTolerance(0.0002);
  vtkSAVRVolumeMapper::FrameInfo info{};
  vtkNew<vtkCallbackCommand> keep;
  keep->SetCallback(KeepFrameInfo);
  keep->SetClientData(&info);
  tolerant.Mapper->AddObserver(vtkSAVRVolumeMapper::RefinementFrameEvent, keep);
  const int tolerantRenders = tolerant.RenderUntilComplete(300);
  std::cout << "tolerance 0.0002: " << tolerantRenders << " frames, estimate "
            << tolerant.Mapper->GetErrorEstimate() << "\n";
  Expect(tolerant.Mapper->GetRefinementComplete(), "refinement completes at the tolerance");
  Expect(tolerantRenders >= 2 && tolerantRenders < 256, "the tolerance ends refinement early");
  Expect(tolerant.Mapper->GetErrorEstimate() >= 0.0 && tolerant.Mapper->GetErrorEstimate() < 0.0002,
    "the estimate is below the tolerance");
  Expect(info.Complete && info.FramesAccumulated == tolerantRenders &&
           info.ErrorEstimate == tolerant.Mapper->GetErrorEstimate() && info.FrameLimit == 256,
    "the event reports frames, limit, estimate and completion");
  const int eventsBefore = info.FramesAccumulated;
  tolerant.Window->Render();
  Expect(tolerant.Mapper->GetNumberOfFramesAccumulated() == eventsBefore,
    "no frames are added after the tolerance is met");
}
// An edit taken back before refinement completes: with an error tolerance, the frames after the
// edit go to the tiles it made change again; every other tile shows the function taken back too,
// and the refined image is the one before the edit.
void EditTakenBackBeforeCompletion(vtkImageData* data)
{
  savr_scenes::Scene scene(data, 200, 200);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(64);
  scene.Mapper->SetErrorTolerance(0.0005);
  scene.RenderUntilComplete(300);
  vtkSmartPointer<vtkImageData> before = savr_scenes::Capture(scene.Window);
  vtkPiecewiseFunction* opacity = scene.Property->GetScalarOpacity();
  vtkNew<vtkPiecewiseFunction> kept;
  kept->DeepCopy(opacity);
  opacity->AddPoint(160.0, 1.0);
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> edited = savr_scenes::Capture(scene.Window);
  Expect(!scene.Mapper->GetRefinementComplete(), "the edit makes some tiles take frames again");
  opacity->DeepCopy(kept);
  scene.RenderUntilComplete(300);
  const auto back = savr_scenes::Compare(before, savr_scenes::Capture(scene.Window));
  const auto shown = savr_scenes::Compare(before, edited);
  std::cout << "edit taken back before completion: the edit changed the image by max " << shown.Max
            << " mean " << shown.Mean << "; taken back, max " << back.Max << " mean " << back.Mean
            << "\n";
  Expect(shown.Mean > 1.0, "the edit shows");
  Expect(back.Max <= 4.0 && back.Mean < 0.05, "taken back, the image is the one before the edit");
}
} // namespace

int TestSAVRProgression(int argc, char* argv[])
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet();
  savr_scenes::Scene scene(data, 200, 200);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  int events = 0;
  vtkNew<vtkCallbackCommand> counter;
  counter->SetCallback(CountFrame);
  counter->SetClientData(&events);
  scene.Mapper->AddObserver(vtkSAVRVolumeMapper::RefinementFrameEvent, counter);

  // Accumulation, one frame per render, memory growing with it.
  // (Room for 4 frames from the first on, for 8 from the fifth.)
  vtkTypeUInt64 memoryAt1 = 0;
  for (int k = 1; k <= 5; ++k)
  {
    scene.Window->Render();
    Expect(scene.Mapper->GetNumberOfFramesAccumulated() == k, "one frame per render");
    memoryAt1 = k == 1 ? scene.Mapper->GetMemoryInUse() : memoryAt1;
  }
  Expect(events == 5, "one event per refinement frame");
  Expect(!scene.Mapper->GetRefinementComplete(), "not complete after 5 of 8 frames");
  const vtkTypeUInt64 memoryAt5 = scene.Mapper->GetMemoryInUse();
  Expect(memoryAt1 > 0, "samples are stored");
  Expect(memoryAt5 == 2 * memoryAt1, "room grows with the frames, up to the frame limit");

  // A camera move mid-refinement starts over.
  const vtkTypeUInt64 takenBeforeMove = scene.Mapper->GetNumberOfSamplesTaken();
  scene.Renderer->GetActiveCamera()->Azimuth(10.0);
  scene.Window->Render();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 1, "a camera move resets the frame count");
  // (At least the samples the frame keeps, from each ray's front to its horizon: the first frame
  // samples a few rows past it, in pieces. Fewer than the five frames before.)
  const vtkTypeUInt64 takenByMove = scene.Mapper->GetNumberOfSamplesTaken() - takenBeforeMove;
  Expect(takenByMove >= scene.Mapper->GetNumberOfStoredSamples() && takenByMove < takenBeforeMove &&
           scene.Mapper->GetNumberOfStoredSamples() > 0,
    "the new frame's samples are counted as taken");
  Expect(scene.Mapper->GetMemoryInUse() < memoryAt5, "a reset frees the old samples");

  // Complete, then reuse.
  const int renders = scene.RenderUntilComplete();
  Expect(renders == 7, "7 more renders complete 8 frames");
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 8, "8 frames accumulated");
  const int eventsAtCompletion = events;
  vtkSmartPointer<vtkImageData> complete = savr_scenes::Capture(scene.Window);
  scene.Window->Render();
  Expect(events == eventsAtCompletion, "nothing changed: the image is reused, no frame is made");
  Expect(savr_scenes::Compare(complete, savr_scenes::Capture(scene.Window)).Max == 0.0,
    "the reused image is the same");

  // A transfer-function edit re-blends the stored samples.
  const vtkTypeUInt64 memoryFilled = scene.Mapper->GetMemoryInUse();
  const vtkTypeUInt64 takenFilled = scene.Mapper->GetNumberOfSamplesTaken();
  scene.Property->GetScalarOpacity()->AddPoint(160.0, 0.6);
  scene.Window->Render();
  Expect(events == eventsAtCompletion + 1, "a transfer-function edit makes one re-blend frame");
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 8, "re-blending keeps the frames");
  Expect(scene.Mapper->GetMemoryInUse() == memoryFilled &&
           scene.Mapper->GetNumberOfSamplesTaken() == takenFilled,
    "re-blending takes no new samples (the sampler is not called)");
  vtkSmartPointer<vtkImageData> edited = savr_scenes::Capture(scene.Window);
  Expect(savr_scenes::Compare(edited, complete).Mean > 0.5, "the edit changes the image");

  Expect(
    savr_scenes::Compare(edited, EditedFreshRender(data, scene.Renderer->GetActiveCamera())).Max ==
      0.0,
    "re-blending equals a fresh render with the edited function (and 1 thread equals all)");

  // Interaction: single passes that store nothing, then accumulation resumes.
  scene.Mapper->InteractiveOn();
  scene.Renderer->GetActiveCamera()->Azimuth(5.0);
  scene.Window->Render();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 0, "interacting frames store nothing");
  Expect(scene.Mapper->GetMemoryInUse() == 0, "interacting frames allocate nothing");
  Expect(!scene.Mapper->GetRefinementComplete(), "interacting is never complete");
  Expect(savr_scenes::CoveredFraction(
           savr_scenes::Capture(scene.Window), scene.Renderer->GetBackground()) > 0.1,
    "the interacting frame is drawn");
  scene.Mapper->InteractiveOff();
  scene.Window->Render();
  Expect(
    scene.Mapper->GetNumberOfFramesAccumulated() == 1, "accumulation resumes after interaction");

  // Interacting without moving the camera, after completion: complete again only once the
  // stored samples are blended again, not while the interacting pass is on screen.
  scene.RenderUntilComplete();
  scene.Mapper->InteractiveOn();
  scene.Window->Render();
  scene.Mapper->InteractiveOff();
  Expect(!scene.Mapper->GetRefinementComplete(), "an interacting pass on screen is not complete");
  scene.Window->Render();
  Expect(scene.Mapper->GetRefinementComplete(), "the next frame blends the stored samples again");

  // A memory budget that holds the images but is too small for one frame: plain ray casting
  // that still follows the transfer function.
  scene.Mapper->SetMemoryBudget(scene.Mapper->GetImageMemoryInUse() + 1024);
  scene.Window->Render();
  Expect(scene.Mapper->GetRefinementComplete() && scene.Mapper->GetMemoryInUse() == 0,
    "no samples are stored, and one pass is final");
  vtkSmartPointer<vtkImageData> beforeEdit = savr_scenes::Capture(scene.Window);
  scene.Property->GetScalarOpacity()->AddPoint(100.0, 0.5);
  scene.Window->Render();
  Expect(savr_scenes::Compare(beforeEdit, savr_scenes::Capture(scene.Window)).Mean > 0.5,
    "a transfer-function edit shows without stored samples");
  scene.Property->GetScalarOpacity()->RemovePoint(100.0);
  scene.Mapper->SetMemoryBudget(vtkTypeUInt64(1) << 30);

  SmallWorldStartsOver(data);

  // Pre-integration is a way of blending: switching it re-blends the stored samples, and on
  // this smooth transfer function it changes the refined image only a little.
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> pointSampled = savr_scenes::Capture(scene.Window);
  const vtkTypeUInt64 memoryBefore = scene.Mapper->GetMemoryInUse();
  const int framesBefore = scene.Mapper->GetNumberOfFramesAccumulated();
  const vtkTypeUInt64 takenBefore = scene.Mapper->GetNumberOfSamplesTaken();
  scene.Mapper->PreIntegrationOn();
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> preIntegrated = savr_scenes::Capture(scene.Window);
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == framesBefore &&
           scene.Mapper->GetMemoryInUse() == memoryBefore &&
           scene.Mapper->GetRefinementComplete() &&
           scene.Mapper->GetNumberOfSamplesTaken() == takenBefore,
    "switching to pre-integration re-blends without sampling");
  const auto integrationChange = savr_scenes::Compare(pointSampled, preIntegrated);
  std::cout << "pre-integrated vs point sampled: max " << integrationChange.Max << " mean "
            << integrationChange.Mean << "\n";
  Expect(integrationChange.Mean > 0.0 && integrationChange.Mean < 1.0,
    "pre-integration changes a smooth image a little");
  scene.Mapper->PreIntegrationOff();

  ToleranceEndsRefinement(data);
  EditTakenBackBeforeCompletion(data);

  scene.RenderUntilComplete();
  if (!savr_scenes::MatchesBaseline(scene.Window, argc, argv))
  {
    ++Expect.Failures;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

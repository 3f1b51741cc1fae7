// Multi-component scalars against VTK's fixed-point mapper at a fine step. Without arguments:
// two components, independent (each component through its own colour and opacity functions,
// weighted by ComponentWeight) and dependent (the first component's colour, the second's
// opacity). With "four": three and four independent components, and four dependent ones
// (RGBA). In both, an edit of the last component's transfer function re-blends to a fresh
// render's bytes without sampling again, every component shows, images do not depend on the
// thread count, and a baseline.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <string>

namespace
{
savr_scenes::Expectations Expect;

void FourIndependent(vtkVolumeProperty* property)
{
  savr_scenes::IndependentComponentsProperty(property);
  savr_scenes::LastComponentFunctions(property, 0.4);
}

savr_scenes::Scene* Render(
  vtkImageData* data, vtkCamera* camera, const std::function<void(vtkVolumeProperty*)>& configure)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes;
  scenes.emplace_back(new savr_scenes::Scene(data, 160, 160));
  savr_scenes::Scene& scene = *scenes.back();
  configure(scene.Property);
  scene.Mapper->SetSampleDistance(0.5);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  scene.Renderer->SetActiveCamera(camera);
  scene.RenderUntilComplete();
  return &scene;
}

void SetUpCamera(vtkCamera* camera)
{
  camera->SetPosition(50, 35, 70);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  camera->SetClippingRange(1, 300);
}

// Renders `data` configured by `configure` with both mappers and checks they agree.
savr_scenes::Scene* AgainstFixedPoint(vtkImageData* data, vtkCamera* camera, const char* name,
  const std::function<void(vtkVolumeProperty*)>& configure)
{
  savr_scenes::Scene* scene = Render(data, camera, configure);
  vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene->Window);
  vtkSmartPointer<vtkImageData> peer =
    savr_scenes::FixedPointImage(data, camera, 160, 160, nullptr, configure);
  const auto d = savr_scenes::Compare(image, peer);
  const double covered = savr_scenes::CoveredFraction(image, scene->Renderer->GetBackground());
  std::cout << name << " components vs the fixed-point mapper: max " << d.Max << " mean " << d.Mean
            << " levels; covered " << covered << "\n";
  // Both quantize the components (8 bits each here, 15 bits there) and sample differently
  // (this mapper's samples are trilinear and 1/16 of a voxel apart after refinement, the
  // fixed-point mapper's 0.05 apart on its own lattice): measured 1.0 levels on average for two
  // independent components, 1.1 for three and four, 0.5 for luminance-alpha and 0.6 for RGBA.
  Expect(d.Mean < 2.0, std::string(name) + " components render as the fixed-point mapper does");
  Expect(covered > 0.05, std::string(name) + " components: not blank");
  return scene;
}

int FourComponents(int argc, char* argv[])
{
  vtkNew<vtkCamera> camera;
  SetUpCamera(camera);
  vtkSmartPointer<vtkImageData> three = savr_scenes::ComponentImage(3);
  vtkSmartPointer<vtkImageData> four = savr_scenes::ComponentImage(4);
  vtkSmartPointer<vtkImageData> rgba = savr_scenes::ColorAndAlphaImage();
  AgainstFixedPoint(three, camera, "three independent",
    [](vtkVolumeProperty* p)
    {
      savr_scenes::IndependentComponentsProperty(p);
      savr_scenes::LastComponentFunctions(p, 0.4);
    });
  savr_scenes::Scene* scene = AgainstFixedPoint(four, camera, "four independent", FourIndependent);
  AgainstFixedPoint(rgba, camera, "four dependent (RGBA)", savr_scenes::ColorAndAlphaProperty);
  Expect(scene->Mapper->GetNumberOfFramesAccumulated() == 8, "four components refine");

  // Every component shows: with any one's weight at 0 the image changes.
  vtkSmartPointer<vtkImageData> all = savr_scenes::Capture(scene->Window);

  // While the camera moves, one pass at the base step draws all four components too.
  scene->Mapper->InteractiveOn();
  scene->Window->Render();
  const auto moving = savr_scenes::Compare(savr_scenes::Capture(scene->Window), all);
  std::cout << "four components, interacting vs refined: max " << moving.Max << " mean "
            << moving.Mean << " levels\n";
  Expect(moving.Mean > 0.0 && moving.Mean < 3.0, "an interacting frame draws four components");
  scene->Mapper->InteractiveOff();
  scene->RenderUntilComplete();
  for (int c = 0; c < 4; ++c)
  {
    savr_scenes::Scene* without = Render(four, camera,
      [c](vtkVolumeProperty* p)
      {
        FourIndependent(p);
        p->SetComponentWeight(c, 0.0);
      });
    const double change = savr_scenes::Compare(savr_scenes::Capture(without->Window), all).Mean;
    std::cout << "without component " << c << ": mean change " << change << " levels\n";
    Expect(change > 0.5, "component " + std::to_string(c) + " shows");
  }

  // Editing the fourth component's opacity after refinement re-blends: no new frame, and the
  // image equals a fresh render with the edited function.
  const int frames = scene->Mapper->GetNumberOfFramesAccumulated();
  const vtkTypeUInt64 taken = scene->Mapper->GetNumberOfSamplesTaken();
  savr_scenes::LastComponentFunctions(scene->Property, 0.8);
  scene->Window->Render();
  Expect(scene->Mapper->GetNumberOfFramesAccumulated() == frames &&
           scene->Mapper->GetRefinementComplete() &&
           scene->Mapper->GetNumberOfSamplesTaken() == taken,
    "a fourth component's edit re-blends without sampling");
  vtkSmartPointer<vtkImageData> edited = savr_scenes::Capture(scene->Window);
  const auto editedProperty = [](vtkVolumeProperty* p)
  {
    savr_scenes::IndependentComponentsProperty(p);
    savr_scenes::LastComponentFunctions(p, 0.8);
  };
  savr_scenes::Scene* fresh = Render(four, camera, editedProperty);
  Expect(savr_scenes::Compare(edited, savr_scenes::Capture(fresh->Window)).Max == 0.0,
    "the re-blended image equals a fresh render");
  Expect(savr_scenes::Compare(edited, all).Mean > 0.5, "the edit changes the image");

  // Two more bytes per sample hold the third and fourth components.
  const double bytes = savr_scenes::BytesPerStoredSample(scene->Mapper);
  std::cout << "four components: " << bytes << " bytes per stored sample\n";
  Expect(bytes <= 4.0 + 1e-9, "four components take at most 4 bytes per sample");

  // Images do not depend on the thread count.
  savr_scenes::Scene* oneThread = Render(four, camera, editedProperty);
  oneThread->Mapper->SetNumberOfThreads(1);
  oneThread->RenderUntilComplete();
  Expect(savr_scenes::Compare(savr_scenes::Capture(oneThread->Window), edited).Max == 0.0,
    "1 thread and all threads give the same bytes");

  // Shaded: lit by the first component's gradient, and not the unshaded image.
  savr_scenes::Scene* shaded = Render(four, camera,
    [&](vtkVolumeProperty* p)
    {
      editedProperty(p);
      p->ShadeOn();
    });
  const vtkSmartPointer<vtkImageData> lit = savr_scenes::Capture(shaded->Window);
  Expect(savr_scenes::CoveredFraction(lit, shaded->Renderer->GetBackground()) > 0.05 &&
           savr_scenes::Compare(lit, edited).Mean > 1.0,
    "four shaded components: lit, not blank");

  scene->Window->Render();
  if (!savr_scenes::MatchesBaseline(scene->Window, argc, argv))
  {
    ++Expect.Failures;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
} // namespace

int TestSAVRComponents(int argc, char* argv[])
{
  if (argc > 1 && std::string(argv[1]) == "four")
  {
    return FourComponents(argc, argv);
  }
  vtkSmartPointer<vtkImageData> data = savr_scenes::ComponentImage(2);
  vtkNew<vtkCamera> camera;
  SetUpCamera(camera);

  struct Case
  {
    const char* Name;
    std::function<void(vtkVolumeProperty*)> Configure;
  };
  const Case cases[] = { { "independent", savr_scenes::IndependentComponentsProperty },
    { "dependent", savr_scenes::DependentComponentsProperty } };
  savr_scenes::Scene* independentScene = nullptr;
  for (const Case& c : cases)
  {
    savr_scenes::Scene* scene = AgainstFixedPoint(data, camera, c.Name, c.Configure);
    if (!independentScene)
    {
      independentScene = scene;
    }
  }

  // The second component matters: without it (weight 0) the image changes.
  vtkSmartPointer<vtkImageData> withSecond = savr_scenes::Capture(independentScene->Window);
  savr_scenes::Scene* firstOnly = Render(data, camera,
    [](vtkVolumeProperty* p)
    {
      savr_scenes::IndependentComponentsProperty(p);
      p->SetComponentWeight(1, 0.0);
    });
  Expect(savr_scenes::Compare(savr_scenes::Capture(firstOnly->Window), withSecond).Mean > 1.0,
    "the second component shows");

  // Editing the second component's opacity after refinement re-blends: no new frame, and the
  // image equals a fresh render with the edited function.
  const int frames = independentScene->Mapper->GetNumberOfFramesAccumulated();
  const vtkTypeUInt64 taken = independentScene->Mapper->GetNumberOfSamplesTaken();
  savr_scenes::SecondComponentFunctions(independentScene->Property, 0.9);
  independentScene->Window->Render();
  Expect(independentScene->Mapper->GetNumberOfFramesAccumulated() == frames &&
           independentScene->Mapper->GetRefinementComplete() &&
           independentScene->Mapper->GetNumberOfSamplesTaken() == taken,
    "a second component's edit re-blends without sampling");
  vtkSmartPointer<vtkImageData> edited = savr_scenes::Capture(independentScene->Window);
  savr_scenes::Scene* fresh = Render(data, camera,
    [](vtkVolumeProperty* p)
    {
      savr_scenes::IndependentComponentsProperty(p);
      savr_scenes::SecondComponentFunctions(p, 0.9);
    });
  Expect(savr_scenes::Compare(edited, savr_scenes::Capture(fresh->Window)).Max == 0.0,
    "the re-blended image equals a fresh render");
  Expect(savr_scenes::Compare(edited, withSecond).Mean > 0.5, "the edit changes the image");

  // Images do not depend on the thread count.
  savr_scenes::Scene* oneThread = Render(data, camera,
    [](vtkVolumeProperty* p)
    {
      savr_scenes::IndependentComponentsProperty(p);
      savr_scenes::SecondComponentFunctions(p, 0.9);
    });
  oneThread->Mapper->SetNumberOfThreads(1);
  oneThread->RenderUntilComplete();
  Expect(savr_scenes::Compare(savr_scenes::Capture(oneThread->Window), edited).Max == 0.0,
    "1 thread and all threads give the same bytes");

  // New data whose second component spans another range: the tables follow the new range, so
  // the image equals a fresh render of the new data.
  auto changing = vtkSmartPointer<vtkImageData>::New();
  changing->DeepCopy(data);
  savr_scenes::Scene* changed =
    Render(changing, camera, savr_scenes::IndependentComponentsProperty);
  vtkDataArray* pair = changing->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < pair->GetNumberOfTuples(); ++i)
  {
    pair->SetComponent(i, 1, 0.5 * pair->GetComponent(i, 1));
  }
  pair->Modified();
  changed->RenderUntilComplete();
  auto halved = vtkSmartPointer<vtkImageData>::New();
  halved->DeepCopy(changing);
  savr_scenes::Scene* reference =
    Render(halved, camera, savr_scenes::IndependentComponentsProperty);
  const auto afterChange = savr_scenes::Compare(
    savr_scenes::Capture(changed->Window), savr_scenes::Capture(reference->Window));
  std::cout << "after a change of the second component's range vs a fresh render: max "
            << afterChange.Max << "\n";
  Expect(afterChange.Max == 0.0, "new component ranges give new tables");

  independentScene->Window->Render();
  if (!savr_scenes::MatchesBaseline(independentScene->Window, argc, argv))
  {
    ++Expect.Failures;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

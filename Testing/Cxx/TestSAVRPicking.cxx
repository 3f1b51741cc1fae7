// Picking and selection with a SAVR volume in the view: a vtkHardwareSelector's passes see no
// volume (it draws nothing then; its image would read as junk ids) and still see the surface
// beside it; vtkVolumePicker picks the volume inside its bounds. Refinement carries on after.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataObject.h"
#include "vtkHardwareSelector.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkPolyDataMapper.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkSphereSource.h"
#include "vtkVolumePicker.h"

#include <string>

int TestSAVRPicking(int, char*[])
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(10);
  savr_scenes::Scene scene(data, 200, 160);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(4);

  // An opaque sphere beside the volume (which spans -10..10): the selector must still find it.
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(18.0, 0.0, 0.0);
  sphere->SetRadius(4.0);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> sphereActor;
  sphereActor->SetMapper(sphereMapper);
  scene.Renderer->AddActor(sphereActor);
  scene.Renderer->ResetCamera();
  scene.RenderUntilComplete();

  savr_scenes::Expectations expect;
  vtkNew<vtkHardwareSelector> selector;
  selector->SetRenderer(scene.Renderer);
  selector->SetArea(0, 0, 199, 159);
  selector->SetFieldAssociation(vtkDataObject::FIELD_ASSOCIATION_CELLS);
  vtkSmartPointer<vtkSelection> selection;
  selection.TakeReference(selector->Select());
  // Every id must be one of the sphere's cells: the volume's colours, read as ids, give ids
  // of any prop and any size.
  sphere->Update();
  const vtkIdType sphereCells = sphere->GetOutput()->GetNumberOfCells();
  vtkIdType sphereIds = 0;
  vtkIdType otherIds = 0;
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    vtkObjectBase* prop = node->GetProperties()->Get(vtkSelectionNode::PROP());
    vtkAbstractArray* list = node->GetSelectionList();
    for (vtkIdType i = 0; list && i < list->GetNumberOfTuples(); ++i)
    {
      const vtkIdType id = list->GetVariantValue(i).ToLongLong();
      const bool sphereCell = prop == sphereActor.GetPointer() && id >= 0 && id < sphereCells;
      ++(sphereCell ? sphereIds : otherIds);
    }
  }
  const std::string counts = " (" + std::to_string(sphereIds) + " of the sphere's " +
                             std::to_string(sphereCells) + " cells, " + std::to_string(otherIds) +
                             " other ids)";
  std::cout << counts << "\n";
  expect(sphereIds > 0, "the selector finds the sphere's cells" + counts);
  expect(otherIds == 0, "the selector finds nothing else" + counts);

  // The picker hits the volume at the window's centre of the volume's projection.
  double centre[4] = { 0.0, 0.0, 0.0, 1.0 };
  scene.Renderer->SetWorldPoint(centre);
  scene.Renderer->WorldToDisplay();
  const double* display = scene.Renderer->GetDisplayPoint();
  vtkNew<vtkVolumePicker> picker;
  const int picked = picker->Pick(display[0], display[1], 0.0, scene.Renderer);
  const double* position = picker->GetPickPosition();
  expect(picked && picker->GetProp3D() == scene.Volume.GetPointer(),
    "vtkVolumePicker picks the volume at its centre");
  bool inside = true;
  for (int a = 0; a < 3; ++a)
  {
    inside = inside && position[a] >= -10.0 - 1e-6 && position[a] <= 10.0 + 1e-6;
  }
  expect(inside, "the pick position lies inside the volume's bounds");

  // Selection leaves the stored samples alone: a render after it reuses the refined image.
  const int frames = scene.Mapper->GetNumberOfFramesAccumulated();
  scene.Window->Render();
  expect(
    scene.Mapper->GetRefinementComplete() && scene.Mapper->GetNumberOfFramesAccumulated() == frames,
    "refinement stays complete after selection and picking");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

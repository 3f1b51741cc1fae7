// Example 5: images of several components. Independent components each go through their own
// colour and opacity functions, weighted: the wavelet, a green shell, a blue shell and a red
// slab (--components 2 to 4). Dependent components are two (the first's colour, the second's
// opacity; key c switches two components between independent and dependent) or four (--rgba:
// unsigned char RGBA, the colour from the first three, the opacity from the fourth).
//
//   savr_components [--components 2|3|4] [--rgba] [--headless]
//                   [--output savr_components.png] [--size 512]

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkRenderWindowInteractor.h"

#include <algorithm>
#include <cstdio>

namespace
{
// Key c: two components, independent or dependent.
void OnKey(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
  auto* property = static_cast<vtkVolumeProperty*>(clientData);
  if (interactor->GetKeyCode() != 'c')
  {
    return;
  }
  property->GetIndependentComponents() ? savr_scenes::DependentComponentsProperty(property)
                                       : savr_scenes::IndependentComponentsProperty(property);
  interactor->Render();
}
} // namespace

int main(int argc, char* argv[])
{
  int components = 2;
  bool rgba = false;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_components: images of two to four components, independent or dependent, rendered "
    "with\nvtkSAVRVolumeMapper (key c: two components independent or dependent).");
  savr_scenes::WindowOptions window(arguments, "savr_components.png");
  arguments.Option("--components", &components, "Independent components, 2 to 4 (2).");
  arguments.Flag("--rgba", &rgba, "Four dependent components: unsigned char RGBA.");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  components = std::min(std::max(components, 2), 4);

  // The components on the wavelet's grid, 61 points along each axis.
  vtkSmartPointer<vtkImageData> image =
    rgba ? savr_scenes::ColorAndAlphaImage(30) : savr_scenes::ComponentImage(components, 30);
  savr_scenes::Scene scene(image, window.Size, window.Size);
  if (rgba)
  {
    savr_scenes::ColorAndAlphaProperty(scene.Property);
  }
  else
  {
    savr_scenes::IndependentComponentsProperty(scene.Property);
    if (components > 2)
    {
      savr_scenes::LastComponentFunctions(scene.Property, 0.4);
    }
  }
  scene.Window->SetWindowName("vtkSAVR: components");
  vtkNew<vtkCallbackCommand> onKey;
  onKey->SetCallback(OnKey);
  onKey->SetClientData(scene.Property.GetPointer());
  return savr_scenes::Show(scene.Window, { scene.Mapper }, window,
    !rgba && components == 2 ? onKey.GetPointer() : nullptr);
}

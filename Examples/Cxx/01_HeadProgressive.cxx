// Example 1: the MRI head (vtkImageData) rendered with vtkSAVRVolumeMapper, refining
// progressively in an interactive window. Drag to rotate: while you drag, frames are single
// passes; when you let go, samples accumulate frame by frame until the image is final. Keys
// toggle features while it refines, and the mapper re-blends or starts over as each needs:
// h shading, g gradient opacity, i pre-integration.
//
//   savr_head [--headless] [--output savr_head.png] [--size 512] [--frames N] [--step S]
//             [--shade] [--gradient-opacity] [--preintegrate] [--tolerance E] [--nearest]
//
// --headless renders offscreen until refinement completes, prints each frame's time and the
// frame count, and writes the final image as PNG.

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkSAVRRefinementDriver.h"
#include "vtkSAVRVolumeMapper.h"

#include "vtkCallbackCommand.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindowInteractor.h"

#include <cstdlib>

namespace
{
struct Settings
{
  int Frames = 0;
  double Step = 0.0;
  double Tolerance = 0.0;
  bool Shade = false;
  bool GradientOpacity = false;
  bool PreIntegrate = false;
  bool Nearest = false;
};

// The keys: each toggles one setting of the property or the mapper.
struct Keys
{
  vtkVolumeProperty* Property;
  vtkSAVRVolumeMapper* Mapper;
};

void OnKey(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* keys = static_cast<Keys*>(clientData);
  auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
  vtkSAVRVolumeMapper* mapper = keys->Mapper;
  switch (interactor->GetKeyCode())
  {
    case 'h':
      keys->Property->SetShade(!keys->Property->GetShade());
      break;
    case 'g':
      keys->Property->SetDisableGradientOpacity(!keys->Property->GetDisableGradientOpacity());
      break;
    case 'i':
      mapper->SetPreIntegration(!mapper->GetPreIntegration());
      break;
    default:
      return;
  }
  interactor->Render();
}
} // namespace

int main(int argc, char* argv[])
{
  Settings settings;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_head: the MRI head rendered with vtkSAVRVolumeMapper, refining progressively in an\n"
    "interactive window (keys: h shading, g gradient opacity, i pre-integration).");
  savr_scenes::WindowOptions window(arguments, "savr_head.png");
  arguments.Option("--frames", &settings.Frames, "Frames to accumulate (0: from the data).");
  arguments.Option("--step", &settings.Step, "Base sample distance (0: the voxel spacing).");
  arguments.Option("--tolerance", &settings.Tolerance, "Stop refining below this error.");
  arguments.Flag("--shade", &settings.Shade, "Shade with the gradient.");
  arguments.Flag("--gradient-opacity", &settings.GradientOpacity, "Fade small gradients.");
  arguments.Flag("--preintegrate", &settings.PreIntegrate, "Pre-integrate sample pairs.");
  arguments.Flag("--nearest", &settings.Nearest, "Nearest-neighbour interpolation.");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkImageData> head = savr_scenes::Head();
  if (head->GetNumberOfPoints() == 0)
  {
    return EXIT_FAILURE;
  }

  // Skin and bone of a T1 MRI, lit when shaded; gradient opacity fades regions whose gradient
  // is below 25 levels per voxel, and is opaque from 85.
  vtkNew<vtkVolumeProperty> property;
  savr_scenes::HeadProperty(property);
  property->SetInterpolationType(
    settings.Nearest ? VTK_NEAREST_INTERPOLATION : VTK_LINEAR_INTERPOLATION);
  property->SetShade(settings.Shade);
  property->SetAmbient(0.3);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.2);
  property->SetSpecularPower(10.0);
  vtkNew<vtkPiecewiseFunction> gradientOpacity;
  gradientOpacity->AddPoint(0.0, 0.0);
  gradientOpacity->AddPoint(25.5, 0.0);
  gradientOpacity->AddPoint(84.15, 1.0);
  property->SetGradientOpacity(gradientOpacity);
  property->SetDisableGradientOpacity(!settings.GradientOpacity);

  // The mapper: base step and frame count default from the voxel spacing.
  vtkNew<vtkSAVRVolumeMapper> mapper;
  mapper->SetInputData(head);
  mapper->SetSampleDistance(settings.Step);
  mapper->SetMaximumNumberOfFrames(settings.Frames);
  mapper->SetPreIntegration(settings.PreIntegrate);
  mapper->SetErrorTolerance(settings.Tolerance);

  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.15);
  savr_scenes::FaceTheHead(renderer);
  vtkNew<vtkRenderWindow> renderWindow;
  renderWindow->SetSize(window.Size, window.Size);
  renderWindow->AddRenderer(renderer);
  renderWindow->SetWindowName("vtkSAVR: the MRI head");
  if (window.Headless)
  {
    return savr_scenes::RenderHeadless(renderWindow, { mapper }, window.Output);
  }

  // The interactor drags the camera; the driver re-renders on a timer while refinement is
  // incomplete, and switches the mapper to single passes while the user drags.
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(renderWindow);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  Keys keys{ property, mapper };
  vtkNew<vtkCallbackCommand> onKey;
  onKey->SetCallback(OnKey);
  onKey->SetClientData(&keys);
  interactor->AddObserver(vtkCommand::KeyPressEvent, onKey);
  vtkNew<vtkSAVRRefinementDriver> driver;
  driver->SetMapper(mapper);
  driver->SetInteractor(interactor);
  renderWindow->Render();
  interactor->Start();
  return EXIT_SUCCESS;
}

// Example 1: the MRI head (vtkImageData) rendered with vtkSAVRVolumeMapper, refining
// progressively in an interactive window. Drag to rotate: while you drag, frames are single
// passes; when you let go, samples accumulate frame by frame until the image is final.
//
//   savr_head [file.nii.gz] [--headless] [--output head.png] [--size 512] [--frames N] [--step S]
//             [--shade] [--preintegrate] [--tolerance E] [--blend
//             composite|mip|minip|average|additive]
//             [--crop] [--clip] [--nearest] [--parallel]
//
// --crop shows a fence of the head's middle thirds (VTK's cropping regions), --clip cuts the
// head with a plane through its centre, --parallel uses a parallel projection. In the window,
// keys toggle features while it refines: h shading, i pre-integration, x cropping, k the
// clipping plane, b the next blend mode.
//
// --headless renders offscreen until refinement completes, prints each frame's time and the
// frame count, and writes the final image as PNG.

#include "vtkSAVRRefinementDriver.h"
#include "vtkSAVRVolumeMapper.h"

#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char* argv[])
{
  std::string file = "/usr/share/mricron/templates/ch2.nii.gz"; // Debian package mricron-data
  std::string output = "savr_head.png";
  bool headless = false;
  int size = 512;
  int frames = 0;
  double step = 0.0;
  bool shade = false;
  bool preIntegrate = false;
  double tolerance = 0.0;
  std::string blend = "composite";
  bool crop = false;
  bool clip = false;
  bool nearest = false;
  bool parallel = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--headless")
      headless = true;
    else if (arg == "--output" && i + 1 < argc)
      output = argv[++i];
    else if (arg == "--size" && i + 1 < argc)
      size = std::atoi(argv[++i]);
    else if (arg == "--frames" && i + 1 < argc)
      frames = std::atoi(argv[++i]);
    else if (arg == "--step" && i + 1 < argc)
      step = std::atof(argv[++i]);
    else if (arg == "--shade")
      shade = true;
    else if (arg == "--preintegrate")
      preIntegrate = true;
    else if (arg == "--tolerance" && i + 1 < argc)
      tolerance = std::atof(argv[++i]);
    else if (arg == "--blend" && i + 1 < argc)
      blend = argv[++i];
    else if (arg == "--crop")
      crop = true;
    else if (arg == "--clip")
      clip = true;
    else if (arg == "--nearest")
      nearest = true;
    else if (arg == "--parallel")
      parallel = true;
    else if (arg[0] != '-')
      file = arg;
    else
    {
      std::fprintf(stderr, "unknown option %s\n", arg.c_str());
      return EXIT_FAILURE;
    }
  }

  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  if (reader->GetOutput()->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "cannot read %s\n", file.c_str());
    return EXIT_FAILURE;
  }

  // Transfer functions: skin and bone of a T1 MRI (8-bit values).
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
  color->AddRGBPoint(60.0, 0.75, 0.45, 0.35);
  color->AddRGBPoint(110.0, 0.95, 0.8, 0.7);
  color->AddRGBPoint(255.0, 1.0, 1.0, 0.95);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(40.0, 0.0);
  opacity->AddPoint(70.0, 0.05);
  opacity->AddPoint(120.0, 0.25);
  opacity->AddPoint(255.0, 0.6);
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationType(nearest ? VTK_NEAREST_INTERPOLATION : VTK_LINEAR_INTERPOLATION);
  property->SetShade(shade);
  property->SetAmbient(0.3);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.2);
  property->SetSpecularPower(10.0);

  // The mapper: base step and frame count default from the voxel spacing.
  vtkNew<vtkSAVRVolumeMapper> mapper;
  mapper->SetInputConnection(reader->GetOutputPort());
  mapper->SetSampleDistance(step);
  mapper->SetMaximumNumberOfFrames(frames);
  mapper->SetPreIntegration(preIntegrate);
  mapper->SetErrorTolerance(tolerance);
  const char* blendModes[] = { "composite", "mip", "minip", "average", "additive", "iso" };
  const int blendValues[] = { vtkVolumeMapper::COMPOSITE_BLEND,
    vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
    vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND,
    vtkVolumeMapper::ISOSURFACE_BLEND };
  int blendIndex = -1;
  for (int b = 0; b < 6; ++b)
  {
    blendIndex = blend == blendModes[b] ? b : blendIndex;
  }
  if (blendIndex < 0)
  {
    std::fprintf(stderr, "unknown blend mode %s\n", blend.c_str());
    return EXIT_FAILURE;
  }
  mapper->SetBlendMode(blendValues[blendIndex]);
  // The isosurface mode shows the surface of the value 120 (opacity 0.25 there).
  property->GetIsoSurfaceValues()->SetValue(0, 120.0);
  // Cropping: the middle third of every axis, shown as a fence.
  double bounds[6];
  reader->GetOutput()->GetBounds(bounds);
  double thirds[6];
  for (int a = 0; a < 3; ++a)
  {
    thirds[2 * a] = bounds[2 * a] + (bounds[2 * a + 1] - bounds[2 * a]) / 3.0;
    thirds[2 * a + 1] = bounds[2 * a] + 2.0 * (bounds[2 * a + 1] - bounds[2 * a]) / 3.0;
  }
  mapper->SetCroppingRegionPlanes(thirds);
  mapper->SetCroppingRegionFlagsToFence();
  mapper->SetCropping(crop);
  // Clipping: a plane through the centre, keeping the front half.
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(
    (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2);
  plane->SetNormal(0.0, -1.0, 0.0);
  if (clip)
  {
    mapper->AddClippingPlane(plane);
  }

  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.1, 0.1, 0.15);
  // Face the head: +y is anterior and +z superior in the image's index space.
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 1, 0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  camera->Azimuth(35.0);
  camera->Elevation(10.0);
  camera->SetParallelProjection(parallel);
  renderer->ResetCamera();

  vtkNew<vtkRenderWindow> window;
  window->SetSize(size, size);
  window->AddRenderer(renderer);
  window->SetWindowName("vtkSAVR: MRI head");

  if (headless)
  {
    window->SetOffScreenRendering(1);
    std::printf("frame  accumulated  ms      memory_MiB  error_estimate\n");
    int render = 0;
    do
    {
      window->Render();
      ++render;
      std::printf("%5d  %11d  %7.1f  %10.2f  %14.2e\n", render,
        mapper->GetNumberOfFramesAccumulated(), 1e3 * mapper->GetLastFrameTime(),
        mapper->GetMemoryInUse() / 1048576.0, mapper->GetErrorEstimate());
    } while (!mapper->GetRefinementComplete() && render < 100000);
    std::printf("refinement complete: %d frames at base step %g (effective step %g)\n",
      mapper->GetNumberOfFramesAccumulated(), mapper->GetEffectiveSampleDistance(),
      mapper->GetEffectiveSampleDistance() / mapper->GetNumberOfFramesAccumulated());
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(output.c_str());
    writer->SetInputConnection(grab->GetOutputPort());
    writer->Write();
    std::printf("wrote %s\n", output.c_str());
    return EXIT_SUCCESS;
  }

  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  interactor->SetInteractorStyle(style);
  window->Render();

  // Keys toggle features; the mapper re-blends or starts over as each needs.
  vtkNew<vtkCallbackCommand> keys;
  struct KeyState
  {
    vtkSAVRVolumeMapper* Mapper;
    vtkVolumeProperty* Property;
    vtkPlane* Plane;
    const int* Blends;
    int Blend;
  } keyState{ mapper, property, plane, blendValues, blendIndex };
  keys->SetClientData(&keyState);
  keys->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void*)
    {
      auto* state = static_cast<KeyState*>(clientData);
      auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
      switch (interactor->GetKeyCode())
      {
        case 'h':
          state->Property->SetShade(!state->Property->GetShade());
          break;
        case 'i':
          state->Mapper->SetPreIntegration(!state->Mapper->GetPreIntegration());
          break;
        case 'x':
          state->Mapper->SetCropping(!state->Mapper->GetCropping());
          break;
        case 'k':
          if (state->Mapper->GetNumberOfClippingPlanes() > 0)
          {
            state->Mapper->RemoveAllClippingPlanes();
          }
          else
          {
            state->Mapper->AddClippingPlane(state->Plane);
          }
          break;
        case 'b':
          state->Blend = (state->Blend + 1) % 6;
          state->Mapper->SetBlendMode(state->Blends[state->Blend]);
          break;
        default:
          return;
      }
      interactor->Render();
    });
  interactor->AddObserver(vtkCommand::KeyPressEvent, keys);

  // Re-renders on a timer while refinement is incomplete; single passes while dragging.
  vtkNew<vtkSAVRRefinementDriver> driver;
  driver->SetMapper(mapper);
  driver->SetInteractor(interactor);
  interactor->Start();
  return EXIT_SUCCESS;
}

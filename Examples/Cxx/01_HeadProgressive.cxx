// Example 1: the MRI head (vtkImageData) rendered with vtkSAVRVolumeMapper, refining
// progressively in an interactive window. Drag to rotate: while you drag, frames are single
// passes; when you let go, samples accumulate frame by frame until the image is final.
//
//   savr_head [file.nii.gz] [--headless] [--output head.png] [--size 512] [--frames N] [--step S]
//             [--shade] [--preintegrate] [--tolerance E]
//
// --headless renders offscreen until refinement completes, prints each frame's time and the
// frame count, and writes the final image as PNG.

#include "vtkSAVRRefinementDriver.h"
#include "vtkSAVRVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
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
  property->SetInterpolationTypeToLinear();
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

  // Re-renders on a timer while refinement is incomplete; single passes while dragging.
  vtkNew<vtkSAVRRefinementDriver> driver;
  driver->SetMapper(mapper);
  driver->SetInteractor(interactor);
  interactor->Start();
  return EXIT_SUCCESS;
}

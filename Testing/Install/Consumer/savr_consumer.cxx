// Renders VTK's wavelet with an installed vtkSAVR, headless, until refinement completes, and fails
// when the image shows nothing but the background.
#include "vtkSAVRVolumeMapper.h"

#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkRTAnalyticSource.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <cstdlib>
#include <iostream>

int main()
{
  vtkNew<vtkRTAnalyticSource> wavelet;
  wavelet->SetWholeExtent(-10, 10, -10, 10, -10, 10);

  vtkNew<vtkSAVRVolumeMapper> mapper;
  mapper->SetInputConnection(wavelet->GetOutputPort());

  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(37.0, 0.2, 0.3, 0.9);
  color->AddRGBPoint(276.0, 0.9, 0.4, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(37.0, 0.0);
  opacity->AddPoint(276.0, 0.6);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->GetProperty()->SetColor(color);
  volume->GetProperty()->SetScalarOpacity(opacity);
  volume->GetProperty()->SetInterpolationTypeToLinear();

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(volume);
  renderer->SetBackground(0.0, 0.0, 0.0);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(96, 96);
  window->AddRenderer(renderer);

  // Each Render() is one refinement frame; the cap only guards against a mapper that never ends.
  int renders = 0;
  for (; !mapper->GetRefinementComplete() && renders < 64; ++renders)
  {
    window->Render();
  }

  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetRGBACharPixelData(0, 0, 95, 95, /*front=*/0, pixels);
  vtkIdType lit = 0;
  for (vtkIdType i = 0; i < pixels->GetNumberOfTuples(); ++i)
  {
    const bool black = pixels->GetTypedComponent(i, 0) == 0 &&
                       pixels->GetTypedComponent(i, 1) == 0 && pixels->GetTypedComponent(i, 2) == 0;
    lit += black ? 0 : 1;
  }
  std::cout << renders << " renders, " << mapper->GetNumberOfFramesAccumulated()
            << " frames accumulated, " << lit << " of " << pixels->GetNumberOfTuples()
            << " pixels not background\n";
  const bool drawn = lit > pixels->GetNumberOfTuples() / 10;
  return mapper->GetRefinementComplete() && drawn ? EXIT_SUCCESS : EXIT_FAILURE;
}

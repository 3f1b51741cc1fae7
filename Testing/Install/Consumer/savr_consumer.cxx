// Renders VTK's wavelet with an installed vtkSAVR, headless, until refinement completes, and fails
// when the image shows nothing but the background; then samples the wavelet along a ray with the
// engine's sampler (installed headers, vtkSAVR::savrCore), and fails unless it reads the voxels.
#include "vtkSAVRImageSampler.h"
#include "vtkSAVRVolumeMapper.h"

#include "sampler/Sampler.h"

#include <vtkColorTransferFunction.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRTAnalyticSource.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>

namespace
{
// Three samples one voxel apart along x, from voxel (3, -2, 5): they must equal those voxels.
bool SamplerReadsTheVoxels(vtkImageData* image)
{
  vtkNew<vtkSAVRImageSampler> adaptor;
  if (!adaptor->Build(image, image->GetPointData()->GetScalars(), /*cellData=*/false,
        /*volumeMatrix=*/nullptr, VTK_LINEAR_INTERPOLATION))
  {
    std::cerr << "vtkSAVRImageSampler::Build: " << adaptor->GetErrorMessage() << "\n";
    return false;
  }
  const std::shared_ptr<const savr::Sampler> sampler = adaptor->GetSampler();
  savr::Ray ray;
  ray.Origin = Eigen::Vector3d(3.0, -2.0, 5.0);
  ray.Direction = Eigen::Vector3d::UnitX();
  float values[3];
  sampler->SampleRay(ray, 0.0, 1.0, 3, values);
  bool same = true;
  for (int i = 0; i < 3; ++i)
  {
    int voxel[3] = { 3 + i, -2, 5 };
    const double expected = image->GetScalarComponentAsDouble(voxel[0], voxel[1], voxel[2], 0);
    std::cout << "sample " << i << ": " << values[i] << ", voxel " << expected << "\n";
    same = same && std::abs(values[i] - expected) <= 1e-4 * std::abs(expected);
  }
  return same;
}
}

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
  const bool sampled = SamplerReadsTheVoxels(wavelet->GetOutput());
  return mapper->GetRefinementComplete() && drawn && sampled ? EXIT_SUCCESS : EXIT_FAILURE;
}

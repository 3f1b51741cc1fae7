#pragma once
// Scenes shared by the rendering tests and the benchmark: the wavelet and the MRI head, their
// transfer functions, and image checks that do not depend on a baseline.

#include "vtkSAVRVolumeMapper.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <sys/stat.h>
#include <vector>

namespace savr_scenes
{

/// The MRI head of Debian's mricron-data package, or SAVR_HEAD_FILE when set.
inline std::string HeadFile()
{
  const char* overridden = std::getenv("SAVR_HEAD_FILE");
  return overridden ? overridden : "/usr/share/mricron/templates/ch2.nii.gz";
}

inline vtkSmartPointer<vtkImageData> Wavelet(int halfExtent = 20)
{
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(-halfExtent, halfExtent, -halfExtent, halfExtent, -halfExtent, halfExtent);
  source->Update();
  return source->GetOutput();
}

inline vtkSmartPointer<vtkImageData> Head()
{
  vtkNew<vtkNIFTIImageReader> reader;
  reader->SetFileName(HeadFile().c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  if (image->GetNumberOfPoints() == 0)
  {
    std::cerr << "cannot read the MRI head from " << HeadFile() << "\n";
  }
  return image;
}

inline void WaveletProperty(vtkVolumeProperty* property)
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(37.0, 0.2, 0.2, 0.9);
  color->AddRGBPoint(150.0, 0.9, 0.9, 0.3);
  color->AddRGBPoint(276.0, 0.9, 0.2, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(37.0, 0.0);
  opacity->AddPoint(120.0, 0.02);
  opacity->AddPoint(200.0, 0.3);
  opacity->AddPoint(276.0, 0.8);
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(1.0);
}

inline void HeadProperty(vtkVolumeProperty* property)
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
  color->AddRGBPoint(60.0, 0.75, 0.45, 0.35);
  color->AddRGBPoint(110.0, 0.95, 0.8, 0.7);
  color->AddRGBPoint(255.0, 1.0, 1.0, 0.95);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(40.0, 0.0);
  opacity->AddPoint(70.0, 0.05);
  opacity->AddPoint(120.0, 0.25);
  opacity->AddPoint(255.0, 0.6);
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(1.0);
}

/// Looks at the face of the MRI head (+y is anterior, +z superior in its index space).
inline void FaceTheHead(vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 1, 0);
  camera->SetViewUp(0, 0, 1);
  camera->Azimuth(35.0);
  camera->Elevation(10.0);
  renderer->ResetCamera();
}

/// Window, renderer and volume with a SAVR mapper, camera framing the data.
struct Scene
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkSAVRVolumeMapper> Mapper;

  Scene(vtkDataObject* data, int width, int height)
  {
    // Windows stay open until the process ends: closing X windows and opening new ones in quick
    // succession makes Xvfb refuse a connection now and then.
    static std::vector<vtkSmartPointer<vtkRenderWindow>> keepOpen;
    keepOpen.emplace_back(this->Window.GetPointer());
    this->Window->SetSize(width, height);
    this->Window->SetMultiSamples(0);
    this->Window->AddRenderer(this->Renderer);
    this->Renderer->SetBackground(0.1, 0.1, 0.15);
    this->Mapper->SetInputDataObject(data);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(30.0);
    this->Renderer->GetActiveCamera()->Elevation(20.0);
    this->Renderer->ResetCameraClippingRange();
  }

  /// Renders until refinement completes (or `maxRenders`); returns the renders made.
  int RenderUntilComplete(int maxRenders = 4096)
  {
    int renders = 0;
    do
    {
      this->Window->Render();
      ++renders;
    } while (!this->Mapper->GetRefinementComplete() && renders < maxRenders);
    return renders;
  }
};

/// The window's pixels as RGB bytes.
inline vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff(); // a render here would be one more refinement frame
  grab->Update();
  vtkSmartPointer<vtkImageData> copy = vtkSmartPointer<vtkImageData>::New();
  copy->DeepCopy(grab->GetOutput());
  return copy;
}

inline unsigned char* Bytes(vtkImageData* image)
{
  return static_cast<unsigned char*>(image->GetPointData()->GetScalars()->GetVoidPointer(0));
}

/// Fraction of pixels that differ from the background colour by more than 8 levels.
inline double CoveredFraction(vtkImageData* image, const double background[3])
{
  const vtkIdType n = image->GetNumberOfPoints();
  const unsigned char* p = Bytes(image);
  vtkIdType covered = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      if (std::abs(p[3 * i + c] - background[c] * 255.0) > 8.0)
      {
        ++covered;
        break;
      }
    }
  }
  return n > 0 ? static_cast<double>(covered) / n : 0.0;
}

struct Difference
{
  double Max = 0.0;  // largest channel difference, in levels of 255
  double Mean = 0.0; // mean channel difference, in levels of 255
};

inline Difference Compare(vtkImageData* a, vtkImageData* b)
{
  Difference d;
  const vtkIdType n = a->GetNumberOfPoints() * 3;
  if (n != b->GetNumberOfPoints() * 3)
  {
    d.Max = d.Mean = 255.0;
    return d;
  }
  const unsigned char* pa = Bytes(a);
  const unsigned char* pb = Bytes(b);
  double sum = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double e = std::abs(static_cast<int>(pa[i]) - static_cast<int>(pb[i]));
    d.Max = std::max(d.Max, e);
    sum += e;
  }
  d.Mean = n > 0 ? sum / n : 0.0;
  return d;
}

} // namespace savr_scenes

namespace savr_scenes
{

/// VTK's fixed-point mapper's image of `data` with the wavelet's transfer function, seen by
/// `camera`, at a fine step (0.05) and full image resolution; `configure` may set up the mapper
/// further (cropping, clipping planes, blend mode) and `property` the volume property.
inline vtkSmartPointer<vtkImageData> FixedPointImage(vtkImageData* data, vtkCamera* camera,
  int width, int height, const std::function<void(vtkVolumeMapper*)>& configure = nullptr,
  const std::function<void(vtkVolumeProperty*)>& property = nullptr)
{
  Scene peer(data, width, height);
  WaveletProperty(peer.Property);
  if (property)
  {
    property(peer.Property);
  }
  vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
  fixedPoint->SetInputData(data);
  fixedPoint->AutoAdjustSampleDistancesOff();
  fixedPoint->SetSampleDistance(0.05);
  fixedPoint->SetImageSampleDistance(1.0);
  if (configure)
  {
    configure(fixedPoint);
  }
  peer.Volume->SetMapper(fixedPoint);
  peer.Renderer->SetActiveCamera(camera);
  peer.Window->Render();
  return Capture(peer.Window);
}

/// Bytes the mapper's stored samples take, per stored sample.
inline double BytesPerStoredSample(vtkSAVRVolumeMapper* mapper)
{
  return static_cast<double>(mapper->GetMemoryInUse()) / mapper->GetNumberOfStoredSamples();
}

/// Counts failed expectations and says which.
struct Expectations
{
  int Failures = 0;
  void operator()(bool condition, const std::string& what)
  {
    if (!condition)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++this->Failures;
    }
  }
};

/// Strict comparison of the window with the baseline named by `-V` (VTK's own comparison
/// forgives differences of up to 16 levels per channel, which would hide a missing refinement):
/// at most `maxLevels` in any channel and `meanLevels` on average. Without a baseline, writes the
/// image into the `-T` folder (to be reviewed and copied into Testing/Data/Baseline) and fails.
inline bool MatchesBaseline(
  vtkRenderWindow* window, int argc, char* argv[], double maxLevels = 3.0, double meanLevels = 0.05)
{
  std::string baseline;
  std::string output = ".";
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == "-V")
      baseline = argv[i + 1];
    if (std::string(argv[i]) == "-T")
      output = argv[i + 1];
  }
  vtkSmartPointer<vtkImageData> image = Capture(window);
  struct stat info;
  if (baseline.empty() || stat(baseline.c_str(), &info) != 0)
  {
    const std::string name = baseline.substr(baseline.find_last_of('/') + 1);
    const std::string written = output + "/" + (name.empty() ? std::string("image.png") : name);
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(written.c_str());
    writer->SetInputData(image);
    writer->Write();
    std::cerr << "no baseline '" << baseline << "'; wrote " << written << "\n";
    return false;
  }
  vtkNew<vtkPNGReader> reader;
  reader->SetFileName(baseline.c_str());
  reader->Update();
  vtkImageData* expected = reader->GetOutput();
  if (expected->GetNumberOfScalarComponents() != 3)
  {
    std::cerr << "baseline " << baseline << " is not RGB\n";
    return false;
  }
  const Difference d = Compare(image, expected);
  std::cout << "against baseline: max " << d.Max << " mean " << d.Mean << " levels\n";
  if (d.Max > maxLevels || d.Mean > meanLevels)
  {
    const std::string written = output + "/" + baseline.substr(baseline.find_last_of('/') + 1);
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(written.c_str());
    writer->SetInputData(image);
    writer->Write();
    std::cerr << "differs from the baseline; wrote " << written << "\n";
    return false;
  }
  return true;
}

} // namespace savr_scenes

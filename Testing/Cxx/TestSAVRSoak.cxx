// A long session through the public API: 300 renders of a small window with camera moves,
// transfer-function edits and data changes (new inputs and values edited in place) interleaved
// with accumulation. The resident memory after a warm-up must stay within a bound: a leak of
// frames, images or sampler structures per reset shows as steady growth long before it is
// noticed in an application.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <unistd.h>

namespace
{
savr_scenes::Expectations Expect;

constexpr int Renders = 300;
constexpr int WarmUpRenders = 60;
// Measured growth after the warm-up is about 1 MiB. The bound leaves room for allocator and
// driver noise; a leak of one 128x128 float RGBA image (256 KiB) at each of the about 200 resets
// after the warm-up still exceeds it.
constexpr double GrowthBoundMiB = 20.0;

double ResidentMiB()
{
  std::ifstream statm("/proc/self/statm");
  long pages = 0;
  long resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) /
         (1024.0 * 1024.0);
}

// Scales the wavelet's values about their middle, so that the data (and its range) change while
// the array stays the same object.
void EditValues(vtkImageData* data, double factor)
{
  vtkDataArray* values = data->GetPointData()->GetScalars();
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
  {
    values->SetTuple1(i, 160.0 + (values->GetTuple1(i) - 160.0) * factor);
  }
  values->Modified();
}
} // namespace

int TestSAVRSoak(int, char*[])
{
  vtkSmartPointer<vtkImageData> large = savr_scenes::Wavelet(20);
  vtkSmartPointer<vtkImageData> small = savr_scenes::Wavelet(12);
  savr_scenes::Scene scene(large, 128, 128);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(8);

  double residentAfterWarmUp = 0.0;
  double residentPeak = 0.0;
  for (int render = 0; render < Renders; ++render)
  {
    // A mix of every kind of change, at periods that do not divide each other, so that each
    // happens mid-accumulation, after completion and together with the others.
    if (render % 3 == 0)
    {
      scene.Renderer->GetActiveCamera()->Azimuth(7.0);
      scene.Renderer->ResetCameraClippingRange();
    }
    if (render % 5 == 1)
    {
      // Toggles one opacity point and one colour, so the functions do not grow.
      if ((render / 5) % 2 == 0)
      {
        scene.Property->GetScalarOpacity()->AddPoint(170.0, 0.7);
      }
      else
      {
        scene.Property->GetScalarOpacity()->RemovePoint(170.0);
      }
      scene.Property->GetRGBTransferFunction()->AddRGBPoint(150.0, 0.2 * (render % 4), 0.8, 0.3);
    }
    if (render % 17 == 2)
    {
      scene.Mapper->SetInputData((render / 17) % 2 == 0 ? small : large);
    }
    if (render % 23 == 4)
    {
      EditValues(large, (render / 23) % 2 == 0 ? 0.9 : 1.0 / 0.9);
    }
    scene.Window->Render();

    const double resident = ResidentMiB();
    if (render + 1 == WarmUpRenders)
    {
      residentAfterWarmUp = resident;
    }
    residentPeak = resident > residentPeak ? resident : residentPeak;
  }
  scene.RenderUntilComplete();
  const double growth = ResidentMiB() - residentAfterWarmUp;
  std::printf("resident memory after %d renders %.1f MiB, peak %.1f MiB, growth after the "
              "warm-up %.2f MiB (bound %.0f MiB)\n",
    WarmUpRenders, residentAfterWarmUp, residentPeak, growth, GrowthBoundMiB);
  Expect(growth < GrowthBoundMiB, "resident memory stays bounded over a long session");
  Expect(residentPeak - residentAfterWarmUp < GrowthBoundMiB, "and so does its peak");
  Expect(scene.Mapper->GetRefinementComplete(), "refinement still completes at the end");
  Expect(savr_scenes::CoveredFraction(
           savr_scenes::Capture(scene.Window), scene.Renderer->GetBackground()) > 0.1,
    "the last image is drawn");
  return Expect.Failures == 0 ? 0 : 1;
}

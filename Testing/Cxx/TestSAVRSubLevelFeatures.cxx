// Transfer functions with features narrower than one level of 8-bit data: an opacity spike a
// thousandth of the value range wide, between two integer levels. The 8-bit volume must converge
// to the image of the same values stored as floats (whose samples are not rounded to integer
// levels), with and without pre-integration; soft transfer functions keep one byte per stored
// sample; an edit that needs finer samples starts over, one that does not re-blends.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <cstdio>

namespace
{
savr_scenes::Expectations Expect;

constexpr int kPoints = 40;
constexpr double kSpike = 100.4;          // between the levels 100 and 101
constexpr double kSpikeHalfWidth = 0.128; // 1e-3 of the range 0..255 wide

// A ball whose values fall from 250 at its centre to 0 at its rim: every level is crossed.
vtkSmartPointer<vtkImageData> Ball(bool floats)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(kPoints, kPoints, kPoints);
  vtkSmartPointer<vtkDataArray> values;
  if (floats)
  {
    values = vtkSmartPointer<vtkFloatArray>::New();
  }
  else
  {
    values = vtkSmartPointer<vtkUnsignedCharArray>::New();
  }
  values->SetName("ball");
  values->SetNumberOfTuples(static_cast<vtkIdType>(kPoints) * kPoints * kPoints);
  const double c = 0.5 * (kPoints - 1);
  vtkIdType id = 0;
  for (int k = 0; k < kPoints; ++k)
    for (int j = 0; j < kPoints; ++j)
      for (int i = 0; i < kPoints; ++i)
      {
        const double r = std::sqrt((i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c));
        values->SetTuple1(id++, std::round(250.0 * std::max(0.0, 1.0 - r / c)));
      }
  image->GetPointData()->SetScalars(values);
  return image;
}

void SoftFunctions(vtkVolumeProperty* property, double shift)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(60.0 + shift, 0.0);
  opacity->AddPoint(250.0, 0.3);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.2, 0.3, 0.9);
  color->AddRGBPoint(250.0, 1.0, 0.8, 0.3);
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
}

void SpikeFunctions(vtkVolumeProperty* property, double at)
{
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(20.0, 0.0005);
  opacity->AddPoint(at - kSpikeHalfWidth, 0.0005);
  opacity->AddPoint(at, 1.0);
  opacity->AddPoint(at + kSpikeHalfWidth, 0.0005);
  opacity->AddPoint(255.0, 0.0005);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.2, 0.3, 0.9);
  color->AddRGBPoint(255.0, 1.0, 0.8, 0.3);
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetScalarOpacityUnitDistance(0.02);
}

// The converged image of the ball, as RGBA floats.
std::vector<float> Converged(bool floats, bool preIntegration)
{
  vtkSmartPointer<vtkImageData> data = Ball(floats);
  savr_scenes::Scene scene(data, 160, 160);
  SpikeFunctions(scene.Property, kSpike);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  scene.Mapper->SetPreIntegration(preIntegration);
  scene.Mapper->SetAutoPreIntegration(false); // each way as asked, on both data
  scene.RenderUntilComplete();
  return savr_scenes::FloatRGBA(savr_scenes::Capture(scene.Window));
}

double BytesPerSample(vtkSAVRVolumeMapper* mapper)
{
  return static_cast<double>(mapper->GetMemoryInUse()) /
         std::max<vtkTypeUInt64>(mapper->GetNumberOfStoredSamples(), 1);
}
} // namespace

int TestSAVRSubLevelFeatures(int, char*[])
{
  // The spike converges on 8-bit data as on the same values stored as floats.
  for (const bool preIntegration : { false, true })
  {
    const std::vector<float> reference = Converged(true, preIntegration);
    const std::vector<float> bytes = Converged(false, preIntegration);
    const savr_scenes::ImageError error = savr_scenes::ErrorAgainst(bytes, reference, false);
    std::printf("spike on 8-bit data, pre-integration %s: RMSE %.5f, largest %.4f against the "
                "float data\n",
      preIntegration ? "on" : "off", error.Rmse, error.Max);
    Expect(error.Rmse < 0.01, "a spike between two levels of 8-bit data is seen");
  }

  // Soft functions: one byte per sample. An edit to a spike starts over with two bytes; edits
  // that need no finer samples re-blend.
  vtkSmartPointer<vtkImageData> data = Ball(false);
  savr_scenes::Scene scene(data, 120, 120);
  SoftFunctions(scene.Property, 0.0);
  scene.Mapper->SetMaximumNumberOfFrames(4);
  scene.RenderUntilComplete();
  std::printf("soft: %.3f bytes per stored sample\n", BytesPerSample(scene.Mapper));
  Expect(BytesPerSample(scene.Mapper) == 1.0, "soft functions on 8-bit data: one byte a sample");

  const vtkTypeUInt64 taken = scene.Mapper->GetNumberOfSamplesTaken();
  SoftFunctions(scene.Property, 3.0);
  scene.Window->Render();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 4 &&
           scene.Mapper->GetNumberOfSamplesTaken() == taken,
    "a soft edit re-blends");

  SpikeFunctions(scene.Property, kSpike);
  scene.Window->Render();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 1, "an edit to a spike starts over");
  scene.RenderUntilComplete();
  std::printf("spike: %.3f bytes per stored sample\n", BytesPerSample(scene.Mapper));
  Expect(BytesPerSample(scene.Mapper) == 2.0, "a spike between levels: two bytes a sample");

  const vtkTypeUInt64 spikeTaken = scene.Mapper->GetNumberOfSamplesTaken();
  SpikeFunctions(scene.Property, kSpike + 20.3);
  scene.Window->Render();
  SoftFunctions(scene.Property, 0.0);
  scene.Window->Render();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 4 &&
           scene.Mapper->GetNumberOfSamplesTaken() == spikeTaken,
    "edits that need no finer samples than those stored re-blend");
  return Expect.Failures == 0 ? 0 : 1;
}

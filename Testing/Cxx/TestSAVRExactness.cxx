// What the README promises from the public API: after K frames (a power of two) at
// SampleDistance s the image equals one frame at SampleDistance s / K, to float round-off. Each
// pixel's samples lie on a lattice anchored at a phase of the pixel's own measured in the
// default step, whatever the step: K frames at s fill the lattice at s / K that one frame at
// s / K takes. Checked with a transfer function with a sharp edge (where a lattice at another
// phase differs by up to a whole level range), at the default step, at a step that is not a
// power of two of it, and at a coarser one, on image data and on a tetrahedral mesh; and with
// K frames against K / 2 frames at half the step.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkColorTransferFunction.h"
#include "vtkImageData.h"
#include "vtkPiecewiseFunction.h"
#include "vtkUnstructuredGrid.h"

#include <cstdio>
#include <string>

namespace
{
savr_scenes::Expectations Expect;

constexpr int kSize = 160;

// Opacity jumps from nearly nothing to a lot over a hundredth of the range: where a ray's
// samples fall against the jump decides the pixel.
void SharpProperty(vtkVolumeProperty* property, const double range[2])
{
  const double edge = range[0] + 0.55 * (range[1] - range[0]);
  const double width = 0.01 * (range[1] - range[0]);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(edge, 0.002);
  opacity->AddPoint(edge + width, 0.8);
  opacity->AddPoint(range[1], 0.8);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(range[0], 0.1, 0.2, 0.9);
  color->AddRGBPoint(edge, 0.9, 0.9, 0.2);
  color->AddRGBPoint(range[1], 1.0, 0.3, 0.1);
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(0.5);
}

vtkSmartPointer<vtkImageData> Refined(vtkDataSet* data, double step, int frames)
{
  savr_scenes::Scene scene(data, kSize, kSize);
  double range[2];
  data->GetScalarRange(range);
  SharpProperty(scene.Property, range);
  scene.Mapper->SetSampleDistance(step);
  scene.Mapper->SetMaximumNumberOfFrames(frames);
  scene.RenderUntilComplete();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == frames,
    "refinement accumulated " + std::to_string(frames) + " frames");
  return savr_scenes::Capture(scene.Window);
}

void CheckSteps(const char* name, vtkDataSet* data, double defaultStep)
{
  for (const double factor : { 1.0, 0.7, 2.0 })
  {
    const double step = factor * defaultStep;
    vtkSmartPointer<vtkImageData> fine = Refined(data, step / 4.0, 1);
    for (const int frames : { 2, 4 })
    {
      vtkSmartPointer<vtkImageData> refined = Refined(data, step * frames / 4.0, frames);
      const savr_scenes::Difference d = savr_scenes::Compare(refined, fine);
      std::printf("%s, %d frames at %.3f x the default step / %d against one frame at / 4: max "
                  "%.0f levels, mean %.4f\n",
        name, frames, factor, 4 / frames, d.Max, d.Mean);
      Expect(d.Max <= 1.0 && d.Mean <= 0.01, std::string(name) + ": " + std::to_string(frames) +
                                               " frames equal one frame at the step / " +
                                               std::to_string(frames));
    }
    // Not equal to a blank: the edge shows.
    const double background[3] = { 0.1, 0.1, 0.15 }; // the scenes' background
    Expect(savr_scenes::CoveredFraction(fine, background) > 0.2, "the volume covers the view");
  }
}
} // namespace

int TestSAVRExactness(int, char*[])
{
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet();
  CheckSteps("wavelet", wavelet, wavelet->GetSpacing()[0]);

  vtkSmartPointer<vtkUnstructuredGrid> mesh = savr_scenes::TetrahedralWavelet(24);
  savr_scenes::Scene probe(mesh, 8, 8);
  probe.Renderer->ResetCamera();
  probe.Window->Render();
  CheckSteps("tetrahedral wavelet", mesh, probe.Mapper->GetEffectiveSampleDistance());
  return Expect.Failures == 0 ? 0 : 1;
}

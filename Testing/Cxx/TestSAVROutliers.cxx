// Values beyond what the transfer functions tell apart: the codes cover the functions' nodes,
// and a sample beyond them takes their end's code. An outlier a million times the data, or
// densities over fifteen decades, then cost no precision where the image has detail, and the
// image is the one the data without them gives. Edits of the functions that widen their domain,
// or narrow it to a few of the codes, sample again; others re-blend.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSAVRParticleSampler.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

namespace
{
constexpr int kSize = 128;
const double kBackground[3] = { 0.1, 0.1, 0.15 };

// A 64^3 Gaussian blob in [0, 1]; `outlier`, when not 0, in one voxel near a corner (where the
// blob is about 0).
vtkSmartPointer<vtkImageData> Blob(double outlier)
{
  constexpr int n = 64;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  vtkNew<vtkFloatArray> values;
  values->SetName("blob");
  values->SetNumberOfTuples(vtkIdType(n) * n * n);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
      {
        const double c = 0.5 * (n - 1);
        const double r2 = (i - c) * (i - c) + (j - c) * (j - c) + (k - c) * (k - c);
        values->SetValue(i + n * (j + vtkIdType(n) * k), static_cast<float>(std::exp(-r2 / 288.0)));
      }
  if (outlier != 0.0)
  {
    values->SetValue(3 + n * (3 + vtkIdType(n) * 3), static_cast<float>(outlier));
  }
  image->GetPointData()->SetScalars(values);
  return image;
}

vtkSmartPointer<vtkImageData> Refined(savr_scenes::Scene& s)
{
  s.RenderUntilComplete();
  return savr_scenes::Capture(s.Window);
}

void SetUp(savr_scenes::Scene& s, double top)
{
  savr_scenes::SpreadProperty(s.Property, std::array<double, 2>{ 0.0, top }.data());
  s.Mapper->SetMaximumNumberOfFrames(8);
  s.Renderer->GetActiveCamera()->Azimuth(30.0);
  s.Renderer->GetActiveCamera()->Elevation(20.0);
  s.Renderer->ResetCameraClippingRange();
}

void Outlier(savr_scenes::Expectations& expect)
{
  savr_scenes::Scene clean(Blob(0.0), kSize, kSize);
  SetUp(clean, 1.0);
  vtkSmartPointer<vtkImageData> withoutOutlier = Refined(clean);
  savr_scenes::Scene s(Blob(1e6), kSize, kSize);
  SetUp(s, 1.0);
  vtkSmartPointer<vtkImageData> withOutlier = Refined(s);

  const double covered = savr_scenes::CoveredFraction(withOutlier, kBackground);
  const savr_scenes::Difference same = savr_scenes::Compare(withOutlier, withoutOutlier);
  // The independent expectation: VTK's fixed-point mapper on the data without the outlier.
  const auto fixedPoint = [&](vtkImageData* data)
  {
    return savr_scenes::FixedPointImage(data, s.Renderer->GetActiveCamera(), kSize, kSize, nullptr,
      [](vtkVolumeProperty* p) {
        savr_scenes::SpreadProperty(p, std::array<double, 2>{ 0.0, 1.0 }.data());
      });
  };
  const savr_scenes::Difference peer = savr_scenes::Compare(withOutlier, fixedPoint(Blob(0.0)));
  const double peerCovered = savr_scenes::CoveredFraction(fixedPoint(Blob(1e6)), kBackground);
  std::printf("outlier 1e6: covered %.3f; vs without it: mean %.3f, max %.0f levels; vs the "
              "fixed-point mapper without it: mean %.2f levels (it covers %.3f with it)\n",
    covered, same.Mean, same.Max, peer.Mean, peerCovered);
  expect(covered > 0.1, "a blob with an outlier is drawn");
  expect(same.Mean < 0.1, "a blob with an outlier is drawn as it is without");
  expect(
    peer.Mean < 3.0, "a blob with an outlier is drawn as the fixed-point mapper draws it without");

  // As ParaView first sets them: functions over the data's range, then rescaled to the blob's.
  savr_scenes::Scene edited(Blob(1e6), kSize, kSize);
  SetUp(edited, 1e6);
  edited.Window->Render();
  edited.Window->Render();
  savr_scenes::SpreadProperty(edited.Property, std::array<double, 2>{ 0.0, 1.0 }.data());
  edited.Window->Render();
  const int afterNarrowing = edited.Mapper->GetNumberOfFramesAccumulated();
  const savr_scenes::Difference rescaled = savr_scenes::Compare(Refined(edited), withOutlier);
  std::printf("narrowed from [0, 1e6] to [0, 1]: frames %d after, then vs the blob: mean %.3f\n",
    afterNarrowing, rescaled.Mean);
  expect(afterNarrowing == 1, "functions narrowed a million times sample again");
  expect(rescaled.Mean < 0.05, "functions narrowed to the blob draw it as set from the start");

  // A colour edit within the domain re-blends; a wider domain samples again.
  const int frames = edited.Mapper->GetNumberOfFramesAccumulated();
  edited.Property->GetRGBTransferFunction(0)->AddRGBPoint(0.5, 0.2, 0.9, 0.3);
  edited.Window->Render();
  const int afterRecolour = edited.Mapper->GetNumberOfFramesAccumulated();
  savr_scenes::SpreadProperty(edited.Property, std::array<double, 2>{ 0.0, 2.0 }.data());
  edited.Window->Render();
  const int afterWidening = edited.Mapper->GetNumberOfFramesAccumulated();
  std::printf("frames %d; after a colour edit %d; after widening to [0, 2] %d\n", frames,
    afterRecolour, afterWidening);
  expect(afterRecolour >= frames, "a colour edit within the domain re-blends");
  expect(afterWidening == 1, "a wider domain samples again");
}

// A halo of particles a unit apart, and within it, when `decades` > 0, cores each ten times
// denser than the last, radii in proportion: summed kernels (a density) up to 10^(3 decades).
vtkSmartPointer<vtkPolyData> NestedClusters(int decades)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> radii;
  radii->SetName("h");
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  const auto lattice = [&](int n, double spacing)
  {
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
        {
          const double c = 0.5 * (n - 1);
          points->InsertNextPoint((i - c + jitter(random)) * spacing,
            (j - c + jitter(random)) * spacing, (k - c + jitter(random)) * spacing);
          radii->InsertNextValue(static_cast<float>(2.0 * spacing));
        }
  };
  lattice(16, 1.0);
  for (int d = 1; d <= decades; ++d)
  {
    lattice(8, std::pow(10.0, -d));
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->AddArray(radii);
  return cloud;
}

void Densities(savr_scenes::Expectations& expect)
{
  const auto draw = [](int decades, double* peak)
  {
    savr_scenes::Scene s(NestedClusters(decades), kSize, kSize);
    // The same camera for every cloud (the bounds framed by default follow the particle count).
    vtkCamera* camera = s.Renderer->GetActiveCamera();
    camera->SetFocalPoint(0.0, 0.0, 0.0);
    camera->SetPosition(0.0, 0.0, 60.0);
    camera->SetViewUp(0.0, 1.0, 0.0);
    SetUp(s, 1.5);
    s.Mapper->SetParticleRadiusArrayName("h");
    s.Mapper->SetParticleKernel(vtkSAVRParticleSampler::SPH_CUBIC);
    s.Mapper->SetParticleNormalized(false);
    // The default step follows the smallest radius: the same step for all, as the halo's.
    s.Mapper->SetSampleDistance(0.25);
    vtkNew<vtkSAVRParticleSampler> field;
    field->Build(vtkPolyData::SafeDownCast(s.Mapper->GetInputDataObject(0, 0)), nullptr, 0.0, "h",
      vtkSAVRParticleSampler::SPH_CUBIC, false, nullptr);
    double range[2] = { 0.0, 0.0 };
    field->GetFieldRange(range);
    *peak = range[1];
    return Refined(s);
  };
  double haloPeak = 0.0;
  vtkSmartPointer<vtkImageData> halo = draw(0, &haloPeak);
  const double haloCovered = savr_scenes::CoveredFraction(halo, kBackground);
  std::printf("halo alone: density up to %.3g, covered %.3f\n", haloPeak, haloCovered);
  expect(haloCovered > 0.1, "the halo's density is drawn");
  for (int decades : { 2, 5 })
  {
    double peak = 0.0;
    vtkSmartPointer<vtkImageData> nested = draw(decades, &peak);
    const double covered = savr_scenes::CoveredFraction(nested, kBackground);
    const savr_scenes::Difference d = savr_scenes::Compare(nested, halo);
    std::printf("cores over %d decades: density up to %.3g, covered %.3f; vs the halo alone: "
                "mean %.3f levels\n",
      decades, peak, covered, d.Mean);
    const std::string which = " (radii over " + std::to_string(decades) + " decades)";
    expect(peak > 1e3 * haloPeak, "the cores' density spans decades" + which);
    expect(covered > 0.9 * haloCovered, "the halo is drawn beside the cores" + which);
    expect(d.Mean < 0.1, "the halo is drawn as it is alone" + which);
  }
}
} // namespace

int TestSAVROutliers(int, char*[])
{
  savr_scenes::Expectations expect;
  Outlier(expect);
  Densities(expect);
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

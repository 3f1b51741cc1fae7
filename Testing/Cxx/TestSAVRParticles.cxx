// Particles (the points of a vtkPolyData) drawn as a volume, against the path VTK users take
// today: the same particles, kernel and normalization resampled to an image by
// vtkSPHInterpolator and drawn by vtkGPUVolumeRayCastMapper, on the same view.
//
// The cloud: a jittered 24^3 lattice over [-10, 10]^3 carrying a smooth field (150 + 70
// sin(0.35 x) cos(0.3 y) + 3 z), the SPH cubic kernel with h the lattice spacing, normalized
// (Shepard). SAVR samples the particles themselves (8 frames from half a radius); the resampled
// image has 81^3 points over the cloud's reach (a quarter of h apart), drawn at a quarter of its
// spacing. Outside every kernel SAVR's volume is empty, the resampled image holds 0 (transparent
// under the transfer function) and interpolates from the cloud's edge down to it within one of
// its cells: the edges differ a little, the rest agrees. Coarser images (21^3, 41^3) must differ
// more: measured mean 5.6, 2.5 and 1.1 levels at 21^3, 41^3 and 81^3. Shaded, SAVR's analytic
// gradient against the GPU mapper's central differences on the resampled image: mean 6.3
// levels at 41^3 and 5.4 at 81^3 (shading itself moves the image by 34.5). Also checked: the
// image is drawn and refines, and changing the kernel starts over; the same points as a
// vtkUnstructuredGrid of vertex cells, and as one with points and no cells, are particles too,
// drawn exactly as the vtkPolyData; a grid with a cell of another kind is a mesh (its
// tetrahedron drawn, not its points).

#include "SAVRImageChecks.h"
#include "SAVRParticleScenes.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkImageData.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkUnstructuredGrid.h"

#include <array>
#include <cmath>
#include <cstdio>

namespace
{
savr_scenes::Expectations Expect;

constexpr int kSize = 160;
constexpr int kLattice = 24;
constexpr double kSpacing = 20.0 / (kLattice - 1);
// Measured on Mesa llvmpipe: mean 1.13 levels, max 88 (at the cloud's edges, where the resampled
// image ramps down to its null value within a cell and the particles end at their kernels' reach).
constexpr double kMeanLevels = 2.0;
constexpr double kShadedMeanLevels = 7.0;

vtkSmartPointer<vtkPolyData> Cloud()
{
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(17);
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> values;
  values->SetName("value");
  for (int k = 0; k < kLattice; ++k)
    for (int j = 0; j < kLattice; ++j)
      for (int i = 0; i < kLattice; ++i)
      {
        double p[3] = { -10.0 + i * kSpacing, -10.0 + j * kSpacing, -10.0 + k * kSpacing };
        for (double& c : p)
        {
          c += 0.3 * kSpacing * (random->GetValue() - 0.5);
          random->Next();
        }
        points->InsertNextPoint(p);
        values->InsertNextValue(
          150.0 + 70.0 * std::sin(0.35 * p[0]) * std::cos(0.3 * p[1]) + 3.0 * p[2]);
      }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(points);
  cloud->GetPointData()->SetScalars(values);
  return cloud;
}

// The particles resampled to `points`^3 points over the cloud's reach.
vtkSmartPointer<vtkImageData> Resampled(vtkPolyData* cloud, int points)
{
  const double reach = 10.0 + 2.0 * kSpacing; // the cubic kernel's cutoff is 2 h
  const double bounds[6] = { -reach, reach, -reach, reach, -reach, reach };
  return savr_scenes::ResampleCubic(cloud, bounds, points, kSpacing);
}

// The cloud's points and values as an unstructured grid: one cell of `cellType` per point, or no
// cells when `cellType` is VTK_EMPTY_CELL.
vtkSmartPointer<vtkUnstructuredGrid> AsGrid(vtkPolyData* cloud, int cellType)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(cloud->GetPoints());
  grid->GetPointData()->ShallowCopy(cloud->GetPointData());
  if (cellType != VTK_EMPTY_CELL)
  {
    grid->Allocate(cloud->GetNumberOfPoints());
    for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
    {
      grid->InsertNextCell(cellType, 1, &i);
    }
  }
  return grid;
}

// The refined image of `data` drawn as the polydata cloud is in the test below.
vtkSmartPointer<vtkImageData> Refined(vtkDataObject* data)
{
  savr_scenes::Scene scene(data, kSize, kSize);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetParticleKernel(vtkSAVRParticleSampler::SPH_CUBIC);
  scene.Mapper->SetParticleRadius(kSpacing);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  scene.RenderUntilComplete();
  return savr_scenes::Capture(scene.Window);
}
} // namespace

int TestSAVRParticles(int, char*[])
{
  vtkSmartPointer<vtkPolyData> cloud = Cloud();
  savr_scenes::Scene scene(cloud, kSize, kSize);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetParticleKernel(vtkSAVRParticleSampler::SPH_CUBIC);
  scene.Mapper->SetParticleRadius(kSpacing);
  scene.Mapper->SetMaximumNumberOfFrames(8);
  scene.Window->Render();
  vtkSmartPointer<vtkImageData> first = savr_scenes::Capture(scene.Window);
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> savr = savr_scenes::Capture(scene.Window);
  const double background[3] = { 0.1, 0.1, 0.15 };
  const double covered = savr_scenes::CoveredFraction(savr, background);
  std::printf("SAVR particles: %d frames, covered %.3f, first frame vs refined: mean %.3f levels\n",
    scene.Mapper->GetNumberOfFramesAccumulated(), covered, savr_scenes::Compare(first, savr).Mean);
  Expect(covered > 0.3, "the particles are drawn");
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 8, "refinement reaches 8 frames");
  Expect(savr_scenes::Compare(first, savr).Mean > 0.05, "refinement changes the image");

  // The resampled path at several resolutions: it comes closer to the particles' own field as
  // its image grows finer, and agrees at the finest.
  bool supported = false;
  auto resampledPath = [&](int points, bool shade)
  {
    vtkSmartPointer<vtkImageData> resampled = Resampled(cloud, points);
    return savr_scenes::GPUImage(
      resampled, scene.Renderer->GetActiveCamera(), kSize, kSize,
      [&](vtkGPUVolumeRayCastMapper* mapper, vtkVolumeProperty* property, vtkRenderer*)
      {
        mapper->SetAutoAdjustSampleDistances(0);
        mapper->SetSampleDistance(0.25 * resampled->GetSpacing()[0]);
        savr_scenes::WaveletProperty(property);
        property->SetShade(shade);
      },
      &supported);
  };
  double coarser = 0.0;
  double finest = 0.0;
  for (int points : { 21, 41, 81 })
  {
    const savr_scenes::Difference d = savr_scenes::Compare(savr, resampledPath(points, false));
    std::printf("SAVR particles vs vtkSPHInterpolator (%d^3) + vtkGPUVolumeRayCastMapper: max "
                "%.0f, mean %.3f levels\n",
      points, d.Max, d.Mean);
    Expect(supported, "the GPU mapper renders here");
    if (points > 21)
    {
      Expect(d.Mean < coarser, "a finer resampled image comes closer to the particles");
    }
    coarser = d.Mean;
    finest = d.Mean;
  }
  Expect(finest <= kMeanLevels, "the particles agree with the finest resampled image");

  // Shading from the field's analytic gradient, against the GPU mapper's central differences on
  // the finest resampled image.
  scene.Property->ShadeOn();
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> shaded = savr_scenes::Capture(scene.Window);
  const savr_scenes::Difference lit = savr_scenes::Compare(shaded, savr);
  const savr_scenes::Difference shadedCoarse =
    savr_scenes::Compare(shaded, resampledPath(41, true));
  const savr_scenes::Difference shadedPath = savr_scenes::Compare(shaded, resampledPath(81, true));
  std::printf("SAVR particles shaded: vs unshaded mean %.3f levels; vs the resampled path shaded: "
              "41^3 max %.0f, mean %.3f; 81^3 max %.0f, mean %.3f levels\n",
    lit.Mean, shadedCoarse.Max, shadedCoarse.Mean, shadedPath.Max, shadedPath.Mean);
  Expect(lit.Mean > 3.0 * kShadedMeanLevels, "shading changes the particles' image");
  Expect(shadedPath.Mean < shadedCoarse.Mean, "a finer resampled image shades closer to SAVR");
  Expect(shadedPath.Mean <= kShadedMeanLevels, "shaded particles agree with the resampled path");
  scene.Property->ShadeOff();

  // Another kernel starts over.
  scene.Mapper->SetParticleKernel(vtkSAVRParticleSampler::GAUSSIAN);
  scene.Window->Render();
  Expect(scene.Mapper->GetNumberOfFramesAccumulated() == 1, "a kernel change starts over");

  // The bounds, which VTK asks for several times a render, are found again only when the
  // particles (their modification time) or the settings they depend on change: a point moved
  // without Modified() is not seen; Modified(), the radius and the kernel are.
  {
    vtkSmartPointer<vtkPolyData> moved = Cloud();
    vtkNew<vtkSAVRVolumeMapper> mapper;
    mapper->SetInputData(moved);
    mapper->SetParticleKernel(vtkSAVRParticleSampler::SPH_CUBIC);
    mapper->SetParticleRadius(kSpacing);
    const double before = mapper->GetBounds()[1];
    moved->GetPoints()->SetPoint(0, 50.0, 0.0, 0.0);
    const double unchanged = mapper->GetBounds()[1];
    moved->GetPoints()->Modified();
    const double modified = mapper->GetBounds()[1];
    mapper->SetParticleRadius(2.0 * kSpacing);
    const double wider = mapper->GetBounds()[1];
    mapper->SetParticleKernel(vtkSAVRParticleSampler::GAUSSIAN);
    const double gaussian = mapper->GetBounds()[1];
    std::printf("particle bounds' largest x: %.3f, %.3f after a point moved, %.3f after "
                "Modified(), %.3f at twice the radius, %.3f with the Gaussian kernel\n",
      before, unchanged, modified, wider, gaussian);
    Expect(unchanged == before, "the bounds of particles not modified are not found again");
    Expect(std::abs(modified - (50.0 + 2.0 * kSpacing)) < 1e-9 &&
             std::abs(wider - (50.0 + 4.0 * kSpacing)) < 1e-9 &&
             std::abs(gaussian - (50.0 + 6.0 * kSpacing)) < 1e-9,
      "the bounds follow Modified(), the radius and the kernel");
  }

  // Unstructured grids of vertices, and of no cells, are the same particles.
  for (const int cellType : { VTK_VERTEX, VTK_POLY_VERTEX, VTK_EMPTY_CELL })
  {
    vtkSmartPointer<vtkImageData> image = Refined(AsGrid(cloud, cellType));
    const savr_scenes::Difference same = savr_scenes::Compare(image, savr);
    std::printf(
      "unstructured grid of cell type %d vs the polydata: max %.0f levels\n", cellType, same.Max);
    Expect(same.Max == 0.0, "an unstructured grid of vertices is drawn as the particles");
  }
  // One tetrahedron among the vertices makes a mesh: only the tetrahedron is drawn.
  vtkSmartPointer<vtkUnstructuredGrid> mixed = AsGrid(cloud, VTK_VERTEX);
  const vtkIdType tetra[4] = { 0, 1, kLattice, kLattice * kLattice };
  mixed->InsertNextCell(VTK_TETRA, 4, tetra);
  const double mixedCovered = savr_scenes::CoveredFraction(Refined(mixed), background);
  std::printf("vertices and a tetrahedron: covered %.3f\n", mixedCovered);
  Expect(mixedCovered < 0.05 * covered, "a grid with other cells is a mesh, not particles");

  // Without a scalar array, summed kernels draw the particles' density: the same bits as the
  // particles each carrying 1. Normalized, a mean of ones says nothing: an error, nothing drawn.
  const auto density = [&](bool withOnes, bool normalized)
  {
    auto points = vtkSmartPointer<vtkPolyData>::New();
    points->SetPoints(cloud->GetPoints());
    if (withOnes)
    {
      vtkNew<vtkDoubleArray> ones;
      ones->SetNumberOfTuples(cloud->GetNumberOfPoints());
      ones->FillValue(1.0);
      points->GetPointData()->SetScalars(ones);
    }
    savr_scenes::Scene s(points, kSize, kSize);
    savr_scenes::SpreadProperty(s.Property, std::array<double, 2>{ 0.0, 1.2 }.data());
    s.Mapper->SetParticleKernel(vtkSAVRParticleSampler::GAUSSIAN);
    s.Mapper->SetParticleRadius(kSpacing);
    s.Mapper->SetParticleNormalized(normalized);
    s.Mapper->SetMaximumNumberOfFrames(4);
    s.RenderUntilComplete();
    return savr_scenes::Capture(s.Window);
  };
  vtkSmartPointer<vtkImageData> unit = density(true, false);
  vtkSmartPointer<vtkImageData> noArray = density(false, false);
  const double densityCovered = savr_scenes::CoveredFraction(noArray, background);
  const double densityMax = savr_scenes::Compare(noArray, unit).Max;
  std::printf("density without an array: covered %.3f; vs ones as the array: max %.0f levels\n",
    densityCovered, densityMax);
  Expect(densityCovered > 0.3, "without an array, the particles' density is drawn");
  Expect(densityMax == 0.0, "the density is the particles each carrying 1");
  Expect(savr_scenes::CoveredFraction(density(false, true), background) < 0.001,
    "normalized without an array: nothing drawn");
  return Expect.Failures == 0 ? 0 : 1;
}

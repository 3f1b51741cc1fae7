// vtkUnstructuredGrid input, sampled natively:
// - the wavelet on voxels, on hexahedra, on a mixed mesh (voxels, hexahedra, wedges, pyramids,
//   tetrahedra) and on tetrahedra renders as the same wavelet on vtkImageData does;
// - a non-convex mesh whose rays leave and re-enter, and a mesh with a tunnel, match the
//   analytic transmittance of the cells each ray crosses, and the background shows through the
//   tunnel;
// - a baseline of the tetrahedral wavelet.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkAppendFilter.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkDoubleArray.h"
#include "vtkIdList.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnstructuredGrid.h"

#include <array>

namespace
{
savr_scenes::Expectations Expect;

// The image's cells as unstructured cells of the kind `kind(i, j, k)` chooses: 0 voxel, 1
// hexahedron, 2 two wedges, 3 six pyramids around an added centre point (with the trilinear
// centre value), 4 five tetrahedra (alternating so that neighbours share faces).
vtkSmartPointer<vtkUnstructuredGrid> Cells(
  vtkImageData* image, const std::function<int(int, int, int)>& kind)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkDataArray* source = image->GetPointData()->GetScalars();
  vtkNew<vtkDoubleArray> values;
  values->SetName("RTData");
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    points->InsertNextPoint(image->GetPoint(i));
    values->InsertNextValue(source->GetTuple1(i));
  }
  int dims[3];
  image->GetDimensions(dims);
  auto id = [&](int i, int j, int k) { return vtkIdType(i + dims[0] * (j + dims[1] * k)); };
  for (int k = 0; k + 1 < dims[2]; ++k)
    for (int j = 0; j + 1 < dims[1]; ++j)
      for (int i = 0; i + 1 < dims[0]; ++i)
      {
        // Lattice corners: c[x + 2y + 4z].
        vtkIdType c[8];
        for (int n = 0; n < 8; ++n)
        {
          c[n] = id(i + (n & 1), j + ((n >> 1) & 1), k + ((n >> 2) & 1));
        }
        switch (kind(i, j, k))
        {
          case 0:
            grid->InsertNextCell(VTK_VOXEL, 8, c);
            break;
          case 1:
          {
            const vtkIdType hex[8] = { c[0], c[1], c[3], c[2], c[4], c[5], c[7], c[6] };
            grid->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
            break;
          }
          case 2:
          {
            const vtkIdType a[6] = { c[0], c[1], c[3], c[4], c[5], c[7] };
            const vtkIdType b[6] = { c[0], c[3], c[2], c[4], c[7], c[6] };
            grid->InsertNextCell(VTK_WEDGE, 6, a);
            grid->InsertNextCell(VTK_WEDGE, 6, b);
            break;
          }
          case 3:
          {
            double centre[3] = { 0, 0, 0 };
            double value = 0.0;
            for (vtkIdType n : c)
            {
              double p[3];
              points->GetPoint(n, p);
              for (int a = 0; a < 3; ++a)
              {
                centre[a] += p[a] / 8.0;
              }
              value += values->GetValue(n) / 8.0;
            }
            const vtkIdType apex = points->InsertNextPoint(centre);
            values->InsertNextValue(value);
            // Six faces of the lattice cube, each a pyramid's base (ordered so the apex is on
            // the side its normal points away from... any consistent loop works for VTK).
            const int faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 },
              { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
            for (const auto& f : faces)
            {
              const vtkIdType pyramid[5] = { c[f[0]], c[f[1]], c[f[2]], c[f[3]], apex };
              grid->InsertNextCell(VTK_PYRAMID, 5, pyramid);
            }
            break;
          }
          default:
          {
            // Five tetrahedra; the corner tetrahedra sit on the even corners or the odd ones.
            const bool even = ((i + j + k) & 1) == 0;
            const int corners[2][5][4] = { { { 0, 1, 2, 4 }, { 3, 1, 2, 7 }, { 5, 1, 4, 7 },
                                             { 6, 2, 4, 7 }, { 1, 2, 4, 7 } },
              { { 1, 0, 3, 5 }, { 2, 0, 3, 6 }, { 4, 0, 5, 6 }, { 7, 3, 5, 6 }, { 0, 3, 5, 6 } } };
            for (const auto& t : corners[even ? 0 : 1])
            {
              const vtkIdType tet[4] = { c[t[0]], c[t[1]], c[t[2]], c[t[3]] };
              grid->InsertNextCell(VTK_TETRA, 4, tet);
            }
            break;
          }
        }
      }
  grid->SetPoints(points);
  grid->GetPointData()->SetScalars(values);
  return grid;
}

savr_scenes::Scene* Render(
  vtkDataObject* data, vtkCamera* camera, int size = 160, double step = 0.5, int frames = 4)
{
  static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes;
  scenes.emplace_back(new savr_scenes::Scene(data, size, size));
  savr_scenes::Scene& scene = *scenes.back();
  // The sampling is compared with the same values on an image: the image mappers' reading of
  // opacity for the grids too (MeshOpacityAsAttenuation has its own conformance test).
  scene.Mapper->MeshOpacityAsAttenuationOff();
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetSampleDistance(step);
  scene.Mapper->SetMaximumNumberOfFrames(frames);
  scene.Renderer->SetActiveCamera(camera);
  scene.RenderUntilComplete();
  return &scene;
}

// A 5 x 5 x 5 block of unit hexahedra (or each cut into five tetrahedra) with a constant value,
// keeping the cells `keep` accepts.
vtkSmartPointer<vtkUnstructuredGrid> Block(
  bool tetrahedra, const std::function<bool(int, int, int)>& keep)
{
  vtkNew<vtkImageData> lattice;
  lattice->SetDimensions(6, 6, 6);
  vtkNew<vtkDoubleArray> ones;
  ones->SetName("RTData");
  ones->SetNumberOfValues(216);
  ones->Fill(200.0);
  lattice->GetPointData()->SetScalars(ones);
  vtkSmartPointer<vtkUnstructuredGrid> all =
    Cells(lattice, [&](int, int, int) { return tetrahedra ? 4 : 1; });
  auto kept = vtkSmartPointer<vtkUnstructuredGrid>::New();
  kept->SetPoints(all->GetPoints());
  kept->GetPointData()->ShallowCopy(all->GetPointData());
  const int perCell = tetrahedra ? 5 : 1;
  for (vtkIdType c = 0; c < all->GetNumberOfCells(); ++c)
  {
    const vtkIdType lattice = c / perCell;
    if (keep(static_cast<int>(lattice % 5), static_cast<int>(lattice / 5 % 5),
          static_cast<int>(lattice / 25)))
    {
      vtkNew<vtkIdList> ids;
      all->GetCellPoints(c, ids);
      kept->InsertNextCell(all->GetCellType(c), ids);
    }
  }
  return kept;
}

// The red level of a pixel whose ray crosses `length` units of the block's material (colour and
// opacity of the value 200 in the wavelet's transfer function) over the scene's background.
double ExpectedRed(double length, const double background[3])
{
  vtkNew<vtkVolumeProperty> property;
  savr_scenes::WaveletProperty(property);
  double rgb[3];
  property->GetRGBTransferFunction()->GetColor(200.0, rgb);
  const double alpha = property->GetScalarOpacity()->GetValue(200.0); // per unit distance 1
  const double transmittance = std::pow(1.0 - alpha, length);
  return 255.0 * (rgb[0] * (1.0 - transmittance) + background[0] * transmittance);
}

double RedAt(vtkImageData* image, int x, int y)
{
  return savr_scenes::Bytes(image)[3 * (x + image->GetDimensions()[0] * y)];
}

// Shading: each sample's gradient is interpolated in its cell from per-point gradients (the
// mean of the point's cells' interpolant gradients), where the image sampler takes central
// differences of the interpolated field one voxel apart: close, not equal (measured: 0.17
// levels on average). Images do not depend on the thread count.
void ShadedCellsMatchTheImage(vtkImageData* wavelet, vtkCamera* camera, vtkImageData* reference)
{
  const auto shaded = [&](vtkDataObject* data, int threads)
  {
    static std::vector<std::unique_ptr<savr_scenes::Scene>> scenes;
    scenes.emplace_back(new savr_scenes::Scene(data, 160, 160));
    savr_scenes::Scene& scene = *scenes.back();
    scene.Mapper->MeshOpacityAsAttenuationOff();
    savr_scenes::WaveletProperty(scene.Property);
    scene.Property->ShadeOn();
    scene.Property->SetAmbient(0.3);
    scene.Property->SetDiffuse(0.7);
    scene.Property->SetSpecular(0.2);
    scene.Mapper->SetSampleDistance(0.5);
    scene.Mapper->SetMaximumNumberOfFrames(4);
    scene.Mapper->SetNumberOfThreads(threads);
    scene.Renderer->SetActiveCamera(camera);
    scene.RenderUntilComplete();
    return savr_scenes::Capture(scene.Window);
  };
  vtkSmartPointer<vtkUnstructuredGrid> hexahedra = Cells(wavelet, [](int, int, int) { return 1; });
  vtkSmartPointer<vtkUnstructuredGrid> tetrahedra = Cells(wavelet, [](int, int, int) { return 4; });
  vtkSmartPointer<vtkImageData> image = shaded(wavelet, 0);
  vtkSmartPointer<vtkImageData> hex = shaded(hexahedra, 0);
  vtkSmartPointer<vtkImageData> tetOne = shaded(tetrahedra, 1);
  vtkSmartPointer<vtkImageData> tetAll = shaded(tetrahedra, 0);
  const auto d = savr_scenes::Compare(hex, image);
  std::cout << "shaded hexahedra vs shaded image data: max " << d.Max << " mean " << d.Mean
            << " levels\n";
  Expect(d.Mean < 0.5, "shaded hexahedra render as the shaded image does");
  Expect(savr_scenes::Compare(hex, reference).Mean > 1.0, "shading changes the image");
  Expect(savr_scenes::Compare(tetOne, tetAll).Max == 0.0,
    "shaded tetrahedra: 1 thread and all threads give the same bytes");
}

// A U-shaped block (non-convex: rays through the arms leave the mesh and re-enter it) with a
// tunnel through its base, seen along x with a parallel projection: each pixel's red level
// follows from the length of material its ray crosses.
void NonConvexBlock(bool tetrahedra)
{
  // Cells (i, j, k) of the 5^3 block: the arms are i = 0 and i = 4 for k >= 2; the base is
  // k < 2, with a tunnel along x at j = 2, k = 0.
  vtkSmartPointer<vtkUnstructuredGrid> shape = Block(tetrahedra,
    [](int i, int j, int k) { return (k < 2 || i == 0 || i == 4) && !(j == 2 && k == 0); });
  vtkNew<vtkCamera> side;
  side->ParallelProjectionOn();
  side->SetFocalPoint(2.5, 2.5, 2.5);
  side->SetPosition(-20, 2.5, 2.5);
  side->SetViewUp(0, 0, 1);
  side->SetParallelScale(2.5); // the window shows y and z from 0 to 5
  side->SetClippingRange(1, 60);
  // A final step of 1/160: the material's edges are found to within 1/320 of a unit.
  savr_scenes::Scene* scene = Render(shape, side, 100, 0.1, 16);
  vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene->Window);
  const double* background = scene->Renderer->GetBackground();
  // Pixel (x, y) sees world z = (y + 0.5) / 20 and y = 5 - (x + 0.5) / 20 (screen right is -y).
  const double arms = RedAt(image, 75, 70);       // z = 3.5: two arms, 2 units
  const double base = RedAt(image, 25, 30);       // z = 1.5: the base, 5 units
  const double tunnel = RedAt(image, 50, 10);     // y = 2.5, z = 0.5: nothing
  const double tunnelSide = RedAt(image, 10, 10); // y = 4.5, z = 0.5: the base
  const char* name = tetrahedra ? "tetrahedra" : "hexahedra";
  std::cout << name << ": arms " << arms << " (expected " << ExpectedRed(2.0, background)
            << "), base " << base << " (expected " << ExpectedRed(5.0, background) << "), tunnel "
            << tunnel << " (background " << 255.0 * background[0] << "), beside the tunnel "
            << tunnelSide << "\n";
  // Two levels: the 8-bit image and the 8-bit stored values.
  Expect(std::abs(arms - ExpectedRed(2.0, background)) <= 2.0,
    std::string(name) + ": rays leave the mesh and re-enter it");
  Expect(std::abs(base - ExpectedRed(5.0, background)) <= 2.0,
    std::string(name) + ": rays through the base");
  Expect(std::abs(tunnel - 255.0 * background[0]) <= 1.0,
    std::string(name) + ": the background shows through the tunnel");
  Expect(std::abs(tunnelSide - ExpectedRed(5.0, background)) <= 2.0,
    std::string(name) + ": beside the tunnel");
  // The tunnel's walls fall on pixel edges (x = 40 and 60): the window shows the mapper's
  // pixels as they are, not resampled, so the pixels either side of each wall are pure (a
  // texture stretched over the viewport would mix neighbours by up to half a pixel).
  const double inside[2] = { RedAt(image, 40, 10), RedAt(image, 59, 10) };
  const double outside[2] = { RedAt(image, 39, 10), RedAt(image, 60, 10) };
  std::cout << name << ": tunnel edges " << inside[0] << ", " << inside[1] << "; walls "
            << outside[0] << ", " << outside[1] << "\n";
  for (int k = 0; k < 2; ++k)
  {
    Expect(std::abs(inside[k] - 255.0 * background[0]) <= 1.0,
      std::string(name) + ": the tunnel's edge pixels show the background only");
    Expect(std::abs(outside[k] - ExpectedRed(5.0, background)) <= 2.0,
      std::string(name) + ": the wall's edge pixels show the material only");
  }
}
} // namespace

int TestSAVRUnstructured(int argc, char* argv[])
{
  // 1. The same field on an image and on unstructured cells.
  vtkSmartPointer<vtkImageData> wavelet = savr_scenes::Wavelet(10);
  vtkNew<vtkCamera> camera;
  camera->SetPosition(45, 30, 60);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  camera->SetViewAngle(30);
  camera->SetClippingRange(1, 300);
  vtkSmartPointer<vtkImageData> reference = savr_scenes::Capture(Render(wavelet, camera)->Window);

  struct Case
  {
    const char* Name;
    std::function<int(int, int, int)> Kind;
    double MaxLevels;
    double MeanLevels;
  };
  // Voxels and axis-aligned hexahedra interpolate trilinearly, exactly as the image does: float
  // round-off only. Wedges, pyramids and tetrahedra interpolate the same corner values with
  // their own shape functions: close, not equal. The wavelet varies slowly on the scale of a
  // cell, so the difference stays within a few levels at any pixel and a tenth on average.
  const Case cases[] = {
    { "voxels", [](int, int, int) { return 0; }, 1.0, 0.01 },
    { "hexahedra", [](int, int, int) { return 1; }, 1.0, 0.01 },
    { "mixed", [](int i, int j, int k) { return (i + 2 * j + 3 * k) % 5; }, 3.0, 0.1 },
    { "tetrahedra", [](int, int, int) { return 4; }, 3.0, 0.1 },
  };
  savr_scenes::Scene* tetScene = nullptr;
  for (const Case& c : cases)
  {
    vtkSmartPointer<vtkUnstructuredGrid> grid = Cells(wavelet, c.Kind);
    savr_scenes::Scene* scene = Render(grid, camera);
    vtkSmartPointer<vtkImageData> image = savr_scenes::Capture(scene->Window);
    const auto d = savr_scenes::Compare(image, reference);
    std::cout << c.Name << " (" << grid->GetNumberOfCells() << " cells) vs image data: max "
              << d.Max << " mean " << d.Mean << " levels\n";
    Expect(d.Max <= c.MaxLevels && d.Mean <= c.MeanLevels,
      std::string(c.Name) + " render as the image does");
    Expect(savr_scenes::CoveredFraction(image, scene->Renderer->GetBackground()) > 0.2,
      std::string(c.Name) + " are not blank");
    tetScene = scene;
  }

  // VTK's own tetrahedralization of the image (vtkDataSetTriangleFilter) renders like ours.
  vtkNew<vtkDataSetTriangleFilter> tetrahedralize;
  tetrahedralize->SetInputData(wavelet);
  tetrahedralize->Update();
  vtkSmartPointer<vtkImageData> vtkTets =
    savr_scenes::Capture(Render(tetrahedralize->GetOutput(), camera)->Window);
  const auto tets = savr_scenes::Compare(vtkTets, reference);
  std::cout << "vtkDataSetTriangleFilter tetrahedra vs image data: max " << tets.Max << " mean "
            << tets.Mean << " levels\n";
  Expect(tets.Max <= 3.0 && tets.Mean <= 0.1,
    "vtkDataSetTriangleFilter's tetrahedra render as the image does");

  ShadedCellsMatchTheImage(wavelet, camera, reference);

  // 2. A U-shaped, non-convex block with a tunnel, as hexahedra and as tetrahedra.
  NonConvexBlock(false);
  NonConvexBlock(true);

  tetScene->Window->Render();
  if (!savr_scenes::MatchesBaseline(tetScene->Window, argc, argv))
  {
    ++Expect.Failures;
  }
  return Expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

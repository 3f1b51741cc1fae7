// Example 1: the MRI head (vtkImageData) rendered with vtkSAVRVolumeMapper, refining
// progressively in an interactive window. Drag to rotate: while you drag, frames are single
// passes; when you let go, samples accumulate frame by frame until the image is final.
// The same window renders the other inputs the mapper takes: --scene pulse is VTK's Gaussian
// pulse as a vtkOverlappingAMR hierarchy, --scene components a multi-component image (the wavelet
// and a distance shown as a green shell; key c switches between independent and dependent
// components; --components 3 adds a blue shell and 4 a red slab, each with its own transfer
// functions), --scene rgba an unsigned char RGBA image (dependent components: the colour from
// the first three, the opacity from the fourth), --scene tets the wavelet cut into tetrahedra (a
// vtkUnstructuredGrid); a file argument may be a .nii/.nii.gz or .vti image, a .vthb AMR
// hierarchy or a .vtu unstructured grid (their first point or cell array is rendered, with a
// transfer function spread over its range).
//
//   savr_head [file] [--scene head|pulse|components|rgba|tets] [--components 2|3|4] [--headless]
//             [--output head.png] [--size 512]
//             [--frames N] [--step S]
//             [--shade] [--preintegrate] [--tolerance E] [--blend
//             composite|mip|minip|average|additive]
//             [--crop] [--clip] [--nearest] [--parallel] [--gradient-opacity] [--inside]
//             [--volumes 2] [--viewports 2] [--array NAME] [--cells]
//
// --crop shows a fence of the head's middle thirds (VTK's cropping regions), --clip cuts the
// head with a plane through its centre, --parallel uses a parallel projection,
// --gradient-opacity fades regions of small gradient, --inside puts the camera inside the
// volume, --volumes 2 adds a second volume beside the first (its own mapper) and --viewports 2
// a second viewport that sees the data from behind; --array renders the named point array
// (--cells: cell array). In the window, keys toggle features while it refines: h shading,
// g gradient opacity, i pre-integration, x cropping, k the clipping plane, b the next blend
// mode, c independent or dependent components.
//
// --headless renders offscreen until refinement completes, prints each frame's time and the
// frame count, and writes the final image as PNG.

#include "SAVRArguments.h"

#include "vtkSAVRRefinementDriver.h"
#include "vtkSAVRVolumeMapper.h"

#include "vtkAMRGaussianPulseSource.h"
#include "vtkCallbackCommand.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInteractorStyleTrackballCamera.h"
#include "vtkNIFTIImageReader.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPNGWriter.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkWindowToImageFilter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLUniformGridAMRReader.h"
#include "vtkXMLUnstructuredGridReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
bool EndsWith(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The first point array of a data set, or its first cell array; selects it on the mapper.
vtkDataArray* FirstArray(vtkDataSet* data, vtkSAVRVolumeMapper* mapper)
{
  for (int cells = 0; cells < 2 && data; ++cells)
  {
    vtkFieldData* arrays = cells ? static_cast<vtkFieldData*>(data->GetCellData())
                                 : static_cast<vtkFieldData*>(data->GetPointData());
    for (int i = 0; i < arrays->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* array = arrays->GetArray(i);
      if (array && array->GetNumberOfComponents() == 1 && array->GetName() &&
          std::string(array->GetName()) != "vtkGhostType")
      {
        if (cells)
        {
          mapper->SetScalarModeToUseCellFieldData();
        }
        else
        {
          mapper->SetScalarModeToUsePointFieldData();
        }
        mapper->SelectScalarArray(array->GetName());
        return array;
      }
    }
  }
  return nullptr;
}
} // namespace

int main(int argc, char* argv[])
{
  std::string file = "/usr/share/mricron/templates/ch2.nii.gz"; // Debian package mricron-data
  std::string scene = "head";
  std::string output = "savr_head.png";
  bool headless = false;
  int size = 512;
  int frames = 0;
  double step = 0.0;
  bool shade = false;
  bool preIntegrate = false;
  double tolerance = 0.0;
  std::string blend = "composite";
  bool crop = false;
  bool clip = false;
  bool nearest = false;
  bool parallel = false;
  int componentCount = 2;
  bool gradientOpacity = false;
  bool inside = false;
  int volumes = 1;
  int viewports = 1;
  std::string arrayName;
  bool cells = false;
  std::vector<std::string> files;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_head [file] [flags]: the MRI head, another scene or a file rendered with "
    "vtkSAVRVolumeMapper,\nrefining progressively in an interactive window (keys: h shading, g "
    "gradient opacity,\ni pre-integration, x cropping, k clipping plane, b next blend mode, c "
    "independent or dependent\ncomponents).");
  arguments.Positional(&files, 1,
    "file: a .nii, .nii.gz or .vti image, a .vthb AMR hierarchy or "
    "a .vtu unstructured grid");
  arguments.Option("--scene", &scene, "head, pulse, components, rgba or tets (head).");
  arguments.Option("--components", &componentCount, "Components of --scene components, 2 to 4.");
  arguments.Flag("--headless", &headless,
    "Render offscreen until refinement completes, print each frame, write --output.");
  arguments.Option("--output", &output, "The PNG --headless writes (savr_head.png).");
  arguments.Option("--size", &size, "Window height (and width per viewport) in pixels (512).");
  arguments.Option("--frames", &frames, "Frames to accumulate (0: from the data).");
  arguments.Option("--step", &step, "Base sample distance (0: from the data).");
  arguments.Flag("--shade", &shade, "Shade with the gradient.");
  arguments.Flag("--preintegrate", &preIntegrate, "Pre-integrate pairs of samples.");
  arguments.Option("--tolerance", &tolerance, "Stop refining below this error estimate.");
  arguments.Option("--blend", &blend, "composite, mip, minip, average, additive or iso.");
  arguments.Flag("--crop", &crop, "Crop to a fence of the middle thirds.");
  arguments.Flag("--clip", &clip, "Clip with a plane through the centre.");
  arguments.Flag("--nearest", &nearest, "Nearest-neighbour interpolation.");
  arguments.Flag("--parallel", &parallel, "Parallel projection.");
  arguments.Flag("--gradient-opacity", &gradientOpacity, "Fade regions of small gradient.");
  arguments.Flag("--inside", &inside, "Put the camera inside the volume.");
  arguments.Option("--volumes", &volumes, "1, or 2 for a second volume beside the first.");
  arguments.Option("--viewports", &viewports, "1, or 2 for a second viewport from behind.");
  arguments.Option("--array", &arrayName, "Render the named point (or --cells: cell) array.");
  arguments.Flag("--cells", &cells, "Render a cell array.");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  if (!files.empty())
  {
    file = files[0];
    scene = "file";
  }
  volumes = std::min(std::max(volumes, 1), 2);
  viewports = std::min(std::max(viewports, 1), 2);
  componentCount = std::min(std::max(componentCount, 2), 4);

  // The input: an image, an AMR hierarchy or an unstructured grid.
  vtkNew<vtkSAVRVolumeMapper> mapper;
  vtkSmartPointer<vtkDataObject> data;
  double range[2] = { 0.0, 255.0 };
  bool head = false;
  int components = 1;
  if (scene == "pulse")
  {
    vtkNew<vtkAMRGaussianPulseSource> pulse;
    pulse->SetDimension(3);
    pulse->SetNumberOfLevels(2);
    pulse->SetRootSpacing(0.5);
    pulse->SetPulseOrigin(-0.4, -0.5, 1.2);
    pulse->SetPulseWidth(0.8, 0.8, 0.8);
    pulse->SetPulseAmplitude(1.0);
    pulse->Update();
    data = pulse->GetOutput();
    mapper->SetScalarModeToUseCellFieldData();
    mapper->SelectScalarArray("Gaussian-Pulse");
    range[0] = 0.0;
    range[1] = 1.0;
  }
  else if (scene == "components")
  {
    // Components on the wavelet's grid: the wavelet; ten times the distance from a point off
    // the centre (a shell of it shows in green); ten times the distance from another point (a
    // blue shell); ten times x, shifted (a red slab through the middle).
    vtkNew<vtkRTAnalyticSource> wavelet;
    wavelet->SetWholeExtent(-30, 30, -30, 30, -30, 30);
    wavelet->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->CopyStructure(wavelet->GetOutput());
    vtkNew<vtkFloatArray> values;
    values->SetName("wavelet, distances and x");
    values->SetNumberOfComponents(componentCount);
    values->SetNumberOfTuples(image->GetNumberOfPoints());
    vtkDataArray* first = wavelet->GetOutput()->GetPointData()->GetScalars();
    const auto distance = [](const double p[3], double x, double y, double z)
    {
      return 10.0 *
             std::sqrt((p[0] - x) * (p[0] - x) + (p[1] - y) * (p[1] - y) + (p[2] - z) * (p[2] - z));
    };
    for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
    {
      double p[3];
      image->GetPoint(i, p);
      const double all[4] = { first->GetTuple1(i), distance(p, 10, -8, 0), distance(p, -12, 10, 15),
        10.0 * (p[0] + 30.0) };
      for (int c = 0; c < componentCount; ++c)
      {
        values->SetComponent(i, c, all[c]);
      }
    }
    image->GetPointData()->SetScalars(values);
    first->GetRange(range);
    data = image;
    components = componentCount;
  }
  else if (scene == "rgba")
  {
    // Unsigned char RGBA on the wavelet's grid: the colour from the position, the alpha from
    // the wavelet.
    vtkNew<vtkRTAnalyticSource> wavelet;
    wavelet->SetWholeExtent(-30, 30, -30, 30, -30, 30);
    wavelet->Update();
    auto image = vtkSmartPointer<vtkImageData>::New();
    image->CopyStructure(wavelet->GetOutput());
    vtkNew<vtkUnsignedCharArray> values;
    values->SetName("rgba");
    values->SetNumberOfComponents(4);
    values->SetNumberOfTuples(image->GetNumberOfPoints());
    vtkDataArray* first = wavelet->GetOutput()->GetPointData()->GetScalars();
    double waveletRange[2];
    first->GetRange(waveletRange);
    for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
    {
      double p[3];
      image->GetPoint(i, p);
      const double rgba[4] = { 128 + 4 * p[0], 128 + 4 * p[1], 200 - 3 * p[2],
        255.0 * (first->GetTuple1(i) - waveletRange[0]) / (waveletRange[1] - waveletRange[0]) };
      for (int c = 0; c < 4; ++c)
      {
        values->SetComponent(i, c, std::round(std::min(std::max(rgba[c], 0.0), 255.0)));
      }
    }
    image->GetPointData()->SetScalars(values);
    data = image;
    components = 4;
  }
  else if (scene == "tets")
  {
    vtkNew<vtkRTAnalyticSource> wavelet;
    wavelet->SetWholeExtent(-24, 23, -24, 23, -24, 23); // 48^3 points
    vtkNew<vtkDataSetTriangleFilter> tetrahedralize;
    tetrahedralize->SetInputConnection(wavelet->GetOutputPort());
    tetrahedralize->Update();
    data = tetrahedralize->GetOutput();
    FirstArray(tetrahedralize->GetOutput(), mapper)->GetRange(range);
  }
  else if (scene == "file" && EndsWith(file, ".vthb"))
  {
    vtkNew<vtkXMLUniformGridAMRReader> reader;
    reader->SetFileName(file.c_str());
    reader->SetMaximumLevelsToReadByDefault(0); // every level
    reader->Update();
    vtkOverlappingAMR* amr = vtkOverlappingAMR::SafeDownCast(reader->GetOutputDataObject(0));
    vtkDataArray* array = nullptr;
    if (amr && amr->GetNumberOfLevels() > 0 && amr->GetNumberOfDataSets(0) > 0)
    {
      array = FirstArray(amr->GetDataSet(0, 0), mapper);
    }
    if (!array)
    {
      std::fprintf(
        stderr, "cannot read an AMR hierarchy with a scalar array from %s\n", file.c_str());
      return EXIT_FAILURE;
    }
    // The range over every block of every level.
    range[0] = VTK_DOUBLE_MAX;
    range[1] = -VTK_DOUBLE_MAX;
    const std::string name = array->GetName();
    for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
    {
      for (unsigned int id = 0; id < amr->GetNumberOfDataSets(level); ++id)
      {
        vtkUniformGrid* block = amr->GetDataSet(level, id);
        vtkDataArray* values = block ? block->GetCellData()->GetArray(name.c_str()) : nullptr;
        values =
          values ? values : (block ? block->GetPointData()->GetArray(name.c_str()) : nullptr);
        if (values)
        {
          range[0] = std::min(range[0], values->GetRange()[0]);
          range[1] = std::max(range[1], values->GetRange()[1]);
        }
      }
    }
    data = amr;
  }
  else if (scene == "file" && EndsWith(file, ".vtu"))
  {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(file.c_str());
    reader->Update();
    vtkDataArray* array = FirstArray(reader->GetOutput(), mapper);
    if (!array)
    {
      std::fprintf(
        stderr, "cannot read an unstructured grid with a scalar array from %s\n", file.c_str());
      return EXIT_FAILURE;
    }
    array->GetRange(range);
    data = reader->GetOutput();
  }
  else if (scene == "file" && EndsWith(file, ".vti"))
  {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(file.c_str());
    reader->Update();
    vtkDataArray* array = FirstArray(reader->GetOutput(), mapper);
    if (!array)
    {
      std::fprintf(stderr, "cannot read an image with a scalar array from %s\n", file.c_str());
      return EXIT_FAILURE;
    }
    array->GetRange(range);
    data = reader->GetOutput();
  }
  else if (scene == "head" || scene == "file")
  {
    vtkNew<vtkNIFTIImageReader> reader;
    reader->SetFileName(file.c_str());
    reader->Update();
    if (reader->GetOutput()->GetNumberOfPoints() == 0)
    {
      std::fprintf(stderr, "cannot read %s\n", file.c_str());
      return EXIT_FAILURE;
    }
    data = reader->GetOutput();
    head = scene == "head";
    if (!head)
    {
      reader->GetOutput()->GetScalarRange(range);
    }
  }
  else
  {
    std::fprintf(
      stderr, "unknown scene %s: use head, pulse, components, rgba or tets\n", scene.c_str());
    return EXIT_FAILURE;
  }
  mapper->SetInputDataObject(data);
  if (!arrayName.empty() || cells)
  {
    // Scalar selection: a named array (or the first), of the points or of the cells.
    vtkDataSet* set = vtkDataSet::SafeDownCast(data);
    vtkFieldData* fields = set ? (cells ? static_cast<vtkFieldData*>(set->GetCellData())
                                        : static_cast<vtkFieldData*>(set->GetPointData()))
                               : nullptr;
    vtkDataArray* array = nullptr;
    if (fields)
    {
      array = arrayName.empty() ? fields->GetArray(0) : fields->GetArray(arrayName.c_str());
    }
    if (!array || !array->GetName())
    {
      std::fprintf(stderr, "no %s array %s in this input\n", cells ? "cell" : "point",
        arrayName.empty() ? "with a name" : arrayName.c_str());
      return EXIT_FAILURE;
    }
    cells ? mapper->SetScalarModeToUseCellFieldData() : mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectScalarArray(array->GetName());
    if (!head)
    {
      array->GetRange(range);
    }
  }

  // Transfer functions: skin and bone of a T1 MRI (8-bit values), or, for other data, blue to
  // yellow to red over the value range, more opaque towards the top.
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkPiecewiseFunction> opacity;
  const auto at = [&](double f) { return range[0] + f * (range[1] - range[0]); };
  if (head)
  {
    color->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
    color->AddRGBPoint(60.0, 0.75, 0.45, 0.35);
    color->AddRGBPoint(110.0, 0.95, 0.8, 0.7);
    color->AddRGBPoint(255.0, 1.0, 1.0, 0.95);
    opacity->AddPoint(40.0, 0.0);
    opacity->AddPoint(70.0, 0.05);
    opacity->AddPoint(120.0, 0.25);
    opacity->AddPoint(255.0, 0.6);
  }
  else
  {
    color->AddRGBPoint(at(0.0), 0.2, 0.2, 0.9);
    color->AddRGBPoint(at(0.5), 0.9, 0.9, 0.3);
    color->AddRGBPoint(at(1.0), 0.9, 0.2, 0.1);
    opacity->AddPoint(at(0.0), 0.0);
    opacity->AddPoint(at(0.35), 0.02);
    opacity->AddPoint(at(0.7), 0.3);
    opacity->AddPoint(at(1.0), 0.8);
  }
  vtkNew<vtkVolumeProperty> property;
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationType(nearest ? VTK_NEAREST_INTERPOLATION : VTK_LINEAR_INTERPOLATION);
  property->SetShade(shade);
  property->SetAmbient(0.3);
  property->SetDiffuse(0.7);
  property->SetSpecular(0.2);
  property->SetSpecularPower(10.0);
  // Gradient opacity: transparent where the gradient is below a tenth of the range per unit
  // length, opaque from a third.
  vtkNew<vtkPiecewiseFunction> gradientFunction;
  gradientFunction->AddPoint(0.0, 0.0);
  gradientFunction->AddPoint(0.1 * (range[1] - range[0]), 0.0);
  gradientFunction->AddPoint(0.33 * (range[1] - range[0]), 1.0);
  property->SetGradientOpacity(gradientFunction);
  property->SetDisableGradientOpacity(!gradientOpacity);
  // The second component of --scene components: a green shell where the distance is 15 to 20.
  vtkNew<vtkColorTransferFunction> secondColor;
  secondColor->AddRGBPoint(0.0, 0.1, 0.8, 0.2);
  secondColor->AddRGBPoint(500.0, 0.2, 1.0, 0.6);
  vtkNew<vtkPiecewiseFunction> secondOpacity;
  secondOpacity->AddPoint(0.0, 0.0);
  secondOpacity->AddPoint(140.0, 0.0);
  secondOpacity->AddPoint(175.0, 0.5);
  secondOpacity->AddPoint(210.0, 0.0);
  // The third: a blue shell where its distance is 150 to 210; the fourth: a red slab at x
  // from -3 to 3.
  vtkNew<vtkColorTransferFunction> thirdColor;
  thirdColor->AddRGBPoint(0.0, 0.2, 0.3, 1.0);
  thirdColor->AddRGBPoint(500.0, 0.5, 0.6, 1.0);
  vtkNew<vtkPiecewiseFunction> thirdOpacity;
  thirdOpacity->AddPoint(0.0, 0.0);
  thirdOpacity->AddPoint(150.0, 0.0);
  thirdOpacity->AddPoint(180.0, 0.7);
  thirdOpacity->AddPoint(210.0, 0.0);
  vtkNew<vtkColorTransferFunction> fourthColor;
  fourthColor->AddRGBPoint(0.0, 1.0, 0.2, 0.1);
  fourthColor->AddRGBPoint(600.0, 1.0, 0.5, 0.1);
  vtkNew<vtkPiecewiseFunction> fourthOpacity;
  fourthOpacity->AddPoint(0.0, 0.0);
  fourthOpacity->AddPoint(270.0, 0.0);
  fourthOpacity->AddPoint(300.0, 0.3);
  fourthOpacity->AddPoint(330.0, 0.0);
  if (scene == "rgba")
  {
    // The fourth component's opacity through the first's function: more opaque where the
    // wavelet is high.
    property->IndependentComponentsOff();
    opacity->RemoveAllPoints();
    opacity->AddPoint(0.0, 0.0);
    opacity->AddPoint(120.0, 0.0);
    opacity->AddPoint(255.0, 0.2);
  }
  else if (components > 1)
  {
    property->SetColor(1, secondColor);
    property->SetScalarOpacity(1, secondOpacity);
    property->SetComponentWeight(1, 0.8);
  }
  if (scene != "rgba" && components > 2)
  {
    property->SetColor(2, thirdColor);
    property->SetScalarOpacity(2, thirdOpacity);
  }
  if (scene != "rgba" && components > 3)
  {
    property->SetColor(3, fourthColor);
    property->SetScalarOpacity(3, fourthOpacity);
  }

  // The mapper: base step and frame count default from the data's spacing or cell size.
  mapper->SetSampleDistance(step);
  mapper->SetMaximumNumberOfFrames(frames);
  mapper->SetPreIntegration(preIntegrate);
  mapper->SetErrorTolerance(tolerance);
  const char* blendModes[] = { "composite", "mip", "minip", "average", "additive", "iso" };
  const int blendValues[] = { vtkVolumeMapper::COMPOSITE_BLEND,
    vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, vtkVolumeMapper::MINIMUM_INTENSITY_BLEND,
    vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, vtkVolumeMapper::ADDITIVE_BLEND,
    vtkVolumeMapper::ISOSURFACE_BLEND };
  int blendIndex = -1;
  for (int b = 0; b < 6; ++b)
  {
    blendIndex = blend == blendModes[b] ? b : blendIndex;
  }
  if (blendIndex < 0)
  {
    std::fprintf(stderr, "unknown blend mode %s\n", blend.c_str());
    return EXIT_FAILURE;
  }
  mapper->SetBlendMode(blendValues[blendIndex]);
  // The isosurface mode shows the surface of the value 120 for the head (opacity 0.25 there),
  // of the value at 60% of the range for other data.
  property->GetIsoSurfaceValues()->SetValue(0, head ? 120.0 : at(0.6));
  // Cropping: the middle third of every axis, shown as a fence.
  double bounds[6];
  mapper->GetBounds(bounds);
  double thirds[6];
  for (int a = 0; a < 3; ++a)
  {
    thirds[2 * a] = bounds[2 * a] + (bounds[2 * a + 1] - bounds[2 * a]) / 3.0;
    thirds[2 * a + 1] = bounds[2 * a] + 2.0 * (bounds[2 * a + 1] - bounds[2 * a]) / 3.0;
  }
  mapper->SetCroppingRegionPlanes(thirds);
  mapper->SetCroppingRegionFlagsToFence();
  mapper->SetCropping(crop);
  // Clipping: a plane through the centre, keeping the front half.
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(
    (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2);
  plane->SetNormal(0.0, -1.0, 0.0);
  if (clip)
  {
    mapper->AddClippingPlane(plane);
  }

  // One mapper per volume and viewport (a mapper keeps the samples of one view): the others
  // copy the first one's settings.
  std::vector<vtkSmartPointer<vtkSAVRVolumeMapper>> mappers = { mapper.GetPointer() };
  const auto newMapper = [&]()
  {
    auto copy = vtkSmartPointer<vtkSAVRVolumeMapper>::New();
    copy->SetInputDataObject(data);
    copy->SetScalarMode(mapper->GetScalarMode());
    if (mapper->GetArrayAccessMode() == VTK_GET_ARRAY_BY_NAME)
    {
      copy->SelectScalarArray(mapper->GetArrayName());
    }
    else
    {
      copy->SelectScalarArray(mapper->GetArrayId());
    }
    copy->SetSampleDistance(mapper->GetSampleDistance());
    copy->SetMaximumNumberOfFrames(mapper->GetMaximumNumberOfFrames());
    copy->SetPreIntegration(mapper->GetPreIntegration());
    copy->SetErrorTolerance(mapper->GetErrorTolerance());
    copy->SetBlendMode(mapper->GetBlendMode());
    copy->SetCroppingRegionPlanes(mapper->GetCroppingRegionPlanes());
    copy->SetCroppingRegionFlags(mapper->GetCroppingRegionFlags());
    copy->SetCropping(mapper->GetCropping());
    if (clip)
    {
      copy->AddClippingPlane(plane);
    }
    mappers.push_back(copy);
    return copy;
  };
  const auto newVolume = [&](vtkSAVRVolumeMapper* m)
  {
    auto v = vtkSmartPointer<vtkVolume>::New();
    v->SetMapper(m);
    v->SetProperty(property);
    return v;
  };

  vtkNew<vtkRenderer> renderer;
  renderer->AddVolume(newVolume(mapper));
  if (volumes > 1)
  {
    // The second volume beside the first, along x.
    vtkSmartPointer<vtkVolume> second = newVolume(newMapper());
    second->SetPosition(1.15 * (bounds[1] - bounds[0]), 0.0, 0.0);
    renderer->AddVolume(second);
  }
  renderer->SetBackground(0.1, 0.1, 0.15);
  // Face the head: +y is anterior and +z superior in the image's index space.
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, head ? 1 : -1, 0);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 0, 1);
  camera->Azimuth(35.0);
  camera->Elevation(head ? 10.0 : 25.0);
  camera->SetParallelProjection(parallel);
  renderer->ResetCamera();
  if (inside)
  {
    // From the volume's centre, a little behind it, looking the same way.
    const double* f = camera->GetFocalPoint();
    const double* p = camera->GetPosition();
    const double c[3] = { (bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2,
      (bounds[4] + bounds[5]) / 2 };
    camera->SetPosition(
      c[0] + 0.1 * (p[0] - f[0]), c[1] + 0.1 * (p[1] - f[1]), c[2] + 0.1 * (p[2] - f[2]));
    camera->SetFocalPoint(c[0] - (p[0] - f[0]), c[1] - (p[1] - f[1]), c[2] - (p[2] - f[2]));
    renderer->ResetCameraClippingRange();
  }

  vtkNew<vtkRenderWindow> window;
  window->SetSize(viewports > 1 ? 2 * size : size, size);
  window->AddRenderer(renderer);
  vtkNew<vtkRenderer> back;
  if (viewports > 1)
  {
    // The right half sees the data from the opposite side, through a mapper of its own.
    renderer->SetViewport(0.0, 0.0, 0.5, 1.0);
    back->SetViewport(0.5, 0.0, 1.0, 1.0);
    back->SetBackground(0.12, 0.1, 0.1);
    back->AddVolume(newVolume(newMapper()));
    back->GetActiveCamera()->DeepCopy(camera);
    back->GetActiveCamera()->Azimuth(180.0);
    back->ResetCameraClippingRange();
    window->AddRenderer(back);
  }
  window->SetWindowName(("vtkSAVR: " + (scene == "file" ? file : scene)).c_str());

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
    } while (!std::all_of(mappers.begin(), mappers.end(),
               [](vtkSAVRVolumeMapper* m) { return m->GetRefinementComplete(); }) &&
             render < 100000);
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

  // Keys toggle features; the mapper re-blends or starts over as each needs.
  vtkNew<vtkCallbackCommand> keys;
  struct KeyState
  {
    std::vector<vtkSmartPointer<vtkSAVRVolumeMapper>>* Mappers;
    vtkVolumeProperty* Property;
    vtkPlane* Plane;
    const int* Blends;
    int Blend;
    int Components;
  } keyState{ &mappers, property, plane, blendValues, blendIndex, components };
  keys->SetClientData(&keyState);
  keys->SetCallback(
    [](vtkObject* caller, unsigned long, void* clientData, void*)
    {
      auto* state = static_cast<KeyState*>(clientData);
      auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
      switch (interactor->GetKeyCode())
      {
        case 'h':
          state->Property->SetShade(!state->Property->GetShade());
          break;
        case 'g':
          state->Property->SetDisableGradientOpacity(!state->Property->GetDisableGradientOpacity());
          break;
        case 'i':
          for (vtkSAVRVolumeMapper* m : *state->Mappers)
          {
            m->SetPreIntegration(!m->GetPreIntegration());
          }
          break;
        case 'x':
          for (vtkSAVRVolumeMapper* m : *state->Mappers)
          {
            m->SetCropping(!m->GetCropping());
          }
          break;
        case 'k':
          for (vtkSAVRVolumeMapper* m : *state->Mappers)
          {
            if (m->GetNumberOfClippingPlanes() > 0)
            {
              m->RemoveAllClippingPlanes();
            }
            else
            {
              m->AddClippingPlane(state->Plane);
            }
          }
          break;
        case 'c':
          // Dependent components are two (luminance, alpha) or four (RGBA: see --scene rgba).
          if (state->Components != 2)
          {
            std::printf("key c switches two components between independent and dependent\n");
            return;
          }
          state->Property->SetIndependentComponents(!state->Property->GetIndependentComponents());
          break;
        case 'b':
          state->Blend = (state->Blend + 1) % 6;
          for (vtkSAVRVolumeMapper* m : *state->Mappers)
          {
            m->SetBlendMode(state->Blends[state->Blend]);
          }
          break;
        default:
          return;
      }
      interactor->Render();
    });
  interactor->AddObserver(vtkCommand::KeyPressEvent, keys);

  // Re-renders on a timer while refinement is incomplete; single passes while dragging.
  // One driver per mapper.
  std::vector<vtkSmartPointer<vtkSAVRRefinementDriver>> drivers;
  for (vtkSAVRVolumeMapper* m : mappers)
  {
    drivers.push_back(vtkSmartPointer<vtkSAVRRefinementDriver>::New());
    drivers.back()->SetMapper(m);
    drivers.back()->SetInteractor(interactor);
  }
  interactor->Start();
  return EXIT_SUCCESS;
}

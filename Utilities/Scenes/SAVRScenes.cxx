#include "SAVRScenes.h"

#include "vtkAMRGaussianPulseSource.h"
#include "vtkCamera.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkFloatArray.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkMath.h"
#include "vtkNIFTIImageReader.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkRTAnalyticSource.h"
#include "vtkRendererCollection.h"
#include "vtkUniformGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLUniformGridAMRReader.h"
#include "vtkXMLUnstructuredGridReader.h"

#include "SAVRImageChecks.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace savr_scenes
{
namespace
{
vtkSmartPointer<vtkImageData> WaveletOver(int low, int high)
{
  vtkNew<vtkRTAnalyticSource> source;
  source->SetWholeExtent(low, high, low, high, low, high);
  source->Update();
  return source->GetOutput();
}

double Distance(const double p[3], double x, double y, double z)
{
  return std::sqrt((p[0] - x) * (p[0] - x) + (p[1] - y) * (p[1] - y) + (p[2] - z) * (p[2] - z));
}

bool EndsWith(const std::string& s, const std::string& tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// An image on the wavelet's grid whose point scalars, `components` per point, `values` computes
// from the point and the wavelet's value there.
template <typename Array>
vtkSmartPointer<vtkImageData> OnWaveletGrid(int halfExtent, const char* name, int components,
  const std::function<void(const double p[3], double wavelet, double* tuple)>& values)
{
  vtkSmartPointer<vtkImageData> wavelet = WaveletOver(-halfExtent, halfExtent);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->CopyStructure(wavelet);
  vtkNew<Array> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(wavelet->GetNumberOfPoints());
  vtkDataArray* first = wavelet->GetPointData()->GetScalars();
  std::vector<double> tuple(components);
  for (vtkIdType i = 0; i < wavelet->GetNumberOfPoints(); ++i)
  {
    double p[3];
    wavelet->GetPoint(i, p);
    values(p, first->GetTuple1(i), tuple.data());
    for (int c = 0; c < components; ++c)
    {
      array->SetComponent(i, c, tuple[c]);
    }
  }
  image->GetPointData()->SetScalars(array);
  return image;
}

template <typename Reader>
vtkSmartPointer<vtkDataObject> Read(const std::string& file)
{
  vtkNew<Reader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  return reader->GetOutputDataObject(0);
}

vtkFieldData* Arrays(vtkDataSet* data, bool cells)
{
  return cells ? static_cast<vtkFieldData*>(data->GetCellData())
               : static_cast<vtkFieldData*>(data->GetPointData());
}
} // namespace

std::string HeadFile()
{
  const char* overridden = std::getenv("SAVR_HEAD_FILE");
  return overridden ? overridden : "/usr/share/mricron/templates/ch2.nii.gz";
}

vtkSmartPointer<vtkImageData> Head()
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

vtkSmartPointer<vtkImageData> Wavelet(int halfExtent)
{
  return WaveletOver(-halfExtent, halfExtent);
}

vtkSmartPointer<vtkUnstructuredGrid> TetrahedralWavelet(int points)
{
  const int half = points / 2;
  vtkNew<vtkDataSetTriangleFilter> tetrahedralize;
  tetrahedralize->SetInputData(WaveletOver(-half, points - half - 1));
  tetrahedralize->Update();
  return tetrahedralize->GetOutput();
}

vtkSmartPointer<vtkUnstructuredGrid> HexahedralWavelet(int points, bool wedges)
{
  const int half = points / 2;
  vtkSmartPointer<vtkImageData> lattice = WaveletOver(-half, points - half - 1);
  // A period of 8 cells and an amplitude of 0.05 cell bend the cells' faces by a few percent.
  constexpr double amplitude = 0.05;
  const double frequency = 2.0 * vtkMath::Pi() / 8.0;
  vtkNew<vtkPoints> warped;
  warped->SetNumberOfPoints(lattice->GetNumberOfPoints());
  for (vtkIdType n = 0; n < lattice->GetNumberOfPoints(); ++n)
  {
    double p[3];
    lattice->GetPoint(n, p);
    const double s[3] = { std::sin(frequency * p[0]), std::sin(frequency * p[1]),
      std::sin(frequency * p[2]) };
    warped->SetPoint(n, p[0] + amplitude * s[1] * s[2], p[1] + amplitude * s[2] * s[0],
      p[2] + amplitude * s[0] * s[1]);
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(warped);
  grid->GetPointData()->SetScalars(lattice->GetPointData()->GetScalars());
  const int cells = points - 1;
  grid->Allocate(static_cast<vtkIdType>(cells) * cells * cells * (wedges ? 2 : 1));
  const auto id = [points](int i, int j, int k)
  { return static_cast<vtkIdType>(i + points * (j + static_cast<vtkIdType>(points) * k)); };
  for (int k = 0; k < cells; ++k)
  {
    for (int j = 0; j < cells; ++j)
    {
      for (int i = 0; i < cells; ++i)
      {
        // VTK's hexahedron order: the quadrilateral at k counter-clockwise seen from +z, then
        // the one at k + 1.
        const vtkIdType c[8] = { id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
          id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1) };
        if (wedges && i % 2 == 0)
        {
          // Cut along the diagonal plane through corners 0, 2, 6 and 4; each wedge's first
          // triangle turns clockwise seen from +z, its normal away from the second triangle, as
          // VTK orders a wedge (vtkCellValidator finds the other turn's faces inside out).
          const vtkIdType a[6] = { c[0], c[2], c[1], c[4], c[6], c[5] };
          const vtkIdType b[6] = { c[0], c[3], c[2], c[4], c[7], c[6] };
          grid->InsertNextCell(VTK_WEDGE, 6, a);
          grid->InsertNextCell(VTK_WEDGE, 6, b);
        }
        else
        {
          grid->InsertNextCell(VTK_HEXAHEDRON, 8, c);
        }
      }
    }
  }
  return grid;
}

vtkSmartPointer<vtkOverlappingAMR> GaussianPulse()
{
  vtkNew<vtkAMRGaussianPulseSource> source;
  source->SetDimension(3);
  source->SetNumberOfLevels(2);
  source->SetRootSpacing(0.5);
  source->SetRefinementRatio(2);
  source->SetPulseOrigin(PulseOrigin[0], PulseOrigin[1], PulseOrigin[2]);
  source->SetPulseWidth(PulseWidth, PulseWidth, PulseWidth);
  source->SetPulseAmplitude(1.0);
  source->Update();
  return source->GetOutput();
}

vtkSmartPointer<vtkImageData> ComponentImage(int count, int halfExtent)
{
  const double s = halfExtent / 12.0;
  return OnWaveletGrid<vtkFloatArray>(halfExtent, "components", count,
    [&](const double p[3], double wavelet, double* tuple)
    {
      const double all[4] = { wavelet, 10.0 * Distance(p, 4 * s, -3 * s, 0) / s,
        10.0 * Distance(p, -4 * s, 3 * s, 2 * s) / s, 10.0 * (p[0] + 12.0 * s) / s };
      std::copy(all, all + count, tuple);
    });
}

vtkSmartPointer<vtkImageData> ColorAndAlphaImage(int halfExtent)
{
  const double s = halfExtent / 12.0;
  double range[2];
  Wavelet(halfExtent)->GetPointData()->GetScalars()->GetRange(range);
  return OnWaveletGrid<vtkUnsignedCharArray>(halfExtent, "rgba", 4,
    [&](const double p[3], double wavelet, double* tuple)
    {
      const double alpha = (wavelet - range[0]) / (range[1] - range[0]) * 255.0;
      const double rgba[4] = { 128 + 10 * p[0] / s, 128 + 10 * p[1] / s, 200 - 6 * p[2] / s,
        alpha };
      for (int c = 0; c < 4; ++c)
      {
        tuple[c] = std::round(std::min(std::max(rgba[c], 0.0), 255.0));
      }
    });
}

void WaveletProperty(vtkVolumeProperty* property)
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

void HeadProperty(vtkVolumeProperty* property)
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

void PulseProperty(vtkVolumeProperty* property)
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.1, 0.2, 0.9);
  color->AddRGBPoint(0.5, 0.9, 0.9, 0.2);
  color->AddRGBPoint(1.0, 0.9, 0.2, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(0.1, 0.02);
  opacity->AddPoint(1.0, 0.9);
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
  property->SetScalarOpacityUnitDistance(0.3);
}

void SpreadProperty(vtkVolumeProperty* property, const double range[2])
{
  const auto at = [&](double f) { return range[0] + f * (range[1] - range[0]); };
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(at(0.0), 0.2, 0.2, 0.9);
  color->AddRGBPoint(at(0.5), 0.9, 0.9, 0.3);
  color->AddRGBPoint(at(1.0), 0.9, 0.2, 0.1);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(at(0.0), 0.0);
  opacity->AddPoint(at(0.35), 0.02);
  opacity->AddPoint(at(0.7), 0.3);
  opacity->AddPoint(at(1.0), 0.8);
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
  property->SetInterpolationTypeToLinear();
}

void SecondComponentFunctions(vtkVolumeProperty* property, double shellOpacity)
{
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0.0, 0.1, 0.8, 0.2);
  color->AddRGBPoint(250.0, 0.2, 1.0, 0.6);
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(55.0, 0.0);
  opacity->AddPoint(70.0, shellOpacity);
  opacity->AddPoint(85.0, 0.0);
  opacity->AddPoint(250.0, 0.0);
  property->SetColor(1, color);
  property->SetScalarOpacity(1, opacity);
  property->SetScalarOpacityUnitDistance(1, 1.0);
}

void IndependentComponentsProperty(vtkVolumeProperty* property)
{
  WaveletProperty(property);
  property->IndependentComponentsOn();
  SecondComponentFunctions(property, 0.6);
  property->SetComponentWeight(0, 1.0);
  property->SetComponentWeight(1, 0.7);
}

void LastComponentFunctions(vtkVolumeProperty* property, double slabOpacity)
{
  vtkNew<vtkColorTransferFunction> blue;
  blue->AddRGBPoint(0.0, 0.2, 0.3, 1.0);
  blue->AddRGBPoint(250.0, 0.5, 0.6, 1.0);
  vtkNew<vtkPiecewiseFunction> shell;
  shell->AddPoint(0.0, 0.0);
  shell->AddPoint(70.0, 0.0);
  shell->AddPoint(80.0, 0.7);
  shell->AddPoint(90.0, 0.0);
  shell->AddPoint(250.0, 0.0);
  property->SetColor(2, blue);
  property->SetScalarOpacity(2, shell);
  vtkNew<vtkColorTransferFunction> red;
  red->AddRGBPoint(0.0, 1.0, 0.2, 0.1);
  red->AddRGBPoint(240.0, 1.0, 0.5, 0.1);
  vtkNew<vtkPiecewiseFunction> slab;
  slab->AddPoint(0.0, 0.0);
  slab->AddPoint(105.0, 0.0);
  slab->AddPoint(120.0, slabOpacity);
  slab->AddPoint(135.0, 0.0);
  slab->AddPoint(240.0, 0.0);
  property->SetColor(3, red);
  property->SetScalarOpacity(3, slab);
  property->SetScalarOpacityUnitDistance(2, 1.0);
  property->SetScalarOpacityUnitDistance(3, 2.0);
  property->SetComponentWeight(2, 0.8);
  property->SetComponentWeight(3, 1.0);
}

void DependentComponentsProperty(vtkVolumeProperty* property)
{
  WaveletProperty(property);
  property->IndependentComponentsOff();
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(55.0, 0.0);
  opacity->AddPoint(70.0, 0.5);
  opacity->AddPoint(85.0, 0.0);
  opacity->AddPoint(250.0, 0.0);
  property->SetScalarOpacity(opacity);
}

void ColorAndAlphaProperty(vtkVolumeProperty* property)
{
  WaveletProperty(property);
  property->IndependentComponentsOff();
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0.0, 0.0);
  opacity->AddPoint(120.0, 0.0);
  opacity->AddPoint(255.0, 0.3);
  property->SetScalarOpacity(opacity);
}

vtkSmartPointer<vtkDataObject> ReadDataFile(const std::string& file, std::string& error)
{
  vtkSmartPointer<vtkDataObject> data;
  if (EndsWith(file, ".vti"))
  {
    data = Read<vtkXMLImageDataReader>(file);
  }
  else if (EndsWith(file, ".vtu"))
  {
    data = Read<vtkXMLUnstructuredGridReader>(file);
  }
  else if (EndsWith(file, ".vthb"))
  {
    vtkNew<vtkXMLUniformGridAMRReader> reader;
    reader->SetFileName(file.c_str());
    reader->SetMaximumLevelsToReadByDefault(0); // every level
    reader->Update();
    data = reader->GetOutputDataObject(0);
  }
  else if (EndsWith(file, ".nii") || EndsWith(file, ".nii.gz"))
  {
    data = Read<vtkNIFTIImageReader>(file);
  }
  else
  {
    error = "unsupported file " + file + ": use a .vti, .vtu, .vthb, .nii or .nii.gz file";
    return nullptr;
  }
  auto* set = vtkDataSet::SafeDownCast(data);
  auto* amr = vtkOverlappingAMR::SafeDownCast(data);
  if (!(set && set->GetNumberOfPoints() > 0) && !(amr && amr->GetNumberOfLevels() > 0))
  {
    error = "cannot read " + file;
    return nullptr;
  }
  return data;
}

vtkDataArray* FirstScalarArray(vtkDataObject* data, bool& cells)
{
  vtkDataSet* first = vtkDataSet::SafeDownCast(data);
  auto* amr = vtkOverlappingAMR::SafeDownCast(data);
  if (amr && amr->GetNumberOfLevels() > 0 && amr->GetNumberOfDataSets(0) > 0)
  {
    first = amr->GetDataSet(0, 0);
  }
  for (int c = 0; c < 2 && first; ++c)
  {
    vtkFieldData* arrays = Arrays(first, c == 1);
    for (int i = 0; i < arrays->GetNumberOfArrays(); ++i)
    {
      vtkDataArray* array = arrays->GetArray(i);
      if (array && array->GetNumberOfComponents() == 1 &&
          std::string(array->GetName() ? array->GetName() : "") != "vtkGhostType")
      {
        cells = c == 1;
        return array;
      }
    }
  }
  return nullptr;
}

bool ArrayRange(vtkDataObject* data, const char* name, bool cells, double range[2])
{
  std::vector<vtkDataSet*> parts;
  if (auto* amr = vtkOverlappingAMR::SafeDownCast(data))
  {
    for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
    {
      for (unsigned int id = 0; id < amr->GetNumberOfDataSets(level); ++id)
      {
        parts.push_back(amr->GetDataSet(level, id));
      }
    }
  }
  else
  {
    parts.push_back(vtkDataSet::SafeDownCast(data));
  }
  range[0] = VTK_DOUBLE_MAX;
  range[1] = -VTK_DOUBLE_MAX;
  for (vtkDataSet* part : parts)
  {
    vtkDataArray* values = part ? Arrays(part, cells)->GetArray(name) : nullptr;
    if (values)
    {
      range[0] = std::min(range[0], values->GetRange()[0]);
      range[1] = std::max(range[1], values->GetRange()[1]);
    }
  }
  return range[0] <= range[1];
}

void FaceTheHead(vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(0, 0, 0);
  camera->SetPosition(0, 1, 0);
  camera->SetViewUp(0, 0, 1);
  camera->Azimuth(35.0);
  camera->Elevation(10.0);
  renderer->ResetCamera();
}

Scene::Scene(vtkDataObject* data, int width, int height)
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

int Scene::RenderUntilComplete(int maxRenders)
{
  int renders = 0;
  do
  {
    this->Window->Render();
    ++renders;
  } while (!this->Mapper->GetRefinementComplete() && renders < maxRenders);
  return renders;
}

vtkSmartPointer<vtkImageData> GPUImage(vtkImageData* data, vtkCamera* camera, int width,
  int height,
  const std::function<void(vtkGPUVolumeRayCastMapper*, vtkVolumeProperty*, vtkRenderer*)>&
    configure,
  bool* supported)
{
  // One window for every call: see Scene about opening windows in quick succession.
  static vtkNew<vtkRenderWindow> window;
  window->GetRenderers()->RemoveAllItems();
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkGPUVolumeRayCastMapper> mapper;
  vtkNew<vtkVolumeProperty> property;
  vtkNew<vtkVolume> volume;
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  window->AddRenderer(renderer);
  renderer->SetBackground(0.1, 0.1, 0.15);
  mapper->SetInputData(data);
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  renderer->AddVolume(volume);
  if (configure)
  {
    configure(mapper, property, renderer);
  }
  renderer->GetActiveCamera()->DeepCopy(camera);
  renderer->ResetCameraClippingRange();
  window->Render();
  if (supported)
  {
    *supported = mapper->IsRenderSupported(window, property) != 0;
  }
  vtkSmartPointer<vtkImageData> image = Capture(window);
  window->GetRenderers()->RemoveAllItems();
  return image;
}

vtkSmartPointer<vtkImageData> FixedPointImage(vtkImageData* data, vtkCamera* camera, int width,
  int height, const std::function<void(vtkVolumeMapper*)>& configure,
  const std::function<void(vtkVolumeProperty*)>& property)
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

double BytesPerStoredSample(vtkSAVRVolumeMapper* mapper)
{
  return static_cast<double>(mapper->GetMemoryInUse()) / mapper->GetNumberOfStoredSamples();
}

} // namespace savr_scenes

// Vector arrays drawn by their magnitude or by one component (VectorMode, as
// vtkSmartVolumeMapper's), on images, AMR hierarchies and meshes: each the same bits as the
// one-component array of those values computed here. Without a vector mode an AMR vector array is
// refused with the reason.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkUniformGrid.h"
#include "vtkUnstructuredGrid.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

namespace
{
constexpr int kSize = 120;

// From `scalars` (one component): a three-component array "v" of (s, s / 2, 1 / 4 - s / 8) and
// the arrays its magnitude and its component 1 would be, "magnitude" and "second".
void AddVectors(vtkDataSetAttributes* attributes, vtkDataArray* scalars)
{
  const vtkIdType n = scalars->GetNumberOfTuples();
  vtkNew<vtkFloatArray> v;
  v->SetName("v");
  v->SetNumberOfComponents(3);
  v->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> magnitude;
  magnitude->SetName("magnitude");
  magnitude->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> second;
  second->SetName("second");
  second->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    const double s = scalars->GetComponent(i, 0);
    const float c[3] = { static_cast<float>(s), static_cast<float>(0.5 * s),
      static_cast<float>(0.25 - 0.125 * s) };
    v->SetTypedTuple(i, c);
    double sum = 0.0;
    for (float x : c)
    {
      sum += static_cast<double>(x) * x;
    }
    magnitude->SetValue(i, static_cast<float>(std::sqrt(sum)));
    second->SetValue(i, c[1]);
  }
  attributes->AddArray(v);
  attributes->AddArray(magnitude);
  attributes->AddArray(second);
}

struct Drawn
{
  vtkSmartPointer<vtkImageData> Image;
  int Errors = 0;
  std::string LastError;
};

void CountError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* drawn = static_cast<Drawn*>(clientData);
  ++drawn->Errors;
  drawn->LastError = callData ? static_cast<const char*>(callData) : "";
}

// `data`'s array `name` (point or cell data) drawn to completion, with `mode` and `component`.
Drawn Draw(vtkDataObject* data, const char* name, bool cells, int mode, int component,
  const std::array<double, 2>& range)
{
  savr_scenes::Scene s(data, kSize, kSize);
  savr_scenes::SpreadProperty(s.Property, range.data());
  vtkNew<vtkCallbackCommand> errors;
  Drawn drawn;
  errors->SetCallback(CountError);
  errors->SetClientData(&drawn);
  s.Mapper->AddObserver(vtkCommand::ErrorEvent, errors);
  if (cells)
  {
    s.Mapper->SetScalarModeToUseCellFieldData();
  }
  else
  {
    s.Mapper->SetScalarModeToUsePointFieldData();
  }
  s.Mapper->SelectScalarArray(name);
  s.Mapper->SetVectorMode(mode);
  s.Mapper->SetVectorComponent(component);
  s.Mapper->SetMaximumNumberOfFrames(4);
  s.RenderUntilComplete(64);
  drawn.Image = savr_scenes::Capture(s.Window);
  return drawn;
}

void Compare(savr_scenes::Expectations& expect, const std::string& kind, vtkDataObject* data,
  bool cells, const std::array<double, 2>& range)
{
  const double background[3] = { 0.1, 0.1, 0.15 };
  const Drawn magnitude = Draw(data, "v", cells, vtkSAVRVolumeMapper::MAGNITUDE, 0, range);
  const Drawn expected = Draw(data, "magnitude", cells, vtkSAVRVolumeMapper::DISABLED, 0, range);
  const Drawn second = Draw(data, "v", cells, vtkSAVRVolumeMapper::COMPONENT, 1, range);
  const Drawn expectedSecond = Draw(data, "second", cells, vtkSAVRVolumeMapper::DISABLED, 0, range);
  const savr_scenes::Difference m = savr_scenes::Compare(magnitude.Image, expected.Image);
  const savr_scenes::Difference c = savr_scenes::Compare(second.Image, expectedSecond.Image);
  const double covered = savr_scenes::CoveredFraction(magnitude.Image, background);
  std::printf("%s: magnitude covered %.3f, vs its array max %.0f levels; component 1 vs its array "
              "max %.0f; errors %d\n",
    kind.c_str(), covered, m.Max, c.Max, magnitude.Errors + second.Errors);
  expect(covered > 0.05, kind + ": the magnitude is drawn");
  expect(m.Max == 0.0, kind + ": the magnitude is drawn as the array of magnitudes");
  expect(c.Max == 0.0, kind + ": component 1 is drawn as the array of that component");
  expect(savr_scenes::Compare(magnitude.Image, second.Image).Mean > 0.5,
    kind + ": the two modes differ");
  expect(magnitude.Errors + second.Errors == 0, kind + ": no error");
}
} // namespace

int TestSAVRVectors(int, char*[])
{
  savr_scenes::Expectations expect;

  vtkSmartPointer<vtkImageData> image = savr_scenes::Wavelet(12);
  AddVectors(image->GetPointData(), image->GetPointData()->GetScalars());
  Compare(expect, "image", image, false, { 40.0, 310.0 });

  vtkSmartPointer<vtkUnstructuredGrid> mesh = savr_scenes::TetrahedralWavelet(16);
  AddVectors(mesh->GetPointData(), mesh->GetPointData()->GetScalars());
  Compare(expect, "tetrahedra", mesh, false, { 40.0, 310.0 });

  vtkSmartPointer<vtkOverlappingAMR> amr = savr_scenes::GaussianPulse();
  for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
  {
    for (unsigned int id = 0; id < amr->GetNumberOfDataSets(level); ++id)
    {
      vtkUniformGrid* grid = amr->GetDataSet(level, id);
      AddVectors(grid->GetCellData(), grid->GetCellData()->GetArray("Gaussian-Pulse"));
    }
  }
  Compare(expect, "AMR", amr, true, { 0.0, 1.15 });
  const Drawn refused = Draw(amr, "v", true, vtkSAVRVolumeMapper::DISABLED, 0, { 0.0, 1.15 });
  std::printf("AMR vector array without a vector mode: %d error(s): %s\n", refused.Errors,
    refused.LastError.c_str());
  expect(refused.Errors == 1 && refused.LastError.find("VectorMode") != std::string::npos,
    "an AMR vector array without a vector mode is refused, naming VectorMode");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

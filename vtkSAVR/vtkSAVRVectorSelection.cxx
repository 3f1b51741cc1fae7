#include "vtkSAVRVectorSelection.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>

namespace
{
// Whether `mode` draws `array` as a new one-component array (else it is drawn as it is).
bool Derives(vtkDataArray* array, int mode)
{
  return array && array->GetNumberOfComponents() > 1 &&
         (mode == vtkSAVRVectorSelection::kMagnitude || mode == vtkSAVRVectorSelection::kComponent);
}

template <typename T, typename Out>
void Magnitudes(const T* in, vtkIdType tuples, int components, Out* out)
{
  for (vtkIdType i = 0; i < tuples; ++i)
  {
    double sum = 0.0;
    for (int c = 0; c < components; ++c)
    {
      const double v = static_cast<double>(in[i * components + c]);
      sum += v * v;
    }
    out[i] = static_cast<Out>(std::sqrt(sum));
  }
}
} // namespace

namespace vtkSAVRVectorSelection
{
int Effective(int mode, vtkVolumeProperty* property)
{
  return property && property->GetIndependentComponents() ? mode : kDisabled;
}

vtkSmartPointer<vtkDataArray> Select(vtkDataArray* array, int mode, int component)
{
  if (!Derives(array, mode))
  {
    return array;
  }
  const vtkIdType tuples = array->GetNumberOfTuples();
  const int components = array->GetNumberOfComponents();
  vtkSmartPointer<vtkDataArray> selected;
  if (mode == kMagnitude)
  {
    // Summed in double: the magnitudes of floats near their largest stay finite.
    if (array->GetDataType() == VTK_DOUBLE)
    {
      auto out = vtkSmartPointer<vtkDoubleArray>::New();
      out->SetNumberOfTuples(tuples);
      Magnitudes(static_cast<const double*>(array->GetVoidPointer(0)), tuples, components,
        out->GetPointer(0));
      selected = out;
    }
    else
    {
      auto out = vtkSmartPointer<vtkFloatArray>::New();
      out->SetNumberOfTuples(tuples);
      switch (array->GetDataType())
      {
        vtkTemplateMacro(Magnitudes(static_cast<const VTK_TT*>(array->GetVoidPointer(0)), tuples,
          components, out->GetPointer(0)));
      }
      selected = out;
    }
  }
  else
  {
    selected = vtkSmartPointer<vtkDataArray>::Take(array->NewInstance());
    selected->SetNumberOfComponents(1);
    selected->SetNumberOfTuples(tuples);
    selected->CopyComponent(0, array, std::min(std::max(component, 0), components - 1));
  }
  selected->SetName(array->GetName());
  return selected;
}

vtkDataArray* Cache::Select(vtkDataArray* array, int mode, int component)
{
  if (!Derives(array, mode))
  {
    this->Selected = nullptr;
    this->Source = nullptr;
    return array;
  }
  if (array != this->Source || array->GetMTime() != this->SourceTime || mode != this->Mode ||
      (mode == kComponent && component != this->Component) || !this->Selected)
  {
    this->Selected = vtkSAVRVectorSelection::Select(array, mode, component);
    this->Source = array;
    this->SourceTime = array->GetMTime();
    this->Mode = mode;
    this->Component = component;
  }
  return this->Selected;
}
}

// Private to the module: a vector array drawn as one component, as vtkSmartVolumeMapper's vector
// mode draws it: by its magnitude, or by one of its components. Applies where the volume
// property's components are independent (dependent components are colours, drawn as such).
#ifndef vtkSAVRVectorSelection_h
#define vtkSAVRVectorSelection_h

#include "vtkSmartPointer.h"
#include "vtkType.h"

class vtkDataArray;
class vtkVolumeProperty;

namespace vtkSAVRVectorSelection
{
/// vtkSmartVolumeMapper's values: DISABLED (-1), MAGNITUDE (0), COMPONENT (1).
constexpr int kDisabled = -1;
constexpr int kMagnitude = 0;
constexpr int kComponent = 1;

/// The mode that applies: `mode`, or kDisabled where `property`'s components are dependent.
int Effective(int mode, vtkVolumeProperty* property);

/// `array` as the one component `mode` draws: `array` itself where it has one component or the
/// mode is kDisabled; else a new array of the same name and tuples, holding the magnitudes (as
/// doubles for a double array, floats otherwise; NaN where a component is) or the component
/// `component` (clamped to the array's; in the array's own type, so that integers stay exact).
vtkSmartPointer<vtkDataArray> Select(vtkDataArray* array, int mode, int component);

/// Select's last result, made again only when the array (or its modification time), the mode or
/// the component changed: the array the samplers share stays the same object between renders.
class Cache
{
public:
  vtkDataArray* Select(vtkDataArray* array, int mode, int component);

private:
  vtkDataArray* Source = nullptr;
  vtkMTimeType SourceTime = 0;
  int Mode = kDisabled;
  int Component = 0;
  vtkSmartPointer<vtkDataArray> Selected;
};
}

#endif

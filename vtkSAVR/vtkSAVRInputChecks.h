// Private to the module: what makes an input, a transfer function, a camera or a viewport
// impossible to draw, as the message the mapper reports (empty when there is nothing wrong).
#ifndef vtkSAVRInputChecks_h
#define vtkSAVRInputChecks_h

#include <string>

class vtkCamera;
class vtkDataArray;
class vtkVolumeProperty;

namespace vtkSAVRInputChecks
{
/// `value` as %g would print it, so that tiny and huge values keep their digits.
std::string Number(double value);

/// Bounds VTK computed for the input that are not finite, or too small for VTK to draw.
std::string BoundsProblem(const double bounds[6]);

/// A double range that a float cannot hold when `storedAsFloat`; for data stored as floats, or
/// of several components, a range whose span overflows or is too small to encode. (Other data
/// is checked by the values its codes cover: CodedRangeProblem.)
std::string ScalarRangeProblem(vtkDataArray* scalars, bool storedAsFloat);

/// Values to code, `values` (the scalars' range, within the transfer functions' domain when
/// `windowed`), whose span overflows, is too small to encode, or that float samples cannot hold.
std::string CodedRangeProblem(const double values[2], bool windowed);

/// A node that is not finite in a function of `property` read for `components` components.
std::string TransferFunctionProblem(vtkVolumeProperty* property, int components);

/// Why the camera's projection cannot be inverted, for data of diagonal `dataSize`.
std::string CameraProblem(vtkCamera* camera, double dataSize);

/// Why frames sample `used` apart when `asked` would take more than `limit` samples in one.
std::string CoarsenedStepNote(double asked, double used, unsigned long long limit);

/// Why slice blending cannot draw `property`'s slice function: it must be a vtkPlane with a
/// finite origin and a finite normal that is not zero. Empty when it can.
std::string SliceProblem(vtkVolumeProperty* property);

/// Images of a `width` x `height` viewport that need `needed` bytes, more than `budget`.
std::string BudgetProblem(
  int width, int height, unsigned long long needed, unsigned long long budget);
}

#endif

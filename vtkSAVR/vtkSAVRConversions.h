// Private to the module: VTK's types as the engine's.
#ifndef vtkSAVRConversions_h
#define vtkSAVRConversions_h

#include "blend/Integrator.h"
#include "image/GridSampler.h"

#include <Eigen/Core>

#include <vector>

class vtkMatrix4x4;
class vtkObject;
class vtkPlaneCollection;
class vtkVolumeProperty;

namespace vtkSAVRConversions
{
/// The engine's type for a VTK scalar type code; false when there is none.
bool ToScalarType(int vtkType, savr::ScalarType& type);

/// The engine's blend mode for a vtkVolumeMapper blend mode; false when there is none.
bool ToBlendMode(int vtkMode, savr::BlendMode& mode);

/// Each plane of `planes` (none for null) as (normal, -normal . origin), keeping the side its
/// normal points to; false when a normal or origin is not finite.
bool ToPlanes(vtkPlaneCollection* planes, std::vector<Eigen::Vector4d>& out);

/// The matrix's elements (the identity for null).
Eigen::Matrix4d ToEigen(vtkMatrix4x4* matrix);

/// Component `c`'s colour function: its gray (vtkPiecewiseFunction) or its RGB
/// (vtkColorTransferFunction) one, as its colour channels say.
vtkObject* ColorFunction(vtkVolumeProperty* property, int c);
}

#endif

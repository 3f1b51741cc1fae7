// Private to the module: VTK's types as the engine's.
#ifndef vtkSAVRConversions_h
#define vtkSAVRConversions_h

#include "GridSampler.h"

#include <Eigen/Core>

class vtkMatrix4x4;

namespace vtkSAVRConversions
{
/// The engine's type for a VTK scalar type code; false when there is none.
bool ToScalarType(int vtkType, savr::ScalarType& type);

/// The matrix's elements (the identity for null).
Eigen::Matrix4d ToEigen(vtkMatrix4x4* matrix);
}

#endif

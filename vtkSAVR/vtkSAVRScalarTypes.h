// Private to the module: VTK scalar type codes as the engine's scalar types.
#ifndef vtkSAVRScalarTypes_h
#define vtkSAVRScalarTypes_h

#include "GridSampler.h"

namespace vtkSAVRScalarTypes
{
/// The engine's type for a VTK scalar type code; false when there is none.
bool ToScalarType(int vtkType, savr::ScalarType& type);
}

#endif

#include "vtkSAVRVTKVersions.h"

#include "vtkCellTypes.h"
#include "vtkNew.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVersionMacros.h"

std::vector<unsigned char> vtkSAVRVTKVersions::DistinctCellTypes(vtkUnstructuredGrid* grid)
{
  std::vector<unsigned char> types;
  // VTK 9.2 deprecates the vtkCellTypes form.
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 0)
  if (vtkUnsignedCharArray* distinct = grid->GetDistinctCellTypesArray())
  {
    for (vtkIdType i = 0; i < distinct->GetNumberOfValues(); ++i)
    {
      types.push_back(distinct->GetValue(i));
    }
  }
#else
  vtkNew<vtkCellTypes> distinct;
  grid->GetCellTypes(distinct);
  for (vtkIdType i = 0; i < distinct->GetNumberOfTypes(); ++i)
  {
    types.push_back(distinct->GetCellType(i));
  }
#endif
  return types;
}

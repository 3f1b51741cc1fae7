// Private to the module: every call whose form differs between the VTK versions the module builds
// against (9.1 on Debian 12, ParaView 5.11's 9.2, 9.3 on Debian 13 and in ParaView 5.13), so that
// version checks stand here and nowhere else.
#ifndef vtkSAVRVTKVersions_h
#define vtkSAVRVTKVersions_h

#include <vector>

class vtkUnstructuredGrid;

namespace vtkSAVRVTKVersions
{
/// The distinct VTK cell types of `grid` (the grid caches them: asking every frame does not walk
/// the cells again).
std::vector<unsigned char> DistinctCellTypes(vtkUnstructuredGrid* grid);
}

#endif

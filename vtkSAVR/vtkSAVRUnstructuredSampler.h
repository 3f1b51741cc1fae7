/**
 * @class   vtkSAVRUnstructuredSampler
 * @brief   Turns a vtkUnstructuredGrid's scalars into a SAVR sampler (or a vtkStructuredGrid's
 * or vtkRectilinearGrid's, as hexahedra or voxels).
 *
 * Tetrahedra, hexahedra, voxels, wedges and pyramids, mixed freely, with point or cell scalars,
 * are sampled natively (nothing is tetrahedralized): each cell interpolates with its own shape
 * functions, and rays find their entry cell with a bounding-volume hierarchy and then walk
 * across shared faces, leaving and re-entering non-convex meshes and meshes with holes. Points
 * outside every cell are transparent. Cells of other types are left out (see
 * GetNumberOfSkippedCells). A curvilinear (structured) grid's cells are its hexahedra and a
 * rectilinear grid's its voxels, walked the same way; blanked cells of a structured grid are
 * transparent (and not counted as skipped).
 *
 * The sampler keeps its own copy of the points (placed in world space by the volume's matrix),
 * the cells and the scalars as 32-bit floats.
 */
#ifndef vtkSAVRUnstructuredSampler_h
#define vtkSAVRUnstructuredSampler_h

#include "vtkObject.h"
#include "vtkSAVRModule.h" // For export macro

#include <memory> // For std::shared_ptr
#include <string> // For std::string

class vtkDataArray;
class vtkMatrix4x4;
class vtkDataSet;

namespace savr
{
class Sampler;
}

class VTKSAVR_EXPORT vtkSAVRUnstructuredSampler : public vtkObject
{
public:
  static vtkSAVRUnstructuredSampler* New();
  vtkTypeMacro(vtkSAVRUnstructuredSampler, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the sampler for `scalars` (point data, or cell data when `cellData` is true) of
   * `grid`, placed by `volumeMatrix` (may be null). Returns false, with the reason in
   * GetErrorMessage(), when the input cannot be sampled.
   */
  bool Build(vtkDataSet* grid, vtkDataArray* scalars, bool cellData, vtkMatrix4x4* volumeMatrix);

  /// The sampler built last, or null. Its interface, sampler/Sampler.h, is installed with the
  /// engine's headers (include/vtkSAVR/savr; link vtkSAVR::savrCore).
  std::shared_ptr<const savr::Sampler> GetSampler() const { return this->Sampler; }

  /// Why the last Build failed.
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

  /// Cells the last Build left out (unsupported types, non-finite points).
  vtkIdType GetNumberOfSkippedCells() const { return this->SkippedCells; }

  /// The median over cells of a cell's longest bounding-box edge, in world units: the mesh's
  /// typical cell size.
  double GetTypicalCellSize() const { return this->TypicalCellSize; }

  /// The diagonal of the bounding box of the mesh's finite points, in world units.
  double GetDiagonal() const { return this->Diagonal; }

protected:
  vtkSAVRUnstructuredSampler();
  ~vtkSAVRUnstructuredSampler() override;

private:
  vtkSAVRUnstructuredSampler(const vtkSAVRUnstructuredSampler&) = delete;
  void operator=(const vtkSAVRUnstructuredSampler&) = delete;

  std::shared_ptr<const savr::Sampler> Sampler;
  std::string ErrorMessage;
  vtkIdType SkippedCells = 0;
  double TypicalCellSize = 0.0;
  double Diagonal = 0.0;
};

#endif

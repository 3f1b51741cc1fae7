/**
 * @class   vtkSAVRAMRSampler
 * @brief   Turns a vtkOverlappingAMR's scalars into a SAVR sampler.
 *
 * The sampler reads the blocks' arrays in place (nothing is copied or resampled). A point is
 * sampled on the finest level whose AMR box contains it; cells blanked as hidden where no finer
 * block covers them are holes. Linear interpolation is trilinear on that level, reading values
 * across block boundaries from the neighbouring block, and, where the level ends, from the
 * coarser level interpolated at the value's position: no seams between blocks of a level. The
 * block index (level-0 bins and each block's overlapping children) is built once per Build.
 *
 * Blocks that are not present (null, as on other ranks of a distributed hierarchy) are left out.
 * Every present block must carry the selected array, with one component and one type.
 */
#ifndef vtkSAVRAMRSampler_h
#define vtkSAVRAMRSampler_h

#include "vtkObject.h"
#include "vtkSAVRModule.h"   // For export macro
#include "vtkSmartPointer.h" // For the selected arrays

#include <memory> // For std::shared_ptr
#include <string> // For std::string
#include <vector> // For the selected arrays

class vtkDataArray;
class vtkMatrix4x4;
class vtkOverlappingAMR;

namespace savr
{
class Sampler;
}

class VTKSAVR_EXPORT vtkSAVRAMRSampler : public vtkObject
{
public:
  static vtkSAVRAMRSampler* New();
  vtkTypeMacro(vtkSAVRAMRSampler, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the sampler for the array chosen as vtkAbstractMapper::GetScalars chooses it
   * (`scalarMode`, `arrayAccessMode`, `arrayId`, `arrayName`) on every block of `amr`, placed by
   * `volumeMatrix` (may be null), with `interpolationType` VTK_NEAREST_INTERPOLATION or
   * VTK_LINEAR_INTERPOLATION. A block's array of several components is sampled as
   * vtkSAVRVolumeMapper's `vectorMode` and `vectorComponent` say (its magnitude, or one of its
   * components; DISABLED, -1, refuses it). Returns false, with the reason in GetErrorMessage(),
   * when the input cannot be sampled.
   */
  bool Build(vtkOverlappingAMR* amr, int scalarMode, int arrayAccessMode, int arrayId,
    const char* arrayName, vtkMatrix4x4* volumeMatrix, int interpolationType, int vectorMode = -1,
    int vectorComponent = 0);

  /// The sampler built last, or null. Its interface, sampler/Sampler.h, is installed with the
  /// engine's headers (include/vtkSAVR/savr; link vtkSAVR::savrCore).
  std::shared_ptr<const savr::Sampler> GetSampler() const { return this->Sampler; }

  /// Why the last Build failed.
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

  /// Cell edge of the coarsest and of the finest level present, in world units (after Build).
  double GetCoarsestSpacing() const { return this->CoarsestSpacing; }
  double GetFinestSpacing() const { return this->FinestSpacing; }

protected:
  vtkSAVRAMRSampler();
  ~vtkSAVRAMRSampler() override;

private:
  vtkSAVRAMRSampler(const vtkSAVRAMRSampler&) = delete;
  void operator=(const vtkSAVRAMRSampler&) = delete;

  std::shared_ptr<const savr::Sampler> Sampler;
  std::vector<vtkSmartPointer<vtkDataArray>> Selected; // blocks' vector arrays as one component
  std::string ErrorMessage;
  double CoarsestSpacing = 0.0;
  double FinestSpacing = 0.0;
};

#endif

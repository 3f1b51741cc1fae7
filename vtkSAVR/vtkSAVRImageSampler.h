/**
 * @class   vtkSAVRImageSampler
 * @brief   Turns a vtkImageData's scalars into a SAVR sampler.
 *
 * The sampler shares the image's scalar array (nothing is copied) and places it in world space
 * with the image's origin, spacing and direction matrix and the volume's matrix. Point and cell
 * scalars of every numeric VTK type are accepted; they must have one component.
 */
#ifndef vtkSAVRImageSampler_h
#define vtkSAVRImageSampler_h

#include "vtkObject.h"
#include "vtkSAVRModule.h" // For export macro

#include <memory> // For std::shared_ptr
#include <string> // For std::string

class vtkDataArray;
class vtkImageData;
class vtkMatrix4x4;

namespace savr
{
class Sampler;
}

class VTKSAVR_EXPORT vtkSAVRImageSampler : public vtkObject
{
public:
  static vtkSAVRImageSampler* New();
  vtkTypeMacro(vtkSAVRImageSampler, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Builds the sampler for `scalars` (point data, or cell data when `cellData` is true) of
   * `image`, placed by `volumeMatrix` (data to world; may be null), with `interpolationType`
   * VTK_NEAREST_INTERPOLATION or VTK_LINEAR_INTERPOLATION. Returns false, and leaves the reason
   * in GetErrorMessage(), when the input cannot be sampled.
   */
  bool Build(vtkImageData* image, vtkDataArray* scalars, bool cellData, vtkMatrix4x4* volumeMatrix,
    int interpolationType);

  /// The sampler built last, or null.
  std::shared_ptr<const savr::Sampler> GetSampler() const { return this->Sampler; }

  /// Why the last Build failed.
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

protected:
  vtkSAVRImageSampler();
  ~vtkSAVRImageSampler() override;

private:
  vtkSAVRImageSampler(const vtkSAVRImageSampler&) = delete;
  void operator=(const vtkSAVRImageSampler&) = delete;

  std::shared_ptr<const savr::Sampler> Sampler;
  std::string ErrorMessage;
};

#endif

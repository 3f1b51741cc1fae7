/**
 * @class   vtkSAVRImageSampler
 * @brief   Turns a vtkImageData's scalars into a SAVR sampler.
 *
 * The sampler shares the image's scalar array (nothing is copied) and places it in world space
 * with the image's origin, spacing and direction matrix and the volume's matrix. Point and cell
 * scalars of every numeric VTK type are accepted, with one to four components. Several
 * components are sampled separately, each quantized to 8 bits over its range, and stored in
 * pairs as 16-bit codes (savr::ComponentSampler), so that their transfer functions can be
 * combined, and edited, after sampling.
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
   * VTK_NEAREST_INTERPOLATION or VTK_LINEAR_INTERPOLATION. With several components, shading
   * and gradient opacity use each component's own gradient when `independentComponents`, else
   * the last's (the one that sets opacity). Dependent components must be two (luminance, alpha) or four (RGBA). Returns
   * false, and leaves the reason in GetErrorMessage(), when the input cannot be sampled.
   */
  bool Build(vtkImageData* image, vtkDataArray* scalars, bool cellData, vtkMatrix4x4* volumeMatrix,
    int interpolationType, bool independentComponents = true);

  /// Components of the scalars the last successful Build sampled (1 to 4), or 0.
  int GetNumberOfComponents() const { return this->NumberOfComponents; }

  /// The smallest voxel edge of the image built last, in world units (after Build).
  double GetSmallestSpacing() const { return this->SmallestSpacing; }

  /// The sampler built last, or null. Its interface, sampler/Sampler.h, is installed with the
  /// engine's headers (include/vtkSAVR/savr; link vtkSAVR::savrCore).
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
  int NumberOfComponents = 0;
  double SmallestSpacing = 0.0;
};

#endif

/**
 * @class   vtkSAVRParticleSampler
 * @brief   Turns the points of a vtkPolyData and a scalar array into a SAVR particle sampler.
 *
 * Particles are the points of a vtkPolyData, or of a vtkUnstructuredGrid whose cells are all
 * vertices or poly-vertices (or that has points and no cells); see Particles(). Each point is a
 * particle: its scalar, a radius h (one for all, or a point array of radii) and
 * a kernel W(r, h) make a field, either normalized (the kernel-weighted mean of the values of the
 * particles that reach a point, as vtkSPHInterpolator's Shepard normalization gives) or summed
 * (a density). Kernels: a Gaussian exp(-r^2 / 2h^2) cut at 3h (radial basis function particle
 * models), and the SPH cubic (cutoff 2h) and quintic (cutoff 3h) splines as vtkSPHCubicKernel
 * and vtkSPHQuinticKernel define them in 3D (h their SpatialStep). Where no particle reaches,
 * the volume is empty. Points are placed in world space by the volume's matrix, and radii are
 * scaled by its mean scale.
 */
#ifndef vtkSAVRParticleSampler_h
#define vtkSAVRParticleSampler_h

#include "vtkObject.h"
#include "vtkSAVRModule.h" // For export macro

#include <memory> // For std::shared_ptr
#include <string> // For std::string

class vtkDataArray;
class vtkDataObject;
class vtkMatrix4x4;
class vtkPointSet;

namespace savr
{
class Sampler;
}

class VTKSAVR_EXPORT vtkSAVRParticleSampler : public vtkObject
{
public:
  static vtkSAVRParticleSampler* New();
  vtkTypeMacro(vtkSAVRParticleSampler, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Kernel
  {
    GAUSSIAN = 0,
    SPH_CUBIC = 1,
    SPH_QUINTIC = 2
  };

  /**
   * Builds the sampler for the point scalars `scalars` of `points`, placed by `volumeMatrix`
   * (may be null). `radius` is every particle's h unless `radii` (one value per point) is given;
   * a radius of 0 or less picks one: the mean distance between particles, (volume of the points'
   * bounding box / points)^(1/3). Returns false, with the reason in GetErrorMessage(), when the
   * input cannot be sampled (no points, a radius array of the wrong length, a radius that is not
   * finite and positive, no particle with a finite position and value).
   */
  bool Build(vtkPointSet* points, vtkDataArray* scalars, double radius, vtkDataArray* radii,
    int kernel, bool normalized, vtkMatrix4x4* volumeMatrix);

  /// As above, with the radii in the point array named `radiiName` (none when null or empty; a
  /// name the points do not have fails).
  bool Build(vtkPointSet* points, vtkDataArray* scalars, double radius, const char* radiiName,
    int kernel, bool normalized, vtkMatrix4x4* volumeMatrix);

  /// `input` as particles when it is some: a vtkPolyData (its points; cells are ignored), or a
  /// vtkUnstructuredGrid with points whose cells are all VTK_VERTEX or VTK_POLY_VERTEX, or that
  /// has none. Null for anything else (a grid with any other cell is a mesh).
  static vtkPointSet* Particles(vtkDataObject* input);

  /// The sampler built last, or null. Its interface, sampler/Sampler.h, is installed with the
  /// engine's headers (include/vtkSAVR/savr; link vtkSAVR::savrCore).
  std::shared_ptr<const savr::Sampler> GetSampler() const { return this->Sampler; }

  /// Why the last Build failed.
  const std::string& GetErrorMessage() const { return this->ErrorMessage; }

  /// Particles the last Build left out (a non-finite position or value).
  vtkIdType GetNumberOfSkippedParticles() const { return this->SkippedParticles; }

  /// The range of the field the last Build made: the values' extremes for the kernel-weighted
  /// mean, bounds on the field for the kernel-weighted sum (a density when the values are 1).
  /// {0, 0} before a successful Build.
  void GetFieldRange(double range[2]) const;

  /// The median particle radius of the last Build, in world units.
  double GetTypicalRadius() const { return this->TypicalRadius; }

  /// The radius Build picks when given none: the mean distance between the particles, (volume of
  /// the box of their finite positions / points)^(1/3) (degenerate edges left out), in the
  /// points' coordinates; 1 when there is no box.
  static double AutomaticRadius(vtkPointSet* points);

  /// The box of the points' finite positions grown by the kernel's reach (its cutoff times the
  /// largest radius), in the points' coordinates: what the particles can fill. Uninitialized
  /// when no position is finite.
  static void SupportBounds(
    vtkPointSet* points, double radius, const char* radiiName, int kernel, double bounds[6]);

protected:
  vtkSAVRParticleSampler();
  ~vtkSAVRParticleSampler() override;

private:
  vtkSAVRParticleSampler(const vtkSAVRParticleSampler&) = delete;
  void operator=(const vtkSAVRParticleSampler&) = delete;

  std::shared_ptr<const savr::Sampler> Sampler;
  std::string ErrorMessage;
  vtkIdType SkippedParticles = 0;
  double TypicalRadius = 0.0;
};

#endif

// Private to the module: the mapper's input as an engine sampler. Holds one adaptor per kind of
// input (image, AMR hierarchy, mesh, particles), builds the sampler of the kind the input is, and
// says what spacing sets the default step. Whether the input changed is decided by
// vtkSAVRFrameChanges; this class only builds.
#ifndef vtkSAVRInputSamplers_h
#define vtkSAVRInputSamplers_h

#include "vtkNew.h"

#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkDataObject;
class vtkMatrix4x4;
class vtkSAVRAMRSampler;
class vtkSAVRImageSampler;
class vtkSAVRParticleSampler;
class vtkSAVRUnstructuredSampler;

namespace savr
{
class Sampler;
}

class vtkSAVRInputSamplers
{
public:
  vtkSAVRInputSamplers();
  ~vtkSAVRInputSamplers();
  vtkSAVRInputSamplers(const vtkSAVRInputSamplers&) = delete;
  vtkSAVRInputSamplers& operator=(const vtkSAVRInputSamplers&) = delete;

  /// Inputs whose cells are walked by the unstructured sampler: unstructured grids (but those of
  /// vertices only, which are particles), and curvilinear and rectilinear grids as their
  /// hexahedra and voxels.
  static bool IsMesh(vtkDataObject* input);

  /// Whether the mapper can sample `input` at all: an image, an AMR hierarchy, a mesh or
  /// particles.
  static bool Supported(vtkDataObject* input);

  /// What a sampler is built from besides the input: the scalars the mapper selected (for AMR,
  /// its array selection instead), the volume's matrix, the property's interpolation and
  /// component independence, and the particles' settings.
  struct Request
  {
    vtkDataArray* Scalars = nullptr;
    bool CellData = false;
    vtkMatrix4x4* VolumeMatrix = nullptr;
    int Interpolation = 0;
    bool IndependentComponents = true;
    int ScalarMode = 0;
    int ArrayAccessMode = 0;
    int ArrayId = -1;
    const char* ArrayName = nullptr;
    int VectorMode = -1; // AMR blocks' vector arrays (vtkSAVRVectorSelection)
    int VectorComponent = 0;
    double ParticleRadius = 0.0;
    const char* ParticleRadiusArrayName = nullptr;
    int ParticleKernel = 0;
    bool ParticleNormalized = true;
  };

  /// What Build made: the sampler (null on failure, with the reason in Error), the finest cell
  /// edge in world units, the step a frame takes by default, the step automatic refinement
  /// reaches (a quarter of the finest edge, finer for meshes of few cells), and warnings about
  /// parts of the input left out.
  struct Result
  {
    std::shared_ptr<const savr::Sampler> Sampler;
    double SmallestSpacing = 0.0;
    double DefaultStep = 0.0;
    double FinestStep = 0.0;
    std::string Error;
    std::vector<std::string> Warnings;
  };

  /// Builds the sampler of `input`, which Supported accepts.
  Result Build(vtkDataObject* input, const Request& request);

  /// Components of the last image built (1 for other inputs).
  int GetNumberOfImageComponents() const;

private:
  vtkNew<vtkSAVRImageSampler> Image;
  vtkNew<vtkSAVRAMRSampler> AMR;
  vtkNew<vtkSAVRUnstructuredSampler> Unstructured;
  vtkNew<vtkSAVRParticleSampler> Particles;
};

#endif

// Private to the module: what changed since the last frame, and so what this frame does.
//
// Each aspect (the input, cropping, the view, the tables of the volume property) is kept as a
// fingerprint of the values it depends on. A stage asks whether its aspect changed; the answer
// records the new fingerprint, and NextAction() turns the frame's answers into what the frame
// does with the stored samples: start over (the view changed: FrameLoop::Reset), add a frame,
// blend them again, or show the last image as it is.
#ifndef vtkSAVRFrameChanges_h
#define vtkSAVRFrameChanges_h

#include "blend/ShadingTable.h"
#include "frame/FrameLoop.h"

#include <optional>
#include <vector>

class vtkDataArray;
class vtkDataObject;
class vtkMatrix4x4;
class vtkObject;
class vtkPiecewiseFunction;
struct vtkSAVRMapperSettings;
class vtkVolumeProperty;

namespace savr
{
class ComponentSampler;
}

class vtkSAVRFrameChanges
{
public:
  enum class Input
  {
    Unchanged,
    Changed,
    KnownBad // the input that failed to build last time: not to be scanned again
  };

  /// What a frame does with the stored samples.
  enum class Action
  {
    SinglePass, // interacting: one pass, nothing stored
    Accumulate, // add a frame of samples
    Reblend,    // every frame is taken, but the image shown is not their current blend
    Reuse       // show the last image again
  };

  /// Starts a frame's answers.
  void BeginFrame();

  /**
   * The input as the sampler would be built from it: the data object, its scalars, the volume's
   * placement and the interpolation (for AMR, the settings that select each block's array).
   * AcceptInput or RejectInput then say whether the sampler built from a changed one.
   */
  Input CompareInput(const vtkSAVRMapperSettings& mapper, vtkDataObject* input,
    vtkDataArray* scalars, int cellFlag, vtkVolumeProperty* property, vtkMatrix4x4* volumeMatrix);
  void AcceptInput();
  void RejectInput();

  /// The cropping planes and flags in world space (only the flag while cropping is off).
  bool CroppingChanged(const vtkSAVRMapperSettings& mapper, vtkMatrix4x4* volumeMatrix);

  /// What the particles' support bounds depend on: `particles` (address and modification time),
  /// the mapper's radius, radii array name and kernel.
  bool ParticleBoundsChanged(const vtkSAVRMapperSettings& mapper, vtkObject* particles);

  /**
   * Whether the stored samples must be discarded: the input, cropping, clipping planes, viewport
   * (`origin` and the view's size), sampling `settings`, blend mode, shading, gradient opacity,
   * or the depth of the geometry changed, or the camera's matrix `worldToNDC` moved a corner of
   * the data's world `bounds` on screen by more than a twentieth of a pixel (or its depth).
   */
  bool ViewChanged(const vtkSAVRMapperSettings& mapper, vtkVolumeProperty* property,
    const savr::View& view, vtkMatrix4x4* worldToNDC, const double bounds[6], const int origin[2],
    const savr::FrameSettings& settings);
  /// The next ViewChanged answers yes.
  void ForgetView();

  /// The transfer functions, or the encoding of the stored samples they are tabulated over.
  /// `components` is the sampler of several components, or null.
  bool TransferFunctionChanged(vtkVolumeProperty* property, const savr::SampleEncoding& encoding,
    bool preIntegration, const savr::ComponentSampler* components, double colorScale,
    bool opacityIsAttenuation);
  bool ShadingChanged(vtkVolumeProperty* property, int components,
    const std::vector<savr::Light>& lights, const Eigen::Vector3d& toViewer, bool twoSided);
  /// The iso values, or the transfer functions that colour them.
  bool IsoSurfacesChanged(vtkVolumeProperty* property);
  /// The gradient-opacity factors as tabulated (`sets` of 256) and each set's magnitude scale.
  bool GradientOpacityChanged(const double* factors, const double* magnitudeScales, int sets);

  /// What this frame does, given the answers above.
  Action NextAction(bool interactive, bool complete, savr::Phase loopPhase) const;

private:
  using Key = std::vector<double>;

  /// What decides a view's samples besides the camera, compared by value: the input and
  /// cropping fingerprints, the clipping planes, the viewport, the engine's frame settings
  /// (savr::SameSampling), the blend mode and, for slices, the plane.
  struct Sampling
  {
    Key Data;
    Key Cropping;
    Key ClippingPlanes;
    int Viewport[4] = { 0, 0, 0, 0 }; // width, height, origin
    savr::FrameSettings Settings;
    int BlendMode = -1;
    Key SlicePlane;
    bool operator==(const Sampling& other) const;
  };

  Key DataKey;
  Key PendingDataKey;
  Key FailedDataKey;
  Key CroppingKey;
  Key ParticleBoundsKey;
  std::optional<Sampling> LastSampling; // none: the next ViewChanged answers yes
  Key ViewKey;
  std::vector<float> Depth;
  Key TableKey;
  Key ShadingKey;
  Key IsoKey;
  Key GradientOpacityKey;
  // This frame changed a table the stored samples are blended through.
  bool BlendChanged = false;
};

#endif

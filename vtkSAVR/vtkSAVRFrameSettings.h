// Private to the module: the mapper's checks and defaults in one place. Resolve turns the
// mapper's settings, the volume property and what the input's sampler says into the engine's
// blend mode and frame settings, or into the reason the frame cannot be drawn. Change detection
// (vtkSAVRFrameChanges) compares the settings it gives by value.
#ifndef vtkSAVRFrameSettings_h
#define vtkSAVRFrameSettings_h

#include "blend/BlendTypes.h"
#include "frame/FrameSettings.h"

#include <cstddef>
#include <string>

class vtkSAVRPropertyTables;
struct vtkSAVRMapperSettings;
class vtkVolumeProperty;

namespace savr
{
class ComponentSampler;
class Sampler;
}

namespace vtkSAVRFrameSettings
{
/// Samples one frame takes at most over the rays' lengths (plus one per ray): as many as a
/// 512x512 view filled by a 256^3 image takes face-on at its voxel spacing, about a second on two
/// cores. Finer steps are coarsened for each frame.
constexpr std::size_t kMaxSamplesPerFrame = std::size_t(1) << 26;

/// What the input's sampler says, as the frame settings depend on it.
struct Data
{
  const savr::Sampler* Sampler = nullptr;             // what frames sample (cropped or not)
  const savr::ComponentSampler* Components = nullptr; // several components' sampler, or null
  int NumberOfComponents = 1;
  double SmallestSpacing = 0.0;   // the finest cell edge, in world units
  double DefaultStep = 0.0;       // SampleDistance's default
  double FinestStep = 0.0;        // the step automatic refinement reaches
  const double* Bounds = nullptr; // the volume's, in world units
};

struct Result
{
  std::string Error; // empty when the frame can be drawn
  savr::BlendMode Mode = savr::BlendMode::Composite;
  /// All but what the view reserves (ReservedBytes), which the view's size decides.
  savr::FrameSettings Settings;
  bool GradientOpacity = false; // gradient opacity is in use (tabulated into `tables`)
  double Diagonal = 0.0;        // of the bounds
};

/// Whether the cropping planes (xmin, xmax, ymin, ymax, zmin, zmax) are all finite (a NaN plane
/// would make every frame look changed; Resolve refuses it).
bool CroppingPlanesFinite(const double planes[6]);

/**
 * The blend mode (pre-integrated, grey intensity and automatic pre-integration included), the
 * rules for several components, slice planes, transfer functions and cropping planes, the
 * default step and frame count, the step's bounds, and the settings for gradients, shading,
 * fine codes, memory and threads. Tabulates gradient opacity into `tables`, whose magnitude
 * scales the settings carry.
 */
Result Resolve(const vtkSAVRMapperSettings& mapper, vtkVolumeProperty* property, const Data& data,
  vtkSAVRPropertyTables& tables);
}

#endif

#pragma once
// Particle scenes shared by the particle benchmark, the convergence report and the tests: a
// clustered cloud of the kind cosmology and SPH simulations produce, and a transfer function
// for it.

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

class vtkImageData;
class vtkVolumeProperty;

namespace savr_scenes
{

/// `points` particles around `clusters` centres spread uniformly over [-50, 50]^3. Each cluster
/// has a scale s between 1.5 and 8 (log-uniform) and a brightness b in [0.4, 1]; a particle
/// lies in a random direction at the distance s (u^(-1/2) - 1) from its centre (u uniform in
/// (0, 1]: a power law, dense at the centre with a long tail), cut at 6 s. The point array
/// "value" is b exp(-d / s), in (0, 1]. The same `seed` gives the same cloud on every machine.
vtkSmartPointer<vtkPolyData> ClusteredCloud(
  long long points, int clusters = 300, unsigned seed = 2017);

/// Colours from blue through purple and orange to white over [0, 1]; the clusters' faint tails
/// (below 0.1) transparent, opacity rising to 0.8 per unit length at 1.
void CloudProperty(vtkVolumeProperty* property);

/// The path VTK users take to draw particles as a volume: `cloud` resampled by
/// vtkSPHInterpolator (the SPH cubic kernel of radius `radius`, Shepard normalization, 0 where no
/// particle reaches) to an image of `points`^3 points over `bounds`, its active scalars the
/// cloud's.
vtkSmartPointer<vtkImageData> ResampleCubic(
  vtkPolyData* cloud, const double bounds[6], int points, double radius);

} // namespace savr_scenes

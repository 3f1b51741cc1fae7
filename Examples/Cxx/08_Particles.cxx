// Example 8: particles as a volume. The points of a vtkPolyData, each carrying a value, are
// sampled through a kernel around each point (here the SPH cubic spline, its radius the mean
// distance between particles, normalized: the kernel-weighted mean of the values that reach a
// point), with no resampling to an image. The cloud is clustered, as cosmology and SPH
// simulations are: dense centres with long tails, empty space between (skipped along each ray).
// Finding and summing the particles near each sample is costly, which is where keeping every
// sample pays: a transfer-function edit re-blends without sampling again.
//
//   savr_particles [--points 1000000] [--clusters 300] [--kernel cubic|quintic|gaussian]
//                  [--radius 0] [--summed] [--headless] [--output savr_particles.png] [--size 512]

#include "SAVRExampleWindow.h"
#include "SAVRParticleScenes.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkSAVRParticleSampler.h"

#include <cstdio>

int main(int argc, char* argv[])
{
  int points = 1000000;
  int clusters = 300;
  std::string kernel = "cubic";
  double radius = 0.0;
  int summed = 0;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_particles: a clustered particle cloud (the points of a vtkPolyData) rendered as a "
    "volume with vtkSAVRVolumeMapper.");
  savr_scenes::WindowOptions window(arguments, "savr_particles.png");
  arguments.Option("--points", &points, "Particles (1000000).");
  arguments.Option("--clusters", &clusters, "Cluster centres (300).");
  arguments.Option("--kernel", &kernel, "cubic, quintic or gaussian (cubic).");
  arguments.Option("--radius", &radius, "Every particle's kernel radius (0: the mean spacing).");
  arguments.Option("--summed", &summed, "1: the weighted sum of the values (a density).");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkPolyData> cloud = savr_scenes::ClusteredCloud(points, clusters);
  std::printf("%d particles around %d centres\n", points, clusters);

  savr_scenes::Scene scene(cloud, window.Size, window.Size);
  savr_scenes::CloudProperty(scene.Property);
  scene.Renderer->SetBackground(0.0, 0.0, 0.0);
  scene.Renderer->GetActiveCamera()->Zoom(1.6);
  scene.Mapper->SetParticleKernel(kernel == "gaussian"  ? vtkSAVRParticleSampler::GAUSSIAN
                                  : kernel == "quintic" ? vtkSAVRParticleSampler::SPH_QUINTIC
                                                        : vtkSAVRParticleSampler::SPH_CUBIC);
  scene.Mapper->SetParticleRadius(radius);
  scene.Mapper->SetParticleNormalized(summed == 0);
  scene.Window->SetWindowName("vtkSAVR: particles");
  return savr_scenes::Show(scene.Window, { scene.Mapper }, window);
}

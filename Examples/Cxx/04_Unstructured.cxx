// Example 4: a vtkUnstructuredGrid, the wavelet on 48^3 points cut into 519,115 tetrahedra by
// vtkDataSetTriangleFilter, sampled in its cells directly (no resampling to a grid). Sampling
// a mesh costs far more than sampling an image, which is where keeping every sample pays most:
// after refinement, a transfer-function edit re-blends without sampling again.
//
//   savr_unstructured [--points 48] [--headless] [--output savr_unstructured.png] [--size 512]

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkUnstructuredGrid.h"

#include <cstdio>

int main(int argc, char* argv[])
{
  int points = 48;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_unstructured: the wavelet cut into tetrahedra (a vtkUnstructuredGrid), rendered with "
    "vtkSAVRVolumeMapper.");
  savr_scenes::WindowOptions window(arguments, "savr_unstructured.png");
  arguments.Option("--points", &points, "Wavelet points along each axis (48).");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkUnstructuredGrid> tets = savr_scenes::TetrahedralWavelet(points);
  std::printf("%lld tetrahedra\n", static_cast<long long>(tets->GetNumberOfCells()));

  // The base step defaults to the typical cell size.
  savr_scenes::Scene scene(tets, window.Size, window.Size);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Window->SetWindowName("vtkSAVR: tetrahedra");
  return savr_scenes::Show(scene.Window, { scene.Mapper }, window);
}

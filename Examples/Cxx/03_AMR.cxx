// Example 3: a vtkOverlappingAMR hierarchy, VTK's Gaussian pulse on two levels, rendered as it
// is: each sample is taken from the finest level that covers it, without resampling the
// hierarchy onto one grid.
//
//   savr_amr [--headless] [--output savr_amr.png] [--size 512]

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkOverlappingAMR.h"

int main(int argc, char* argv[])
{
  savr_scenes::Arguments arguments(argc, argv,
    "savr_amr: VTK's Gaussian pulse as a two-level vtkOverlappingAMR, rendered with "
    "vtkSAVRVolumeMapper.");
  savr_scenes::WindowOptions window(arguments, "savr_amr.png");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  vtkSmartPointer<vtkOverlappingAMR> pulse = savr_scenes::GaussianPulse();

  // The mapper takes the hierarchy itself; the pulse is a cell array of every block.
  savr_scenes::Scene scene(pulse, window.Size, window.Size);
  scene.Mapper->SetScalarModeToUseCellFieldData();
  scene.Mapper->SelectScalarArray("Gaussian-Pulse");
  savr_scenes::PulseProperty(scene.Property);
  scene.Window->SetWindowName("vtkSAVR: AMR Gaussian pulse");
  return savr_scenes::Show(scene.Window, { scene.Mapper }, window);
}

// Example 2: a file of any kind the mapper takes, rendered through the same mapper: a .vti or
// .nii/.nii.gz image, a .vthb AMR hierarchy or a .vtu unstructured grid. The first
// one-component point array is rendered (else the first cell array), or the one --array names,
// with a transfer function spread over its range.
//
//   savr_file [FILE] [--array NAME] [--cells] [--headless] [--output savr_file.png] [--size 512]
//
// Without a file, the MRI head. `python3 Utilities/write_scenes.py scenes` writes a .vtu and a
// .vthb to try.

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkDataArray.h"

#include <cstdio>
#include <cstdlib>

int main(int argc, char* argv[])
{
  std::vector<std::string> files;
  std::string arrayName;
  bool cells = false;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_file [FILE]: an image, AMR hierarchy or unstructured grid from a file, rendered with "
    "vtkSAVRVolumeMapper.");
  arguments.Positional(
    &files, 1, "FILE: a .vti, .nii or .nii.gz image, a .vthb AMR hierarchy or a .vtu grid");
  savr_scenes::WindowOptions window(arguments, "savr_file.png");
  arguments.Option("--array", &arrayName, "Render this point array (or --cells: cell array).");
  arguments.Flag("--cells", &cells, "Render a cell array (the first, or the --array one).");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  const std::string file = files.empty() ? savr_scenes::HeadFile() : files[0];
  std::string error;
  vtkSmartPointer<vtkDataObject> data = savr_scenes::ReadDataFile(file, error);
  if (!data)
  {
    std::fprintf(stderr, "%s\n", error.c_str());
    return EXIT_FAILURE;
  }

  // The array: named, or the first one-component array. The mapper selects it by name.
  if (arrayName.empty())
  {
    vtkDataArray* first = savr_scenes::FirstScalarArray(data, cells);
    arrayName = first && first->GetName() ? first->GetName() : "";
  }
  double range[2];
  if (arrayName.empty() || !savr_scenes::ArrayRange(data, arrayName.c_str(), cells, range))
  {
    std::fprintf(stderr, "no %s array %s in %s\n", cells ? "cell" : "point",
      arrayName.empty() ? "with a name" : arrayName.c_str(), file.c_str());
    return EXIT_FAILURE;
  }
  savr_scenes::Scene scene(data, window.Size, window.Size);
  cells ? scene.Mapper->SetScalarModeToUseCellFieldData()
        : scene.Mapper->SetScalarModeToUsePointFieldData();
  scene.Mapper->SelectScalarArray(arrayName.c_str());
  savr_scenes::SpreadProperty(scene.Property, range);
  scene.Window->SetWindowName(("vtkSAVR: " + file).c_str());
  std::printf("%s: %s array %s, range %g to %g\n", file.c_str(), cells ? "cell" : "point",
    arrayName.c_str(), range[0], range[1]);
  return savr_scenes::Show(scene.Window, { scene.Mapper }, window);
}

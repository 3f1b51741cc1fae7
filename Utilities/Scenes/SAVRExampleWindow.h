#pragma once
// How the examples show their window: headless, rendered until refinement completes with each
// frame's time printed and the image written as PNG; or interactive, refined by a
// vtkSAVRRefinementDriver per mapper while the user drags and presses keys.

#include "SAVRArguments.h"

#include <string>
#include <vector>

class vtkCommand;
class vtkRenderWindow;
class vtkSAVRVolumeMapper;

namespace savr_scenes
{

/// The flags every example takes: --headless, --output and --size.
struct WindowOptions
{
  bool Headless = false;
  std::string Output;
  int Size = 512;

  WindowOptions(Arguments& arguments, const std::string& output);
};

/// Renders offscreen until every mapper's refinement is complete (at most 100,000 renders),
/// prints each frame of the first mapper, and writes the image to `output`.
int RenderHeadless(vtkRenderWindow* window, const std::vector<vtkSAVRVolumeMapper*>& mappers,
  const std::string& output);

/// Opens the window with a trackball camera and a refinement driver per mapper; `keys`, when
/// given, observes the interactor's key presses. Returns when the window closes.
int Interact(vtkRenderWindow* window, const std::vector<vtkSAVRVolumeMapper*>& mappers,
  vtkCommand* keys = nullptr);

/// RenderHeadless or Interact, as the options say.
int Show(vtkRenderWindow* window, const std::vector<vtkSAVRVolumeMapper*>& mappers,
  const WindowOptions& options, vtkCommand* keys = nullptr);

} // namespace savr_scenes

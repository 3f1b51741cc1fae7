// Example 6: every blend mode on the MRI head, each with a transfer function that suits it, side
// by side (one mapper per viewport: a mapper keeps the samples of one view). Top row:
// composite (skin and bone), maximum intensity (the brightest tissue along each ray), minimum
// intensity inside the skull (the dark fluid of the ventricles; outside the head every ray's
// minimum is the air). Bottom row: average intensity (a radiograph), additive (glowing tissue),
// isosurface (the skin: the opaque, shaded surface of the value 50). --blend shows one mode in a
// window of its own; key b then steps to the next.
//
//   savr_blend_modes [--blend composite|mip|minip|average|additive|iso] [--headless]
//                    [--output savr_blend_modes.png] [--size 512]

#include "SAVRExampleWindow.h"
#include "SAVRScenes.h"

#include "vtkCallbackCommand.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderWindowInteractor.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace
{
const char* const kModes[] = { "composite", "mip", "minip", "average", "additive", "iso" };
const int kBlends[] = { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
  vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND,
  vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::ISOSURFACE_BLEND };

// Colour and opacity as points (value, grey level, opacity) of a grey ramp.
void Grey(vtkVolumeProperty* property, std::initializer_list<std::array<double, 3>> points)
{
  vtkNew<vtkColorTransferFunction> color;
  vtkNew<vtkPiecewiseFunction> opacity;
  for (const auto& p : points)
  {
    color->AddRGBPoint(p[0], p[1], p[1], p[1]);
    opacity->AddPoint(p[0], p[2]);
  }
  property->SetColor(color);
  property->SetScalarOpacity(opacity);
}

// Sets `mapper` and `property` up for blend mode `mode` (an index into kModes).
void Configure(int mode, vtkSAVRVolumeMapper* mapper, vtkVolumeProperty* property)
{
  savr_scenes::HeadProperty(property);
  property->SetShade(false);
  mapper->SetCropping(false);
  mapper->SetBlendMode(kBlends[mode]);
  switch (kBlends[mode])
  {
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      Grey(property, { { 0, 0, 0 }, { 60, 0.2, 0.3 }, { 255, 1, 1 } });
      break;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
    {
      // Only the brain: a box inside the skull, where the minimum finds the fluid.
      double b[6];
      mapper->GetBounds(b);
      const double f[6] = { 0.2, 0.8, 0.2, 0.75, 0.3, 0.75 };
      double box[6];
      for (int i = 0; i < 6; ++i)
      {
        box[i] = b[i & ~1] + f[i] * (b[i | 1] - b[i & ~1]);
      }
      mapper->SetCroppingRegionPlanes(box);
      mapper->SetCroppingRegionFlagsToSubVolume();
      mapper->SetCropping(true);
      Grey(property, { { 0, 0, 1 }, { 40, 0.1, 1 }, { 130, 1, 1 }, { 255, 1, 1 } });
      break;
    }
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      Grey(property, { { 0, 0, 0 }, { 10, 0, 1 }, { 110, 1, 1 }, { 255, 1, 1 } });
      break;
    case vtkVolumeMapper::ADDITIVE_BLEND:
      Grey(property, { { 0, 0, 0 }, { 40, 0, 0 }, { 120, 0.9, 0.01 }, { 255, 1, 0.02 } });
      break;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      Grey(property, { { 0, 0.85, 1 }, { 255, 0.85, 1 } });
      property->GetIsoSurfaceValues()->SetValue(0, 50.0);
      property->SetShade(true);
      break;
  }
}

struct Single
{
  int Mode;
  vtkSAVRVolumeMapper* Mapper;
  vtkVolumeProperty* Property;
};

// Key b: the next blend mode, with its transfer function.
void OnKey(vtkObject* caller, unsigned long, void* clientData, void*)
{
  auto* interactor = static_cast<vtkRenderWindowInteractor*>(caller);
  auto* single = static_cast<Single*>(clientData);
  if (interactor->GetKeyCode() == 'b')
  {
    single->Mode = (single->Mode + 1) % 6;
    Configure(single->Mode, single->Mapper, single->Property);
    std::printf("blend mode %s\n", kModes[single->Mode]);
    interactor->Render();
  }
}
} // namespace

int main(int argc, char* argv[])
{
  std::string blend;
  savr_scenes::Arguments arguments(argc, argv,
    "savr_blend_modes: the MRI head in every blend mode, each with a transfer function that "
    "suits it\n(--blend: one mode; key b: the next).");
  savr_scenes::WindowOptions window(arguments, "savr_blend_modes.png");
  arguments.Option("--blend", &blend, "composite, mip, minip, average, additive or iso.");
  if (!arguments.Parse())
  {
    return arguments.ExitCode();
  }
  int only = -1;
  for (int m = 0; m < 6; ++m)
  {
    only = blend == kModes[m] ? m : only;
  }
  if (!blend.empty() && only < 0)
  {
    std::fprintf(stderr, "unknown blend mode %s\n", blend.c_str());
    return EXIT_FAILURE;
  }
  vtkSmartPointer<vtkImageData> head = savr_scenes::Head();
  if (head->GetNumberOfPoints() == 0)
  {
    return EXIT_FAILURE;
  }

  // One renderer, volume and mapper per mode shown; all look through the first one's camera.
  vtkNew<vtkRenderWindow> renderWindow;
  std::vector<vtkSmartPointer<vtkSAVRVolumeMapper>> mappers;
  std::vector<vtkSAVRVolumeMapper*> shown;
  vtkVolumeProperty* property = nullptr;
  vtkNew<vtkRenderer> first;
  for (int m = 0; m < 6; ++m)
  {
    if (only >= 0 && m != only)
    {
      continue;
    }
    auto mapper = vtkSmartPointer<vtkSAVRVolumeMapper>::New();
    mapper->SetInputData(head);
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    property = volume->GetProperty();
    Configure(m, mapper, property);
    auto renderer =
      shown.empty() ? vtkSmartPointer<vtkRenderer>(first) : vtkSmartPointer<vtkRenderer>::New();
    renderer->AddVolume(volume);
    renderer->SetBackground(0.1, 0.1, 0.15);
    renderer->SetActiveCamera(first->GetActiveCamera());
    if (only < 0)
    {
      renderer->SetViewport((m % 3) / 3.0, (1 - m / 3) / 2.0, (m % 3 + 1) / 3.0, (2 - m / 3) / 2.0);
    }
    renderWindow->AddRenderer(renderer);
    mappers.push_back(mapper);
    shown.push_back(mapper);
  }
  savr_scenes::FaceTheHead(first);
  renderWindow->SetSize(only < 0 ? 3 * window.Size / 2 : window.Size, window.Size);
  renderWindow->SetWindowName("vtkSAVR: blend modes");
  Single single{ only, mappers.front(), property };
  vtkNew<vtkCallbackCommand> onKey;
  onKey->SetCallback(OnKey);
  onKey->SetClientData(&single);
  return savr_scenes::Show(renderWindow, shown, window, only >= 0 ? onKey.GetPointer() : nullptr);
}

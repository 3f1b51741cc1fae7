// Data far from the origin (UTM-like coordinates): any camera move that shifts the data on screen
// by a tenth of a pixel or more starts accumulation over, whatever the data's position; a render
// with the camera unchanged (only its modification time bumped, as ParaView does every render)
// keeps accumulating.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace
{
// The data's bounding-box corners in pixels, as the camera projects them.
std::vector<double> CornerPixels(vtkRenderer* renderer, const double bounds[6])
{
  const int* size = renderer->GetSize();
  vtkMatrix4x4* m = renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    renderer->GetTiledAspectRatio(), -1, 1);
  std::vector<double> pixels;
  for (int corner = 0; corner < 8; ++corner)
  {
    const double p[4] = { bounds[corner & 1], bounds[2 + ((corner >> 1) & 1)],
      bounds[4 + ((corner >> 2) & 1)], 1.0 };
    double clip[4];
    m->MultiplyPoint(p, clip);
    pixels.push_back((clip[0] / clip[3] + 1.0) * 0.5 * size[0]);
    pixels.push_back((clip[1] / clip[3] + 1.0) * 0.5 * size[1]);
  }
  return pixels;
}

double LargestShift(const std::vector<double>& a, const std::vector<double>& b)
{
  double shift = 0.0;
  for (std::size_t i = 0; i < a.size(); i += 2)
  {
    shift = std::max(shift, std::hypot(a[i] - b[i], a[i + 1] - b[i + 1]));
  }
  return shift;
}

struct Move
{
  std::string Name;
  std::function<void(vtkCamera*, double)> Apply;
  double Amount;     // the move as given, or a trial amount when scaled
  bool ScaleToTenth; // scale Amount so that the largest corner shift is 0.11 px
};

void PanAlong(vtkCamera* camera, const double axis[3], double distance)
{
  double position[3], focus[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focus);
  for (int i = 0; i < 3; ++i)
  {
    position[i] += distance * axis[i];
    focus[i] += distance * axis[i];
  }
  camera->SetPosition(position);
  camera->SetFocalPoint(focus);
}

void PanRight(vtkCamera* camera, double distance)
{
  double direction[3], right[3];
  camera->GetDirectionOfProjection(direction);
  vtkMath::Cross(direction, camera->GetViewUp(), right);
  vtkMath::Normalize(right);
  PanAlong(camera, right, distance);
}

void PanUp(vtkCamera* camera, double distance)
{
  double up[3];
  camera->GetViewUp(up);
  vtkMath::Normalize(up);
  PanAlong(camera, up, distance);
}

std::vector<Move> Moves()
{
  return {
    { "pan right", PanRight, 1e-3, true },
    { "pan up", PanUp, 1e-3, true },
    { "dolly", [](vtkCamera* c, double a) { c->Dolly(1.0 + a); }, 1e-5, true },
    { "zoom", [](vtkCamera* c, double a) { c->Zoom(1.0 + a); }, 1e-5, true },
    { "azimuth", [](vtkCamera* c, double a) { c->Azimuth(a); }, 1e-4, true },
    { "elevation", [](vtkCamera* c, double a) { c->Elevation(a); }, 1e-4, true },
    { "roll", [](vtkCamera* c, double a) { c->Roll(a); }, 1e-4, true },
    { "pan by 1 unit", PanRight, 1.0, false },
    { "pan by 5 units", PanUp, 5.0, false },
    { "2% dolly", [](vtkCamera* c, double a) { c->Dolly(1.0 + a); }, 0.02, false },
  };
}

// Every move restarts accumulation of the 64-unit wavelet at `origin`; unchanged cameras do not.
void CheckOrigin(double origin, savr_scenes::Expectations& expect)
{
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(32);
  data->SetOrigin(origin, origin, origin);
  savr_scenes::Scene scene(data, 120, 120);
  savr_scenes::WaveletProperty(scene.Property);
  scene.Mapper->SetMaximumNumberOfFrames(64);
  scene.Renderer->ResetCamera();
  scene.Renderer->GetActiveCamera()->Azimuth(30.0);
  scene.Renderer->GetActiveCamera()->Elevation(20.0);
  scene.Renderer->ResetCameraClippingRange();
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  const std::string where = " (data at " + std::to_string(origin) + ")";

  auto accumulateAndIdle = [&](const std::string& after)
  {
    scene.Window->Render();
    scene.Window->Render();
    const int frames = scene.Mapper->GetNumberOfFramesAccumulated();
    // ParaView bumps the camera's modification time every render.
    camera->Modified();
    scene.Renderer->ResetCameraClippingRange();
    scene.Window->Render();
    expect(scene.Mapper->GetNumberOfFramesAccumulated() == frames + 1,
      "an unchanged camera after " + after + " keeps accumulating" + where);
  };

  scene.Window->Render();
  accumulateAndIdle("the first frame");
  double bounds[6];
  scene.Volume->GetBounds(bounds);
  vtkNew<vtkCamera> saved;
  for (const Move& move : Moves())
  {
    double amount = move.Amount;
    const std::vector<double> before = CornerPixels(scene.Renderer, bounds);
    if (move.ScaleToTenth)
    {
      // Moves this small are linear: scale a trial move to a shift of 0.11 px.
      saved->DeepCopy(camera);
      move.Apply(camera, amount);
      amount *= 0.11 / LargestShift(before, CornerPixels(scene.Renderer, bounds));
      camera->DeepCopy(saved);
    }
    move.Apply(camera, amount);
    scene.Renderer->ResetCameraClippingRange();
    const double shift = LargestShift(before, CornerPixels(scene.Renderer, bounds));
    expect(shift >= 0.1, move.Name + " shifts the data by 0.1 px or more" + where);
    scene.Window->Render();
    const int frames = scene.Mapper->GetNumberOfFramesAccumulated();
    std::cout << move.Name << where << ": " << shift << " px, frames accumulated " << frames
              << "\n";
    expect(frames == 1,
      move.Name + " (" + std::to_string(shift) + " px) starts accumulation over" + where);
    accumulateAndIdle(move.Name);
  }
}
} // namespace

int TestSAVRFarOrigin(int, char*[])
{
  savr_scenes::Expectations expect;
  for (double origin : { 0.0, 1e4, 1e7 })
  {
    CheckOrigin(origin, expect);
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

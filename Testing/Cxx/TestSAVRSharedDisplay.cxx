// Several volumes in one window share the OpenGL program that draws their images (the window's
// shader cache holds one per source), and windows that share a context share the cache (ParaView's
// views do). When another volume lets its graphics resources go, as ParaView does when a
// representation is deleted, when VTK's fixed-point mapper, which draws through the same program,
// does so, and when the cache lets its programs go, as a window sharing it does when it closes
// (ParaView deleting another view), the volume must draw on: no OpenGL error, the same image.

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOutputWindow.h"
#include "vtkStringOutputWindow.h"

#include <cstdio>
#include <string>

namespace
{
// Every message VTK prints while it lives, kept instead of printed.
struct CapturedMessages
{
  vtkNew<vtkStringOutputWindow> Window;
  vtkSmartPointer<vtkOutputWindow> Before;
  CapturedMessages()
    : Before(vtkOutputWindow::GetInstance())
  {
    vtkOutputWindow::SetInstance(this->Window);
  }
  ~CapturedMessages() { vtkOutputWindow::SetInstance(this->Before); }
  std::string Text() { return this->Window->GetOutput(); }
};

// A volume of the wavelet, `shift` along x, drawn by `mapper`.
vtkSmartPointer<vtkVolume> Volume(vtkVolumeMapper* mapper, vtkImageData* data, double shift)
{
  mapper->SetInputData(data);
  auto volume = vtkSmartPointer<vtkVolume>::New();
  vtkNew<vtkVolumeProperty> property;
  savr_scenes::WaveletProperty(property);
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  volume->SetPosition(shift, 0.0, 0.0);
  return volume;
}
} // namespace

int TestSAVRSharedDisplay(int, char*[])
{
  savr_scenes::Expectations expect;
  vtkSmartPointer<vtkImageData> data = savr_scenes::Wavelet(10);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(200, 120);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  window->AddRenderer(renderer);

  vtkNew<vtkSAVRVolumeMapper> kept;
  kept->SetMaximumNumberOfFrames(4);
  vtkSmartPointer<vtkVolume> keptVolume = Volume(kept, data, -12.0);
  renderer->AddVolume(keptVolume);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.6);
  int renders = 0;
  while (!kept->GetRefinementComplete() && renders++ < 64)
  {
    window->Render();
  }
  window->Render();
  vtkSmartPointer<vtkImageData> alone = savr_scenes::Capture(window);

  CapturedMessages messages;
  // Another SAVR volume, then VTK's fixed-point mapper, beside it: each drawn, removed and let go.
  {
    vtkNew<vtkSAVRVolumeMapper> other;
    vtkSmartPointer<vtkVolume> volume = Volume(other, data, 12.0);
    renderer->AddVolume(volume);
    window->Render();
    window->Render();
    renderer->RemoveVolume(volume);
    volume->ReleaseGraphicsResources(window);
  }
  window->Render();
  {
    vtkNew<vtkFixedPointVolumeRayCastMapper> other;
    vtkSmartPointer<vtkVolume> volume = Volume(other, data, 12.0);
    renderer->AddVolume(volume);
    window->Render();
    renderer->RemoveVolume(volume);
    volume->ReleaseGraphicsResources(window);
  }
  window->Render();
  vtkOpenGLRenderWindow::SafeDownCast(window)->GetShaderCache()->ReleaseGraphicsResources(window);
  window->Render();
  window->Render();
  vtkSmartPointer<vtkImageData> after = savr_scenes::Capture(window);
  const std::string text = messages.Text();
  const savr_scenes::Difference same = savr_scenes::Compare(after, alone);
  const double covered = savr_scenes::CoveredFraction(after, renderer->GetBackground());
  std::printf("after the others let go: covered %.3f, vs before: max %.0f levels; messages:\n%s\n",
    covered, same.Max, text.empty() ? "(none)" : text.c_str());
  expect(text.empty(), "no message (an OpenGL error among them) after the others let go");
  expect(covered > 0.05 && same.Max <= 1.0, "the kept volume is drawn as before");
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

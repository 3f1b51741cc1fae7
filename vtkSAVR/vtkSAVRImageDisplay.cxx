#include "vtkSAVRImageDisplay.h"

#include "vtkCamera.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLRayCastImageDisplayHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"

#include <algorithm>
#include <cstdint>

/**
 * VTK's display helper, kept in step with the program it draws through. That program is the
 * window's shader cache's, one for every helper of the kind (VTK's fixed-point mapper's too),
 * and windows sharing a context share the cache (ParaView's views do). When the cache lets its
 * programs go (a window sharing it closes) without this helper being told, the program is
 * compiled again under a new handle at the next draw, and the helper's vertex array, set up for
 * the old one, refuses it: an OpenGL error each draw, nothing drawn. Before each draw the
 * program is readied here, and the array set up again when its handle changed.
 */
class vtkSAVRDisplayHelper : public vtkOpenGLRayCastImageDisplayHelper
{
public:
  static vtkSAVRDisplayHelper* New();
  vtkTypeMacro(vtkSAVRDisplayHelper, vtkOpenGLRayCastImageDisplayHelper);

  void Prepare(vtkRenderer* renderer)
  {
    auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
    if (!window || !this->ShaderProgram || !this->ShaderProgram->Program)
    {
      return;
    }
    vtkShaderProgram* program = this->ShaderProgram->Program;
    window->GetShaderCache()->ReadyShaderProgram(program);
    if (program->GetHandle() != this->Handle)
    {
      this->ShaderProgram->VAO->ShaderProgramChanged();
    }
  }

  /// The handle of the program the last draw used.
  void Remember()
  {
    this->Handle = this->ShaderProgram && this->ShaderProgram->Program
                     ? this->ShaderProgram->Program->GetHandle()
                     : 0;
  }

  void ReleaseGraphicsResources(vtkWindow* window) override
  {
    this->Superclass::ReleaseGraphicsResources(window);
    this->Handle = 0;
  }

protected:
  vtkSAVRDisplayHelper() = default;
  ~vtkSAVRDisplayHelper() override = default;

private:
  vtkSAVRDisplayHelper(const vtkSAVRDisplayHelper&) = delete;
  void operator=(const vtkSAVRDisplayHelper&) = delete;

  int Handle = 0;
};

vtkStandardNewMacro(vtkSAVRDisplayHelper);

vtkSAVRImageDisplay::vtkSAVRImageDisplay()
  : Helper(vtkSmartPointer<vtkSAVRDisplayHelper>::New())
{
  this->Helper->SetPreMultipliedColors(1);
}

vtkSAVRImageDisplay::~vtkSAVRImageDisplay() = default;

void vtkSAVRImageDisplay::SetImage(
  const std::vector<unsigned char>& bytes, int width, int height, const int rectangle[4])
{
  const std::size_t w = static_cast<std::size_t>(width);
  const std::size_t h = static_cast<std::size_t>(height);
  const std::uint32_t* in = reinterpret_cast<const std::uint32_t*>(bytes.data());
  // Pixels outside the rectangle are zero: only it is searched.
  const std::size_t left = std::min(static_cast<std::size_t>(rectangle[0]), w);
  const std::size_t right = std::min(static_cast<std::size_t>(rectangle[2]), w);
  std::size_t xBegin = w;
  std::size_t xEnd = 0;
  std::size_t yBegin = h;
  std::size_t yEnd = 0;
  for (std::size_t y = static_cast<std::size_t>(rectangle[1]);
       y < std::min(static_cast<std::size_t>(rectangle[3]), h); ++y)
  {
    const std::uint32_t* row = in + y * w;
    std::size_t first = left;
    while (first < right && row[first] == 0)
    {
      ++first;
    }
    if (first >= right)
    {
      continue;
    }
    std::size_t last = right;
    while (row[last - 1] == 0)
    {
      --last;
    }
    xBegin = std::min(xBegin, first);
    xEnd = std::max(xEnd, last);
    yBegin = std::min(yBegin, y);
    yEnd = y + 1;
  }
  const std::size_t sw = xEnd > xBegin ? xEnd - xBegin : 0;
  const std::size_t sh = yEnd > yBegin ? yEnd - yBegin : 0;
  // Counted per pixel of the image's rectangle: a larger earlier one's memory is let go.
  if (this->Doubled.capacity() > 16 * sw * sh)
  {
    std::vector<unsigned char>().swap(this->Doubled);
  }
  this->Doubled.resize(16 * sw * sh);
  std::uint32_t* out = reinterpret_cast<std::uint32_t*>(this->Doubled.data());
  for (std::size_t y = 0; y < sh; ++y)
  {
    std::uint32_t* row = out + 2 * y * 2 * sw;
    const std::uint32_t* source = in + (yBegin + y) * w + xBegin;
    for (std::size_t x = 0; x < sw; ++x)
    {
      row[2 * x] = row[2 * x + 1] = source[x];
    }
    std::copy(row, row + 2 * sw, row + 2 * sw);
  }
  this->Shown[0] = static_cast<int>(xBegin);
  this->Shown[1] = static_cast<int>(yBegin);
  this->Shown[2] = static_cast<int>(sw);
  this->Shown[3] = static_cast<int>(sh);
}

void vtkSAVRImageDisplay::Draw(
  vtkRenderer* renderer, vtkVolume* volume, const double bounds[6], int width, int height)
{
  if (this->Shown[2] <= 0 || this->Shown[3] <= 0)
  {
    return;
  }
  // The rays themselves stopped at the depth buffer.
  vtkMatrix4x4* toDepth = renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(
    renderer->GetTiledAspectRatio(), 0, 1);
  double nearest = 1.0;
  for (int c = 0; c < 8; ++c)
  {
    const double corner[4] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)],
      bounds[4 + ((c >> 2) & 1)], 1.0 };
    double p[4];
    toDepth->MultiplyPoint(corner, p);
    nearest = std::min(nearest, p[3] > 0.0 ? p[2] / p[3] : 0.0);
  }
  const float depth = static_cast<float>(std::min(std::max(nearest, 1e-6), 1.0));
  int viewport[2] = { 2 * width, 2 * height };
  int size[2] = { 2 * this->Shown[2], 2 * this->Shown[3] };
  int origin[2] = { 2 * this->Shown[0], 2 * this->Shown[1] };
  this->Helper->Prepare(renderer);
  this->Helper->RenderTexture(
    volume, renderer, size, viewport, size, origin, depth, this->Doubled.data());
  this->Helper->Remember();
}

void vtkSAVRImageDisplay::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Helper->ReleaseGraphicsResources(window);
}

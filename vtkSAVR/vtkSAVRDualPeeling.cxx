#include "vtkSAVRDualPeeling.h"

#include "frame/FrameLoop.h"
#include "blend/TransferFunctionTable.h"

#include "vtkDualDepthPeelingPass.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtk_glew.h"

#include <algorithm>

namespace
{
// The pass tells volume mappers its stage and textures only by filling in the GPU mapper's
// shaders; a mapper that blends on the CPU reads them from its protected members, through
// pointers to them taken in a class derived from it (never instantiated).
class PassState : public vtkDualDepthPeelingPass
{
public:
  static bool Volumetric(vtkDualDepthPeelingPass* pass)
  {
    return pass->*(&PassState::CurrentPeelType) == VolumetricPeel;
  }
  static vtkSAVRDualPeeling::Stage StageOf(vtkDualDepthPeelingPass* pass)
  {
    switch (pass->*(&PassState::CurrentStage))
    {
      case InitializingDepth:
        return vtkSAVRDualPeeling::Stage::Initializing;
      case Peeling:
        return vtkSAVRDualPeeling::Stage::Peeling;
      case AlphaBlending:
        return vtkSAVRDualPeeling::Stage::AlphaBlending;
      default:
        return vtkSAVRDualPeeling::Stage::None;
    }
  }
  // The current layers' depths (-near, far), and the next layers' (written by the last
  // translucent peel; the same as the opaque depth's copy before peeling).
  static vtkTextureObject* SourceDepth(vtkDualDepthPeelingPass* pass)
  {
    return (pass->*(&PassState::Textures))[pass->*(&PassState::DepthSource)];
  }
  static vtkTextureObject* DestinationDepth(vtkDualDepthPeelingPass* pass)
  {
    return (pass->*(&PassState::Textures))[pass->*(&PassState::DepthDestination)];
  }
  // The front layer as composited so far.
  static vtkTextureObject* FrontColor(vtkDualDepthPeelingPass* pass)
  {
    return (pass->*(&PassState::Textures))[pass->*(&PassState::FrontSource)];
  }
};

// Reads a width x height RG32F texture of the pass into `pairs`, at the texture unit the pass
// bound it to (or one of its own).
bool ReadDepthPairs(vtkOpenGLRenderWindow* window, vtkTextureObject* texture, int width, int height,
  std::vector<float>& pairs)
{
#ifdef GL_ES_VERSION_3_0
  return false; // no glGetTexImage: the image is drawn whole, over the translucent layers
#endif
  if (!texture || static_cast<int>(texture->GetWidth()) != width ||
      static_cast<int>(texture->GetHeight()) != height || texture->GetComponents() != 2)
  {
    return false;
  }
  const bool bound = texture->GetTextureUnit() >= 0;
  if (!bound)
  {
    texture->Activate();
  }
  pairs.resize(2 * static_cast<std::size_t>(width) * height);
  vtkOpenGLState* state = window->GetState();
  {
    vtkOpenGLState::ScopedglActiveTexture unit(state);
    state->vtkglActiveTexture(GL_TEXTURE0 + texture->GetTextureUnit());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
#ifndef GL_ES_VERSION_3_0
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RG, GL_FLOAT, pairs.data());
#endif
  }
  if (!bound)
  {
    texture->Deactivate();
  }
  return true;
}

// The quad covers `rect` (normalized device coordinates: x0, y0, x1, y1), its texture
// coordinates the images of the rectangle's pixels: each pixel centre falls on a texel's.
const char* const kVertexShader = R"(//VTK::System::Dec
in vec4 ndCoordIn;
in vec2 texCoordIn;
out vec2 texCoord;
uniform vec4 rect;
void main()
{
  texCoord = texCoordIn;
  gl_Position = vec4(mix(rect.xy, rect.zw, ndCoordIn.xy * 0.5 + 0.5), 0.0, 1.0);
}
)";

const char* const kFragmentShader = R"(//VTK::System::Dec
//VTK::Output::Dec
in vec2 texCoord;
uniform sampler2D frontImage;
uniform sampler2D backImage;
uniform sampler2D lastFront;
uniform int underLastFront;
void main()
{
  vec4 front = texture2D(frontImage, texCoord);
  gl_FragData[0] = texture2D(backImage, texCoord);
  if (underLastFront != 0)
  {
    vec4 last = texelFetch(lastFront, ivec2(gl_FragCoord.xy), 0);
    float transmittance = 1.0 - last.a;
    front = vec4(last.rgb + transmittance * front.rgb, 1.0 - transmittance * (1.0 - front.a));
  }
  gl_FragData[1] = front;
}
)";

// Uploads the rectangle's pixels of a width-wide image (zero when `bytes` is empty).
bool Upload(vtkSmartPointer<vtkTextureObject>& texture, vtkOpenGLRenderWindow* window,
  const std::vector<std::uint8_t>& bytes, int width, const int rectangle[4],
  std::vector<std::uint8_t>& scratch)
{
  if (!texture)
  {
    texture = vtkSmartPointer<vtkTextureObject>::New();
    texture->SetMinificationFilter(vtkTextureObject::Nearest);
    texture->SetMagnificationFilter(vtkTextureObject::Nearest);
    texture->SetWrapS(vtkTextureObject::ClampToEdge);
    texture->SetWrapT(vtkTextureObject::ClampToEdge);
  }
  texture->SetContext(window);
  const std::size_t rowBytes = 4 * static_cast<std::size_t>(rectangle[2] - rectangle[0]);
  const std::size_t rows = static_cast<std::size_t>(rectangle[3] - rectangle[1]);
  scratch.assign(rowBytes * rows, 0);
  for (std::size_t y = 0; !bytes.empty() && y < rows; ++y)
  {
    const std::size_t first = 4 * ((rectangle[1] + y) * width + rectangle[0]);
    std::copy(
      bytes.begin() + first, bytes.begin() + first + rowBytes, scratch.begin() + y * rowBytes);
  }
  return texture->Create2DFromRaw(static_cast<unsigned int>(rectangle[2] - rectangle[0]),
    static_cast<unsigned int>(rows), 4, VTK_UNSIGNED_CHAR, scratch.data());
}
} // namespace

vtkSAVRDualPeeling::vtkSAVRDualPeeling() = default;

vtkSAVRDualPeeling::~vtkSAVRDualPeeling() = default;

vtkSAVRDualPeeling::Stage vtkSAVRDualPeeling::Find(vtkVolume* volume)
{
  this->Pass = nullptr;
  this->Current = Stage::None;
  vtkInformation* keys = volume->GetPropertyKeys();
  if (!keys || !keys->Has(vtkOpenGLRenderPass::RenderPasses()))
  {
    return Stage::None;
  }
  for (int i = 0; i < keys->Length(vtkOpenGLRenderPass::RenderPasses()); ++i)
  {
    auto* pass =
      vtkDualDepthPeelingPass::SafeDownCast(keys->Get(vtkOpenGLRenderPass::RenderPasses(), i));
    if (pass && PassState::Volumetric(pass))
    {
      this->Pass = pass;
      this->Current = PassState::StageOf(pass);
      return this->Current;
    }
  }
  return Stage::None;
}

// The rules of vtkGPUVolumeRayCastMapper's shaders under the pass, depth by depth (a layer's
// near depth is stored negated, -1 where there is none; a far depth of -1 means none).
bool vtkSAVRDualPeeling::FindParts(
  vtkRenderer* renderer, int width, int height, const std::vector<float>& opaqueDepth, Parts& parts)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window || !this->Pass || this->Current == Stage::None)
  {
    return false;
  }
  // Before peeling and while peeling the pass's source depths are the outer layers of the
  // stage, its destination depths the inner ones; before peeling the other way round.
  const bool initializing = this->Current == Stage::Initializing;
  vtkTextureObject* outer =
    initializing ? PassState::DestinationDepth(this->Pass) : PassState::SourceDepth(this->Pass);
  vtkTextureObject* inner =
    initializing ? PassState::SourceDepth(this->Pass) : PassState::DestinationDepth(this->Pass);
  if (!ReadDepthPairs(window, outer, width, height, this->Outer) ||
      (this->Current != Stage::AlphaBlending &&
        !ReadDepthPairs(window, inner, width, height, this->Inner)))
  {
    return false;
  }
  const std::size_t n = static_cast<std::size_t>(width) * height;
  for (std::vector<float>* v :
    { &parts.FrontNear, &parts.FrontFar, &parts.BackNear, &parts.BackFar })
  {
    v->assign(n, 0.0f);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    const float outerNear = this->Outer[2 * i];
    const float outerFar = this->Outer[2 * i + 1];
    float frontNear = 0.0f, frontFar = 0.0f, backNear = 0.0f, backFar = 0.0f;
    if (this->Current == Stage::AlphaBlending)
    {
      // Between the layers left, into the back layer.
      if (outerNear != -1.0f)
      {
        backNear = -outerNear;
        backFar = outerFar;
      }
    }
    else if (initializing)
    {
      const float innerNear = this->Inner[2 * i];
      const float innerFar = this->Inner[2 * i + 1];
      if (innerNear == -1.0f)
      {
        // No translucent layer: the whole ray (to opaque geometry) into the back layer.
        backFar = innerFar >= 0.0f ? innerFar : 1.0f;
      }
      else
      {
        frontFar = -innerNear;
        backNear = innerFar;
        backFar = outerFar >= 0.0f ? outerFar : 1.0f;
      }
    }
    else if (outerNear != -1.0f)
    {
      const float innerNear = this->Inner[2 * i];
      const float innerFar = this->Inner[2 * i + 1];
      frontNear = -outerNear;
      frontFar = -innerNear;
      // The same part both ways is drawn at the back only.
      const bool onlyBack = frontNear == innerFar && frontFar == outerFar;
      const bool noInner = innerNear == -1.0f;
      if (noInner)
      {
        frontFar = outerFar;
      }
      const float opaque = opaqueDepth.empty() ? 1.0f : opaqueDepth[i];
      const bool endBehindOpaque = frontFar >= opaque;
      frontFar = std::min(frontFar, opaque);
      if (onlyBack)
      {
        frontNear = frontFar = 0.0f;
      }
      if (!endBehindOpaque && !noInner)
      {
        backNear = innerFar;
        backFar = outerFar;
      }
    }
    parts.FrontNear[i] = frontNear;
    parts.FrontFar[i] = frontFar;
    parts.BackNear[i] = backNear;
    parts.BackFar[i] = backFar;
  }
  return true;
}

void vtkSAVRDualPeeling::Draw(vtkRenderer* renderer, const std::vector<std::uint8_t>& front,
  const std::vector<std::uint8_t>& back, int width, int height, const int rectangle[4])
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
  if (!window || !this->Pass || this->Current == Stage::None || width <= 0 || height <= 0 ||
      rectangle[2] <= rectangle[0] || rectangle[3] <= rectangle[1])
  {
    return;
  }
  if (!Upload(this->FrontTexture, window, front, width, rectangle, this->Scratch) ||
      !Upload(this->BackTexture, window, back, width, rectangle, this->Scratch))
  {
    return;
  }
  if (!this->Quad)
  {
    this->Quad.reset(new vtkOpenGLQuadHelper(window, kVertexShader, kFragmentShader, nullptr));
  }
  else
  {
    window->GetShaderCache()->ReadyShaderProgram(this->Quad->Program);
  }
  vtkShaderProgram* program = this->Quad->Program;
  if (!program)
  {
    return;
  }
  const float rect[4] = { 2.0f * rectangle[0] / width - 1.0f, 2.0f * rectangle[1] / height - 1.0f,
    2.0f * rectangle[2] / width - 1.0f, 2.0f * rectangle[3] / height - 1.0f };
  this->FrontTexture->Activate();
  this->BackTexture->Activate();
  program->SetUniformi("frontImage", this->FrontTexture->GetTextureUnit());
  program->SetUniformi("backImage", this->BackTexture->GetTextureUnit());
  vtkTextureObject* lastFront =
    this->Current == Stage::Peeling ? PassState::FrontColor(this->Pass) : nullptr;
  const bool underLastFront = lastFront && lastFront->GetTextureUnit() >= 0;
  program->SetUniformi("underLastFront", underLastFront ? 1 : 0);
  program->SetUniformi("lastFront",
    underLastFront ? lastFront->GetTextureUnit() : this->FrontTexture->GetTextureUnit());
  program->SetUniform4f("rect", rect);
  this->Quad->Render();
  this->BackTexture->Deactivate();
  this->FrontTexture->Deactivate();
}

void vtkSAVRDualPeeling::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Quad.reset();
  for (vtkTextureObject* texture : { this->FrontTexture.Get(), this->BackTexture.Get() })
  {
    if (texture)
    {
      texture->ReleaseGraphicsResources(window);
    }
  }
}

void vtkSAVRDualPeeling::DrawStage(vtkRenderer* renderer, savr::FrameLoop& loop,
  const savr::TransferFunctionTable& tf, savr::BlendMode mode,
  const std::vector<std::uint8_t>& whole)
{
  const savr::View& view = loop.CurrentView();
  int rectangle[4];
  loop.ImageRectangle(rectangle);
  if (!loop.CanBlendDepthWindows(mode) ||
      !this->FindParts(renderer, view.Width, view.Height, view.Depth, this->StageParts))
  {
    if (this->Current == Stage::Initializing)
    {
      this->Draw(
        renderer, whole, std::vector<std::uint8_t>(), view.Width, view.Height, rectangle);
    }
    return;
  }
  const std::size_t floats = 4 * static_cast<std::size_t>(view.Width) * view.Height;
  this->FrontImage.assign(floats, 0.0f);
  this->BackImage.assign(floats, 0.0f);
  const Parts& parts = this->StageParts;
  savr::FrameLoop::DepthWindow windows[2];
  windows[0] = { parts.FrontNear.data(), parts.FrontFar.data(), this->FrontImage.data() };
  windows[1] = { parts.BackNear.data(), parts.BackFar.data(), this->BackImage.data() };
  loop.BlendDepthWindows(tf, mode, windows, 2);
  loop.ImageBytes(this->FrontImage, this->FrontBytes);
  loop.ImageBytes(this->BackImage, this->BackBytes);
  this->Draw(renderer, this->FrontBytes, this->BackBytes, view.Width, view.Height, rectangle);
}

// Private to the module: how the mapper takes part in VTK's dual depth peeling for volumes
// (vtkRenderer::SetUseDepthPeelingForVolumes with translucent geometry in view).
//
// The pass calls every volume's Render at each of its volume stages: once before peeling (the
// parts of the rays in front of the nearest and behind the farthest translucent layer), once per
// peel (the parts between the layers just peeled and the next ones) and, when it stops before
// every layer is peeled, once more (what lies between the layers left). At each, this reads the
// pass's layer depths, says which part of each pixel's ray the stage draws into the pass's front
// and back layers, and draws the mapper's blends of those parts where the pass expects them, as
// vtkGPUVolumeRayCastMapper's shaders do.
#ifndef vtkSAVRDualPeeling_h
#define vtkSAVRDualPeeling_h

#include "vtkSmartPointer.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace savr
{
class FrameLoop;
class TransferFunctionTable;
enum class BlendMode;
}

class vtkDualDepthPeelingPass;
class vtkOpenGLQuadHelper;
class vtkRenderer;
class vtkTextureObject;
class vtkVolume;
class vtkWindow;

class vtkSAVRDualPeeling
{
public:
  vtkSAVRDualPeeling();
  ~vtkSAVRDualPeeling();

  enum class Stage
  {
    None,         // not called by the pass
    Initializing, // before peeling: in front of and behind the translucent layers
    Peeling,      // a peel: between the layers peeled and the next
    AlphaBlending // after the last peel: between the layers left
  };

  /// Finds the pass among `volume`'s render passes and the stage at which it calls Render.
  Stage Find(vtkVolume* volume);
  /// The stage found last.
  Stage GetStage() const { return this->Current; }

  /// The parts of the rays the current stage draws, as window depths per pixel of the viewport
  /// (width x height, rows from the bottom): pixel i's front part lies between FrontNear[i] and
  /// FrontFar[i], its back part between BackNear[i] and BackFar[i] (none where near >= far).
  /// `opaqueDepth` (empty for none) is the depth the rays end at. False when the pass's depths
  /// cannot be read (their size is not the viewport's).
  struct Parts
  {
    std::vector<float> FrontNear, FrontFar, BackNear, BackFar;
  };
  bool FindParts(vtkRenderer* renderer, int width, int height,
    const std::vector<float>& opaqueDepth, Parts& parts);

  /// Draws the blends of the stage's front and back parts (premultiplied RGBA bytes of the
  /// viewport's size, zero outside `rectangle`: x and y begin, x and y end) into the layers the
  /// pass expects them in. An empty `back` stands for zero.
  void Draw(vtkRenderer* renderer, const std::vector<std::uint8_t>& front,
    const std::vector<std::uint8_t>& back, int width, int height, const int rectangle[4]);

  /// Draws the current stage from `loop`'s stored samples (no new ones): the blends of the
  /// stage's parts in `mode` with `tf`. Images that cannot be blended by parts (a single pass
  /// while interacting, isosurfaces, pre-integration, slices) are drawn whole, `whole` (the
  /// loop's image as bytes), at the first stage, over every translucent layer, as with peeling
  /// for volumes off.
  void DrawStage(vtkRenderer* renderer, savr::FrameLoop& loop,
    const savr::TransferFunctionTable& tf, savr::BlendMode mode,
    const std::vector<std::uint8_t>& whole);

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  // DrawStage's buffers: the parts, their blends and the blends as bytes.
  Parts StageParts;
  std::vector<float> FrontImage;
  std::vector<float> BackImage;
  std::vector<std::uint8_t> FrontBytes;
  std::vector<std::uint8_t> BackBytes;

  vtkDualDepthPeelingPass* Pass = nullptr; // during the Render that found it
  Stage Current = Stage::None;
  std::vector<float> Outer; // the pass's depth pairs (-near, far) per pixel
  std::vector<float> Inner;
  vtkSmartPointer<vtkTextureObject> FrontTexture;
  vtkSmartPointer<vtkTextureObject> BackTexture;
  std::vector<std::uint8_t> Scratch; // an image's rectangle, uploaded
  std::unique_ptr<vtkOpenGLQuadHelper> Quad;
};

#endif

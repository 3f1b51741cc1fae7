// Private to the module: draws the mapper's image into the renderer's viewport, exactly.
//
// vtkRayCastImageDisplayHelper stretches its texture's first to last texel centre over the
// rectangle it draws, and filters linearly: an image of the rectangle's size would come out
// resampled (blurred by up to half a pixel towards the edges). With every pixel doubled in both
// directions, each window pixel's texture lookup falls between two copies of its own pixel, so
// the window shows the image exactly. Fully transparent pixels (premultiplied, all four bytes
// zero) leave the window as it is: only the rectangle around the others is drawn.
#ifndef vtkSAVRImageDisplay_h
#define vtkSAVRImageDisplay_h

#include "vtkSmartPointer.h"

#include <cstddef>
#include <vector>

class vtkSAVRDisplayHelper;
class vtkRenderer;
class vtkVolume;
class vtkWindow;

class vtkSAVRImageDisplay
{
public:
  vtkSAVRImageDisplay();
  ~vtkSAVRImageDisplay();

  /**
   * Takes the premultiplied RGBA `bytes` of a `width` x `height` image whose pixels outside
   * `rectangle` (x and y begin, x and y end) are zero.
   */
  void SetImage(
    const std::vector<unsigned char>& bytes, int width, int height, const int rectangle[4]);

  /**
   * Draws the image taken last over the renderer's viewport of `width` x `height`, at the depth
   * of the nearest corner of `bounds`, so that opaque geometry nearer than the volume still hides
   * it.
   */
  void Draw(
    vtkRenderer* renderer, vtkVolume* volume, const double bounds[6], int width, int height);

  void ReleaseGraphicsResources(vtkWindow* window);

  /// Bytes held per pixel of the image rectangle: the doubled copy, and the texture made of it.
  static constexpr std::size_t BytesPerShownPixel = 2 * 2 * 4 * 2;

private:
  vtkSmartPointer<vtkSAVRDisplayHelper> Helper;
  // The smallest rectangle of the image holding every pixel that is not fully transparent, each
  // pixel doubled in x and y; its origin and size in (undoubled) pixels.
  std::vector<unsigned char> Doubled;
  int Shown[4] = { 0, 0, 0, 0 };
};

#endif

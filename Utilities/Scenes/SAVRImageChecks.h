#pragma once
// Checks on rendered images shared by the rendering tests, the benchmarks and the examples:
// the window's pixels, differences in 8-bit levels, strict baselines, and errors of floating
// point images against a reference.

#include "vtkImageData.h"
#include "vtkSmartPointer.h"

#include <string>
#include <vector>

class vtkRenderWindow;

namespace savr_scenes
{

/// The window's pixels as RGB bytes, without rendering again (a render would be one more
/// refinement frame).
vtkSmartPointer<vtkImageData> Capture(vtkRenderWindow* window);

/// The bytes of an image's scalars.
unsigned char* Bytes(vtkImageData* image);

/// Fraction of pixels that differ from the background colour by more than 8 levels.
double CoveredFraction(vtkImageData* image, const double background[3]);

struct Difference
{
  double Max = 0.0;  // largest channel difference, in levels of 255
  double Mean = 0.0; // mean channel difference, in levels of 255
};

/// Channel differences of two RGB images (255 when their sizes differ).
Difference Compare(vtkImageData* a, vtkImageData* b);

/// Counts failed expectations and says which.
struct Expectations
{
  int Failures = 0;
  void operator()(bool condition, const std::string& what);
};

/// Strict comparison of the window with the baseline named by `-V` (VTK's own comparison
/// forgives differences of up to 16 levels per channel, which would hide a missing refinement):
/// at most `maxLevels` in any channel and `meanLevels` on average. On failure writes the image
/// into the `-T` folder (to be reviewed and, without a baseline, copied into
/// Testing/Data/Baseline), and next to it, when there is a baseline, the difference image.
bool MatchesBaseline(vtkRenderWindow* window, int argc, char* argv[], double maxLevels = 3.0,
  double meanLevels = 0.05);

struct ImageError
{
  double Rmse = 0.0; // root mean square error over the channels compared
  double Max = 0.0;  // largest absolute error
};

/// Error of an RGBA image in [0, 1] (premultiplied, four floats per pixel) against a reference
/// of the same layout: over all four channels, or over RGB only when `alpha` is false.
ImageError ErrorAgainst(
  const std::vector<float>& image, const std::vector<float>& reference, bool alpha = true);

/// An RGB image of bytes as RGBA floats in [0, 1] (alpha 0), to compare with ErrorAgainst.
std::vector<float> FloatRGBA(vtkImageData* image);

/// Writes an image as PNG.
void WritePNG(vtkImageData* image, const std::string& file);

} // namespace savr_scenes

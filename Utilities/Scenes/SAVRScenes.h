#pragma once
// Scenes shared by the rendering tests, the benchmarks and the examples: the data (the MRI head,
// the wavelet on an image or on tetrahedra, the Gaussian pulse as AMR, images of several
// components, any file VTK reads for the mapper), the transfer functions that suit them, and a
// window with a SAVR volume in it.

#include "vtkSAVRVolumeMapper.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <functional>
#include <string>

class vtkCamera;
class vtkDataArray;
class vtkDataObject;
class vtkGPUVolumeRayCastMapper;
class vtkOverlappingAMR;
class vtkUnstructuredGrid;

namespace savr_scenes
{

///@{
/// The MRI head of Debian's mricron-data package (181x217x181, 8 bits), or SAVR_HEAD_FILE when
/// set; Head() is empty, with a message, when the file cannot be read.
std::string HeadFile();
vtkSmartPointer<vtkImageData> Head();
///@}

/// VTK's wavelet (vtkRTAnalyticSource) on the points -halfExtent..halfExtent of every axis.
vtkSmartPointer<vtkImageData> Wavelet(int halfExtent = 20);

/// The wavelet on `points`^3 points cut into tetrahedra by vtkDataSetTriangleFilter (48: 519,115
/// tetrahedra).
vtkSmartPointer<vtkUnstructuredGrid> TetrahedralWavelet(int points = 48);

/// The wavelet on `points`^3 points as VTK_HEXAHEDRON cells ((points - 1)^3 of them; 41: 64,000)
/// of a curvilinear mesh: every point moved off the lattice by a smooth sinusoidal warp of at
/// most 0.05 cell, so that the cells are not parallelepipeds, each point keeping the wavelet's
/// value at its lattice point. With `wedges`, the hexahedra of every other slab of cells across x
/// are each split into two VTK_WEDGE cells (41: 32,000 hexahedra and 64,000 wedges), all the same
/// way: the wedges' triangles face z, so they meet only the same triangles of their own slab, and
/// their quadrilaterals match the neighbouring hexahedra's faces.
vtkSmartPointer<vtkUnstructuredGrid> HexahedralWavelet(int points = 41, bool wedges = false);

///@{
/// VTK's Gaussian pulse as a vtkOverlappingAMR hierarchy of two levels (root spacing 0.5,
/// refinement ratio 2), its cell array "Gaussian-Pulse" exp(-|p - origin|^2 / width^2).
constexpr double PulseOrigin[3] = { -0.4, -0.5, 1.2 };
constexpr double PulseWidth = 0.8;
vtkSmartPointer<vtkOverlappingAMR> GaussianPulse();
///@}

///@{
/// Float components on the wavelet's grid, `count` (2 to 4) of them: the wavelet; ten times the
/// distance from a point off the centre (a green shell under SecondComponentFunctions); ten times
/// the distance from another point (a blue shell); ten times x, shifted to be positive (a red
/// slab). Positions and distances scale with `halfExtent`, so that the values, and the transfer
/// functions below, are those of the default size.
vtkSmartPointer<vtkImageData> ComponentImage(int count, int halfExtent = 12);
/// Unsigned char RGBA on the wavelet's grid: the colour from the position, the alpha from the
/// wavelet.
vtkSmartPointer<vtkImageData> ColorAndAlphaImage(int halfExtent = 12);
///@}

///@{
/// Transfer functions. The wavelet's: blue to yellow to red, more opaque towards the top. The
/// head's: skin and bone of a T1 MRI. The pulse's: blue to red over 0..1. Spread: the wavelet's
/// colours and opacities spread over any value range.
void WaveletProperty(vtkVolumeProperty* property);
void HeadProperty(vtkVolumeProperty* property);
void PulseProperty(vtkVolumeProperty* property);
void SpreadProperty(vtkVolumeProperty* property, const double range[2]);
///@}

///@{
/// Transfer functions of ComponentImage and ColorAndAlphaImage. Independent: each component
/// through its own functions (the second's shell peaks at 0.6); the third and fourth
/// components' functions, the slab's opacity peaking at `slabOpacity`. Dependent: the wavelet's
/// colour, the shell's opacity from the second component. Color and alpha: the colour from the
/// first three components, the opacity from the fourth.
void IndependentComponentsProperty(vtkVolumeProperty* property);
void SecondComponentFunctions(vtkVolumeProperty* property, double shellOpacity);
void LastComponentFunctions(vtkVolumeProperty* property, double slabOpacity);
void DependentComponentsProperty(vtkVolumeProperty* property);
void ColorAndAlphaProperty(vtkVolumeProperty* property);
///@}

///@{
/// An image (.vti, .nii, .nii.gz), an unstructured grid (.vtu) or an AMR hierarchy (.vthb, every
/// level) from a file; null, with the reason in `error`, when it cannot be read.
vtkSmartPointer<vtkDataObject> ReadDataFile(const std::string& file, std::string& error);
/// The first one-component array of the data (of the first block of an AMR hierarchy): its
/// points' first, then its cells' (`cells` says which); VTK's ghost-type array excepted.
vtkDataArray* FirstScalarArray(vtkDataObject* data, bool& cells);
/// The range of the named point or cell array over the whole data (every block of an AMR
/// hierarchy); false when no part has it.
bool ArrayRange(vtkDataObject* data, const char* name, bool cells, double range[2]);
///@}

/// Looks at the face of the MRI head (+y is anterior, +z superior in its index space).
void FaceTheHead(vtkRenderer* renderer);

/// Window, renderer and volume with a SAVR mapper, camera framing the data.
struct Scene
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkVolumeProperty> Property;
  vtkNew<vtkSAVRVolumeMapper> Mapper;

  Scene(vtkDataObject* data, int width, int height);

  /// Renders until refinement completes (or `maxRenders`); returns the renders made.
  int RenderUntilComplete(int maxRenders = 4096);
};

/// VTK's fixed-point mapper's image of `data` with the wavelet's transfer function, seen by
/// `camera`, at a fine step (0.05) and full image resolution; `configure` may set up the mapper
/// further (cropping, clipping planes, blend mode) and `property` the volume property.
vtkSmartPointer<vtkImageData> FixedPointImage(vtkImageData* data, vtkCamera* camera, int width,
  int height, const std::function<void(vtkVolumeMapper*)>& configure = nullptr,
  const std::function<void(vtkVolumeProperty*)>& property = nullptr);

/// vtkGPUVolumeRayCastMapper's image of `data` seen by `camera` in a `width` x `height` window
/// (the same window at every call, open until the process ends, with this call's renderer only)
/// with the scenes' background; `configure` sets up the GPU mapper, the volume property and the
/// renderer (blend mode, sample distance, transfer functions, other props, depth peeling).
/// `supported` (when given) tells whether the GPU mapper can render in that window.
vtkSmartPointer<vtkImageData> GPUImage(vtkImageData* data, vtkCamera* camera, int width,
  int height,
  const std::function<void(vtkGPUVolumeRayCastMapper*, vtkVolumeProperty*, vtkRenderer*)>&
    configure,
  bool* supported = nullptr);

/// Bytes the mapper's stored samples take, per stored sample.
double BytesPerStoredSample(vtkSAVRVolumeMapper* mapper);

} // namespace savr_scenes

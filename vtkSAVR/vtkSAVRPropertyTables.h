// Private to the module: the volume property tabulated for the engine (transfer functions,
// components, shading, isosurfaces, gradient opacity). Whether a table needs building again is
// decided by vtkSAVRFrameChanges; this class builds, and Update hands the tables to the engine.
#ifndef vtkSAVRPropertyTables_h
#define vtkSAVRPropertyTables_h

#include "blend/Integrator.h"
#include "blend/ShadingTable.h"
#include "blend/TransferFunctionTable.h"

#include <array>
#include <vector>

class vtkObject;
class vtkRenderer;
class vtkSAVRFrameChanges;
class vtkVolumeProperty;

namespace savr
{
class ComponentSampler;
class FrameLoop;
struct SampleEncoding;
enum class BlendMode;
}

class vtkSAVRPropertyTables
{
public:
  /// What one frame's tables depend on besides the property's functions.
  struct FrameInputs
  {
    vtkVolumeProperty* Property = nullptr;
    vtkRenderer* Renderer = nullptr;
    const savr::ComponentSampler* Components = nullptr; // with several components
    double ColorScale = 1.0;                            // dependent RGBA colours' normalization
    savr::BlendMode Mode{};
    bool GradientOpacity = false; // in use (TabulateGradientOpacity said so)
    bool PreIntegration = false;
    // The scalar opacity is an attenuation coefficient per unit distance (VTK's unstructured
    // mappers' reading) instead of the opacity of a segment one unit distance long.
    bool OpacityIsAttenuation = false;
  };

  /**
   * Brings every table in line with a frame: each is built again when `changes` says what it
   * depends on changed (which re-blends the stored samples), and the ones in use are handed to
   * `loop` (the others taken from it).
   */
  void Update(const FrameInputs& frame, vtkSAVRFrameChanges& changes, savr::FrameLoop& loop);

  /// The renderer's switched-on lights, as directions towards them with their colours.
  static std::vector<savr::Light> Lights(vtkRenderer* renderer);

  /**
   * Tabulates the gradient opacity function over 256 gradient magnitude codes, up to the
   * steepest gradient the data can have (its value range over the smallest spacing, along a
   * diagonal): of the one component (range `valueRange`), or of each independent component of
   * `components` (not null: several components) over its own range. Returns whether gradient
   * opacity is in use: a function is set, enabled and not 1 everywhere (VTK creates a constant
   * default for anyone who asks for the function), and the components, if several, are
   * independent.
   */
  bool TabulateGradientOpacity(vtkVolumeProperty* property,
    const savr::ComponentSampler* components, const std::array<double, 2>& valueRange,
    double smallestSpacing);
  /// Magnitude codes per scalar unit per world unit of each component, as last tabulated (the
  /// first for data of one component).
  const std::array<double, 4>& GetMagnitudeScales() const { return this->MagnitudeScales; }

  /**
   * Whether the first component's transfer functions have features narrower than one code of
   * `encoding` (the samples' integer levels), which storing samples with fractional bits keeps
   * (savr::SampleEncoding::HasFeaturesBetweenCodes).
   */
  static bool NeedsFineCodes(vtkVolumeProperty* property, const savr::SampleEncoding& encoding);

  /**
   * Colour and opacity of every code of `encoding`. With several components (`components` not
   * null), the codes are pairs of component levels and `colorScale` normalizes dependent RGBA
   * colours as a texture's. With `attenuation` (one component), the opacity function's value
   * is an attenuation coefficient per unit distance: a segment of length L has opacity
   * 1 - exp(-value L / unit distance), as in VTK's unstructured mappers.
   */
  void BuildTransferFunction(vtkVolumeProperty* property, const savr::SampleEncoding& encoding,
    const savr::ComponentSampler* components, double colorScale, bool attenuation = false);
  /// Lit with the first component's coefficients, or each of `components` independent ones
  /// with its own.
  void BuildShading(vtkVolumeProperty* property, const std::vector<savr::Light>& lights,
    const Eigen::Vector3d& toViewer, bool twoSided, int components = 1);
  void BuildIsoSurfaces(vtkVolumeProperty* property);
  /// From the factors TabulateGradientOpacity left.
  void BuildGradientOpacity();

  const savr::TransferFunctionTable& GetTransferFunction() const { return this->Table; }
  const savr::ShadingTable* GetShading() const { return &this->Shading; }
  const savr::IsoSurfaces* GetIsoSurfaces() const { return &this->Isos; }
  const savr::GradientOpacityTable* GetGradientOpacity() const { return &this->GradientOpacity; }

private:
  savr::TransferFunctionTable Table;
  savr::ShadingTable Shading;
  savr::IsoSurfaces Isos;
  savr::GradientOpacityTable GradientOpacity;
  double GradientFactors[4 * 256] = {};
  std::array<double, 4> MagnitudeScales = { 1.0, 1.0, 1.0, 1.0 };
  int GradientSets = 1;
};

#endif

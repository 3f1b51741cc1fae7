/**
 * @class   vtkSAVRParticleVolumeRepresentation
 * @brief   Volume representation of a point cloud (vtkPolyData) drawn by vtkSAVRVolumeMapper.
 *
 * ParaView has no volume representation for vtkPolyData. This one hands the points (each a
 * particle with the colored point array as its value) to vtkSAVRVolumeMapper, which samples the
 * field their kernels make (see vtkSAVRParticleSampler), with the particle settings of its
 * vtkSAVRRepresentationSettings (radius, radius array, kernel, normalization). The volume property
 * (lookup table, scalar opacity function and unit distance, shading) and the placement are
 * vtkVolumeRepresentation's; the blend mode and shading are added here. The mapper's settings and
 * its state are those of its vtkSAVRRepresentationSettings, as in the plugin's other
 * representations.
 *
 * On several ranks a particle's kernel reaches across any split of the domain, so the ranks'
 * points are gathered on the first rank, which draws them alone; the others draw nothing, and
 * the view composites the ranks in order (the first rank's region is the cloud's, the others'
 * are empty), as vtkSAVRAMRVolumeRepresentation does for its gathered blend modes.
 *
 * The plugin's XML adds it to GeometryRepresentation (vtkPolyData) as "SAVR Volume".
 */
#ifndef vtkSAVRParticleVolumeRepresentation_h
#define vtkSAVRParticleVolumeRepresentation_h

#include "vtkSAVRParaViewModule.h"         // For export macro
#include "vtkSAVRRepresentationSettings.h" // For vtkSmartPointer<vtkSAVRRepresentationSettings>
#include "vtkSmartPointer.h"               // For vtkSmartPointer

#include "vtkVolumeRepresentation.h"
#include <string> // For std::string

class vtkColorTransferFunction;
class vtkPiecewiseFunction;
class vtkPolyData;
class vtkSAVRVolumeMapper;

class VTKSAVRPARAVIEW_EXPORT vtkSAVRParticleVolumeRepresentation : public vtkVolumeRepresentation
{
public:
  static vtkSAVRParticleVolumeRepresentation* New();
  vtkTypeMacro(vtkSAVRParticleVolumeRepresentation, vtkVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

  /// Shows or hides the volume.
  void SetVisibility(bool visible) override;

  ///@{
  /// Shading and blending (as ParaView's image volume representation has them).
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  void SetShade(bool shade);
  void SetBlendMode(int mode);
  ///@}

  ///@{
  /// The transfer functions ParaView gives (the colored array's lookup table and opacity
  /// function), put on the volume property before each render whenever an array is colored.
  void SetLookupTable(vtkColorTransferFunction* lut);
  void SetScalarOpacityFunction(vtkPiecewiseFunction* function);
  ///@}

  /// Solid Color's color. In Solid Color with ParticleNormalized off the volume is the
  /// particles' density, drawn in this color, attenuating in proportion to the density: opacity
  /// 1 - exp(-6 density / bound) per unit distance, where bound is the mapper's bound on the
  /// summed field (vtkSAVRParticleSampler's field range, 2 to 3.3 times the densest place).
  void SetDensityColor(double r, double g, double b);

  /// The point array of particle radii (empty or "None": none), forwarded to the mapper by the
  /// settings, which hold the other particle settings (the panel's array list needs the input,
  /// which the settings' proxy has not).
  void SetParticleRadiusArray(const char* name);

  ///@{
  /// The mapper (GetMapper()), its settings and state; null makes new settings
  /// for the same mapper. ParaView passes those of the proxy's SAVRSettings sub-proxy.
  void SetSAVRSettings(vtkSAVRRepresentationSettings* settings);
  vtkSAVRRepresentationSettings* GetSAVRSettings() { return this->Settings; }
  ///@}

protected:
  vtkSAVRParticleVolumeRepresentation();
  ~vtkSAVRParticleVolumeRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

  /// The colored array and the mapper, set before each render.
  void UpdateMapperParameters();

private:
  vtkSAVRParticleVolumeRepresentation(const vtkSAVRParticleVolumeRepresentation&) = delete;
  void operator=(const vtkSAVRParticleVolumeRepresentation&) = delete;

  /// The first rank's box (the cloud's reach) on every rank, from the first rank.
  void ShareBounds();
  /// The density's transfer functions, over the bound on the summed field of the delivered
  /// points (computed once per delivery).
  void UpdateDensityFunctions();

  vtkSmartPointer<vtkPolyData> Cache; // the points handed to the view for delivery
  vtkSmartPointer<vtkSAVRVolumeMapper> Mapper;
  bool Gathered = false;     // several ranks: the first one holds every point
  bool DrawsNothing = false; // gathered, and this is not the first rank
  double Region[6];          // this rank's region while gathered (empty on the others)
  vtkSmartPointer<vtkSAVRRepresentationSettings> Settings; // the mapper's settings and driver
  vtkSmartPointer<vtkColorTransferFunction> LookupTable;   // ParaView's, for a colored array
  vtkSmartPointer<vtkPiecewiseFunction> OpacityFunction;   // ParaView's, for a colored array
  vtkSmartPointer<vtkColorTransferFunction> DensityColor;  // Solid Color's color, constant
  vtkSmartPointer<vtkPiecewiseFunction> DensityOpacity;    // 0 to 1 over the density's bound
  double DensityRGB[3] = { 1.0, 1.0, 1.0 };
  std::string DensityKey; // the points and particle settings DensityOpacity was made for
};

#endif

/**
 * @class   vtkSAVRUnstructuredVolumeRepresentation
 * @brief   ParaView's unstructured-grid volume representation, drawn by vtkSAVRVolumeMapper.
 *
 * ParaView's "Volume" representation of unstructured grids (its distributed rendering with data
 * redistribution and ordered compositing) with vtkSAVRVolumeMapper as the only mapper: the stock
 * SelectMapper choice is ignored. Unlike the stock one, it hands the mapper the cells as they are
 * (tetrahedra, hexahedra, voxels, wedges, pyramids; a structured grid's hexahedra), which the
 * mapper walks natively, rather than the stock preprocessing's tetrahedra. The mapper's settings,
 * and its state are those of its vtkSAVRRepresentationSettings.
 *
 * An unstructured grid whose cells are all vertices (or that has none) is a point cloud, which
 * the mapper samples as particles, with the particle settings of the settings.
 *
 * The plugin's XML adds it to UnstructuredGridRepresentation and StructuredGridRepresentation
 * (curvilinear grids) as "SAVR Volume".
 */
#ifndef vtkSAVRUnstructuredVolumeRepresentation_h
#define vtkSAVRUnstructuredVolumeRepresentation_h

#include "vtkSAVRParaViewModule.h"         // For export macro
#include "vtkSAVRRepresentationSettings.h" // For vtkSmartPointer<vtkSAVRRepresentationSettings>
#include "vtkSmartPointer.h"               // For vtkSmartPointer
#include "vtkUnstructuredGridVolumeRepresentation.h"

class VTKSAVRPARAVIEW_EXPORT vtkSAVRUnstructuredVolumeRepresentation
  : public vtkUnstructuredGridVolumeRepresentation
{
public:
  static vtkSAVRUnstructuredVolumeRepresentation* New();
  vtkTypeMacro(vtkSAVRUnstructuredVolumeRepresentation, vtkUnstructuredGridVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Ignored: this representation always draws with vtkSAVRVolumeMapper.
  void SetActiveVolumeMapper(const char*) override;

  ///@{
  /// The mapper (GetMapper()), its settings and state; null makes new settings
  /// for the same mapper. ParaView passes those of the proxy's SAVRSettings sub-proxy.
  void SetSAVRSettings(vtkSAVRRepresentationSettings* settings);
  vtkSAVRRepresentationSettings* GetSAVRSettings() { return this->Settings; }
  ///@}

  /// The point array of particle radii for a grid of vertices (empty or "None": none), forwarded
  /// to the mapper by the settings, which hold the other particle settings.
  void SetParticleRadiusArray(const char* name);

  ///@{
  /// Shading, which the stock unstructured-grid volume representation does not offer: SAVR lights
  /// grids by per-point gradients. The coefficients are the surface's Lighting ones (shared).
  void SetShade(bool shade);
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  ///@}

  /// Also has the settings watch the view's renders (see vtkSAVRRepresentationSettings).
  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

protected:
  vtkSAVRUnstructuredVolumeRepresentation();
  ~vtkSAVRUnstructuredVolumeRepresentation() override;

  /// The stock parameters, and the vector mode as the stock representation sets it.
  void UpdateMapperParameters() override;

  /// Unstructured grids, composite data (as the stock representation) and structured grids.
  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// The stock preprocessing, then its tetrahedra replaced by the input's own cells.
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkSAVRUnstructuredVolumeRepresentation(const vtkSAVRUnstructuredVolumeRepresentation&) = delete;
  void operator=(const vtkSAVRUnstructuredVolumeRepresentation&) = delete;

  vtkSmartPointer<vtkSAVRRepresentationSettings> Settings; // the mapper's settings and driver
};

#endif

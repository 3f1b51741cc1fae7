/**
 * @class   vtkSAVRAMRVolumeRepresentation
 * @brief   Volume representation of vtkOverlappingAMR drawn natively by vtkSAVRVolumeMapper.
 *
 * ParaView's own AMR volume representation resamples the hierarchy to an image and draws that
 * with its own mapper. This one keeps the hierarchy: the view delivers the vtkOverlappingAMR
 * itself (vtkPVView::SetPiece / vtkPVRenderView::GetPieceProducer) and vtkSAVRVolumeMapper
 * samples it on the finest level present at each point. It owns a plain vtkVolume (ParaView's
 * vtkPVLODVolume refuses to draw a vtkVolumeMapper whose input is not a vtkDataSet) and a
 * vtkVolumeProperty fed by the lookup table, scalar opacity function and unit distance,
 * interpolation and shading properties; the colored array (SetInputArrayToProcess, cell or point
 * data) selects the mapper's scalars; the mapper's settings and its state
 * are those of its vtkSAVRRepresentationSettings, as in the other two representations.
 *
 * On several ranks the blocks of different ranks interleave in depth, which compositing cannot
 * order: each rank instead draws one convex region of the domain, with the blocks it needs from
 * the other ranks, and declares it for ordered compositing (see vtkSAVRAMRDistribution.h; the
 * mapper's cropping is set to the region, so the representation offers no cropping of its own;
 * blend modes other than composite gather every block on the first rank, which draws alone).
 *
 * The plugin's XML adds it to AMRRepresentation as "SAVR Volume".
 */
#ifndef vtkSAVRAMRVolumeRepresentation_h
#define vtkSAVRAMRVolumeRepresentation_h

#include "vtkPVDataRepresentation.h"
#include "vtkSAVRParaViewModule.h"         // For export macro
#include "vtkSAVRRepresentationSettings.h" // For vtkSmartPointer<vtkSAVRRepresentationSettings>
#include "vtkSmartPointer.h"               // For vtkSmartPointer

class vtkColorTransferFunction;
class vtkOverlappingAMR;
class vtkPiecewiseFunction;
class vtkSAVRVolumeMapper;
class vtkVolume;
class vtkVolumeProperty;

class VTKSAVRPARAVIEW_EXPORT vtkSAVRAMRVolumeRepresentation : public vtkPVDataRepresentation
{
public:
  static vtkSAVRAMRVolumeRepresentation* New();
  vtkTypeMacro(vtkSAVRAMRVolumeRepresentation, vtkPVDataRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

  /// Shows or hides the volume.
  void SetVisibility(bool visible) override;

  ///@{
  /// The volume's placement (as ParaView's volume representations have them).
  void SetPosition(double x, double y, double z);
  void SetScale(double x, double y, double z);
  void SetOrientation(double x, double y, double z);
  void SetOrigin(double x, double y, double z);
  void SetPickable(int pickable);
  ///@}

  ///@{
  /// Volume property settings (as ParaView's volume representations have them).
  void SetColor(vtkColorTransferFunction* lut);
  void SetScalarOpacity(vtkPiecewiseFunction* pwf);
  void SetScalarOpacityUnitDistance(double distance);
  void SetInterpolationType(int type);
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  void SetShade(bool shade);
  void SetBlendMode(int mode);
  ///@}

  ///@{
  /// The mapper (GetMapper()), its settings and state; null makes new settings
  /// for the same mapper. ParaView passes those of the proxy's SAVRSettings sub-proxy.
  void SetSAVRSettings(vtkSAVRRepresentationSettings* settings);
  vtkSAVRRepresentationSettings* GetSAVRSettings() { return this->Settings; }
  ///@}

  /// The volume this representation draws and the volume's property.
  vtkVolume* GetActor() { return this->Actor; }
  vtkVolumeProperty* GetVolumeProperty() { return this->Property; }

protected:
  vtkSAVRAMRVolumeRepresentation();
  ~vtkSAVRAMRVolumeRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

  /// The colored array and the volume property, pushed to the mapper before each render.
  void UpdateMapperParameters();

private:
  vtkSAVRAMRVolumeRepresentation(const vtkSAVRAMRVolumeRepresentation&) = delete;
  void operator=(const vtkSAVRAMRVolumeRepresentation&) = delete;

  vtkSmartPointer<vtkOverlappingAMR> Cache; // the hierarchy handed to the view for delivery
  vtkSAVRVolumeMapper* Mapper;              // owned
  vtkVolume* Actor;                         // owned
  vtkVolumeProperty* Property;              // owned
  double DataBounds[6];
  unsigned long DataSize = 0; // KiB
  // On several ranks: this rank's region of the domain (see vtkSAVRAMRDistribution), which it
  // alone draws and declares for ordered compositing.
  bool Distributed = false;
  double Region[6];
  bool Gathered = false;     // a blend mode that gathers every block on the first rank
  bool DrawsNothing = false; // this rank holds no blocks while they are gathered elsewhere
  vtkSmartPointer<vtkSAVRRepresentationSettings> Settings; // the mapper's settings and driver
};

#endif

/**
 * @class   vtkSAVRVolumeRepresentation
 * @brief   ParaView's image volume representation, drawn by vtkSAVRVolumeMapper.
 *
 * Everything ParaView's "Volume" representation of image data does (transfer functions, scalar
 * opacity unit distance, shading, blend mode, cropping, array selection, distributed rendering
 * with ordered compositing) with vtkSAVRVolumeMapper in place of the default mapper. Each still
 * render adds one refinement frame (or part of one, see MaximumRenderTime) until the mapper's
 * refinement is complete. The mapper's settings and its state are those of its
 * vtkSAVRRepresentationSettings.
 *
 * The plugin's XML adds it to UniformGridRepresentation as "SAVR Volume".
 */
#ifndef vtkSAVRVolumeRepresentation_h
#define vtkSAVRVolumeRepresentation_h

#include "vtkImageVolumeRepresentation.h"
#include "vtkSAVRParaViewModule.h"         // For export macro
#include "vtkSAVRRepresentationSettings.h" // For vtkSmartPointer<vtkSAVRRepresentationSettings>
#include "vtkSmartPointer.h"               // For vtkSmartPointer

class VTKSAVRPARAVIEW_EXPORT vtkSAVRVolumeRepresentation : public vtkImageVolumeRepresentation
{
public:
  static vtkSAVRVolumeRepresentation* New();
  vtkTypeMacro(vtkSAVRVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The mapper (GetMapper()), its settings and state; null makes new settings
  /// for the same mapper. ParaView passes those of the proxy's SAVRSettings sub-proxy.
  void SetSAVRSettings(vtkSAVRRepresentationSettings* settings);
  vtkSAVRRepresentationSettings* GetSAVRSettings() { return this->Settings; }
  ///@}

  /// Also has the settings watch the view's renders (see vtkSAVRRepresentationSettings).
  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

protected:
  vtkSAVRVolumeRepresentation();
  ~vtkSAVRVolumeRepresentation() override;

  /// The stock parameters, and the vector mode as the stock representation sets it.
  void UpdateMapperParameters() override;

private:
  vtkSAVRVolumeRepresentation(const vtkSAVRVolumeRepresentation&) = delete;
  void operator=(const vtkSAVRVolumeRepresentation&) = delete;

  vtkSmartPointer<vtkSAVRRepresentationSettings> Settings; // the mapper's settings and driver
};

#endif

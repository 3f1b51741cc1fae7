/**
 * @class   vtkSAVRVolumeRepresentation
 * @brief   ParaView's image volume representation, drawn by vtkSAVRVolumeMapper.
 *
 * Everything ParaView's "Volume" representation of image data does (transfer functions, scalar
 * opacity unit distance, shading, blend mode, cropping, array selection, distributed rendering
 * with ordered compositing) with vtkSAVRVolumeMapper in place of the default mapper, and the
 * mapper's settings forwarded. Each still render adds one refinement frame until the mapper's
 * refinement is complete; the getters report the mapper's state for information properties.
 *
 * The plugin's XML adds it to UniformGridRepresentation as "SAVR Volume".
 */
#ifndef vtkSAVRVolumeRepresentation_h
#define vtkSAVRVolumeRepresentation_h

#include "vtkImageVolumeRepresentation.h"
#include "vtkSAVRParaViewModule.h" // For export macro

class vtkSAVRRefinementDriver;
class vtkSAVRVolumeMapper;

class VTKSAVRPARAVIEW_EXPORT vtkSAVRVolumeRepresentation : public vtkImageVolumeRepresentation
{
public:
  static vtkSAVRVolumeRepresentation* New();
  vtkTypeMacro(vtkSAVRVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// Forwarded to vtkSAVRVolumeMapper (see its documentation for the defaults).
  void SetSampleDistance(double distance);
  void SetMaximumNumberOfFrames(int frames);
  void SetErrorTolerance(double tolerance);
  void SetPreIntegration(bool preIntegrate);
  void SetNumberOfThreads(int threads);
  ///@}

  /// Bytes the stored samples may take, forwarded to the mapper's 64-bit budget (negative
  /// values mean 0, which leaves every frame plain ray casting).
  void SetMemoryBudget(vtkIdType bytes);

  ///@{
  /// The mapper's state after the last render, for read-only information properties.
  int GetNumberOfFramesAccumulated();
  int GetFrameLimit();
  int GetRefinementComplete();
  double GetErrorEstimate();
  double GetLastFrameTime();
  double GetMemoryInUse();
  ///@}

  /// The mapper this representation draws with.
  vtkSAVRVolumeMapper* GetSAVRVolumeMapper() { return this->Mapper; }

  /// Also attaches the refinement driver to the view's interactor, when the view has one.
  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

protected:
  vtkSAVRVolumeRepresentation();
  ~vtkSAVRVolumeRepresentation() override;

private:
  vtkSAVRVolumeRepresentation(const vtkSAVRVolumeRepresentation&) = delete;
  void operator=(const vtkSAVRVolumeRepresentation&) = delete;

  vtkSAVRRefinementDriver* Driver; // re-renders while refinement is incomplete
  vtkSAVRVolumeMapper* Mapper;     // held by the superclass's VolumeMapper
};

#endif

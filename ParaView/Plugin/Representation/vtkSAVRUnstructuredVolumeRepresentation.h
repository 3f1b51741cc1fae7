/**
 * @class   vtkSAVRUnstructuredVolumeRepresentation
 * @brief   ParaView's unstructured-grid volume representation, drawn by vtkSAVRVolumeMapper.
 *
 * ParaView's "Volume" representation of unstructured grids (its preprocessing, which turns the
 * cells into tetrahedra, and its distributed rendering with data redistribution and ordered
 * compositing) with vtkSAVRVolumeMapper as the only mapper: the stock SelectMapper choice is
 * ignored. The mapper's settings and state are forwarded as in vtkSAVRVolumeRepresentation.
 *
 * The plugin's XML adds it to UnstructuredGridRepresentation as "SAVR Volume".
 */
#ifndef vtkSAVRUnstructuredVolumeRepresentation_h
#define vtkSAVRUnstructuredVolumeRepresentation_h

#include "vtkSAVRParaViewModule.h" // For export macro
#include "vtkUnstructuredGridVolumeRepresentation.h"

class vtkSAVRRefinementDriver;
class vtkSAVRVolumeMapper;

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
  /// Forwarded to vtkSAVRVolumeMapper (see vtkSAVRVolumeRepresentation).
  void SetSampleDistance(double distance);
  void SetMaximumNumberOfFrames(int frames);
  void SetErrorTolerance(double tolerance);
  void SetPreIntegration(bool preIntegrate);
  void SetNumberOfThreads(int threads);
  void SetMemoryBudget(vtkIdType bytes);
  ///@}

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
  vtkSAVRUnstructuredVolumeRepresentation();
  ~vtkSAVRUnstructuredVolumeRepresentation() override;

private:
  vtkSAVRUnstructuredVolumeRepresentation(const vtkSAVRUnstructuredVolumeRepresentation&) = delete;
  void operator=(const vtkSAVRUnstructuredVolumeRepresentation&) = delete;

  vtkSAVRRefinementDriver* Driver; // re-renders while refinement is incomplete
  vtkSAVRVolumeMapper* Mapper;     // owned by the superclass's list of mappers
};

#endif

/**
 * @class   vtkSAVRRepresentationSettings
 * @brief   The vtkSAVRVolumeMapper settings, state and refinement driver of a representation.
 *
 * What the plugin's three representations have in common: the mapper's settings (forwarded to
 * it), its state after the last render (for read-only information properties) and the
 * vtkSAVRRefinementDriver that re-renders the view while refinement is incomplete.
 *
 * Each representation owns one for its mapper. The plugin's XML defines the properties once, on
 * the "SAVRSettings" proxy, which each representation proxy holds as a sub-proxy: ParaView creates
 * this object for it and hands it to the representation's SetSAVRSettings(), which connects it to
 * the representation's mapper, so the properties reach that mapper.
 */
#ifndef vtkSAVRRepresentationSettings_h
#define vtkSAVRRepresentationSettings_h

#include "vtkCommand.h" // For vtkCommand::UserEvent
#include "vtkNew.h"     // For vtkNew
#include "vtkObject.h"
#include "vtkSAVRParaViewModule.h"   // For export macro
#include "vtkSAVRRefinementDriver.h" // For vtkNew<vtkSAVRRefinementDriver>
#include "vtkSAVRVolumeMapper.h"     // For vtkSmartPointer<vtkSAVRVolumeMapper>
#include "vtkSmartPointer.h"         // For vtkSmartPointer
#include "vtkWeakPointer.h"          // For vtkWeakPointer

class vtkAlgorithm;
class vtkInformation;
class vtkInformationRequestKey;
class vtkMatrix4x4;
class vtkPVDataRepresentation;
class vtkView;

class VTKSAVRPARAVIEW_EXPORT vtkSAVRRepresentationSettings : public vtkObject
{
public:
  static vtkSAVRRepresentationSettings* New();
  vtkTypeMacro(vtkSAVRRepresentationSettings, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Invoked after every frame of the mapper that sampled or re-blended (its ProgressEvent,
  /// renders by the refinement driver included): the state the information properties report
  /// has changed. vtkSMSAVRSettingsProxy refreshes them on it, for the Properties panel.
  enum
  {
    StateChangedEvent = vtkCommand::UserEvent + 0x5A8
  };

  /**
   * Makes `settings` (a new one when null) the settings of `mapper` held in `holder`: the
   * settings previously held detach their refinement driver. Representations call this from
   * their constructor (for their new mapper) and their SetSAVRSettings() (for the mapper of the
   * settings held so far), with themselves as `owner`: the mapper's progress (frames over the
   * limit, 1 once complete) becomes the owner's own ProgressEvent, which ParaView's progress
   * handler observes.
   */
  static void Install(vtkSmartPointer<vtkSAVRRepresentationSettings>& holder,
    vtkSAVRRepresentationSettings* settings, vtkSAVRVolumeMapper* mapper, vtkAlgorithm* owner);

  /**
   * For the plugin's own volume representations, at REQUEST_UPDATE: declares to the view a
   * volume drawn where its data is (never delivered to the client nor gathered, distributed
   * rendering required). With `region` (this rank's part of the domain), the ranks' images are
   * composited in the order of the regions, which are also given as the geometry bounds (ParaView
   * 5.11 orders the images by those, not by the bounds given for ordered compositing: it reads
   * the wrong key; compositing by depth would keep the background, which the other ranks draw
   * at the volume's depth). Without, the geometry bounds are `dataBounds`.
   */
  static void DeclareVolumeInPlace(vtkInformation* inInfo, vtkInformation* outInfo,
    vtkPVDataRepresentation* representation, const double* region, const double dataBounds[6],
    vtkMatrix4x4* matrix);

  ///@{
  /// The mapper the settings go to, whose state is reported and whose refinement is driven: the
  /// representation's mapper.
  void SetMapper(vtkSAVRVolumeMapper* mapper);
  vtkSAVRVolumeMapper* GetMapper() const { return this->Mapper; }
  ///@}

  ///@{
  /// Forwarded to vtkSAVRVolumeMapper (see its documentation for the defaults). Ignored while
  /// no mapper is set.
  void SetSampleDistance(double distance);
  void SetMaximumNumberOfFrames(int frames);
  void SetErrorTolerance(double tolerance);
  void SetPreIntegration(bool preIntegrate);
  void SetNumberOfThreads(int threads);
  ///@}

  ///@{
  /// The particle settings, forwarded to vtkSAVRVolumeMapper (they apply to point clouds: the
  /// points of a vtkPolyData, an unstructured grid of vertices): every particle's radius (0:
  /// automatic), the point array of radii (null, empty or "None": none), the kernel
  /// (vtkSAVRParticleSampler::Kernel) and whether the field is normalized. A change that moves
  /// the particles' reach (radius, radii, kernel) marks the representation modified, so that the
  /// view gets the new bounds.
  void SetParticleRadius(double radius);
  void SetParticleRadiusArray(const char* name);
  void SetParticleKernel(int kernel);
  void SetParticleNormalized(bool normalized);
  ///@}

  ///@{
  /// Whether a saved screenshot or animation frame is refined to completion within its capture
  /// (default true): during a capture the mapper's CompleteEachRender is set to this.
  vtkSetMacro(RefineSavedImages, bool);
  vtkGetMacro(RefineSavedImages, bool);
  ///@}

  /// Bytes the mapper may hold for a view, forwarded to its 64-bit budget (rounded to whole
  /// bytes; negative values and NaN mean 0, which leaves every frame plain ray casting). A double
  /// so that the property has a widget in ParaView's panel (5.11 has none for vtkIdType) and
  /// still holds any budget exactly (integers up to 2^53).
  void SetMemoryBudget(double bytes);

  ///@{
  /// The mapper's state after the last render, for read-only information properties (0 while
  /// no mapper is set).
  int GetNumberOfFramesAccumulated();
  int GetFrameLimit();
  int GetRefinementComplete();
  double GetErrorEstimate();
  double GetLastFrameTime();
  double GetMemoryInUse();
  ///@}

  /**
   * Attaches the refinement driver to the interactor of `view` (a vtkPVRenderView), or detaches
   * it when the view has none or is null. Where ParaView renders a view in this process with an
   * interactor (the GUI's built-in session, or pvpython/pvbatch after Interact()), the driver
   * re-renders the window on the interactor's repeating timer while refinement is incomplete,
   * and makes the mapper render single passes while the user drags: the image refines on its
   * own once interaction stops. Without an interactor (pvbatch scripts, render servers) every
   * Render() call is one frame.
   */
  void AttachRefinementDriver(vtkView* view);

  /// The refinement driver (see AttachRefinementDriver), whose StartEvent and EndEvent bracket
  /// each render it makes itself.
  vtkSAVRRefinementDriver* GetRefinementDriver() const { return this->Driver; }

  /// Representations pass each view request here: a render request attaches the driver and,
  /// while the view captures a screenshot, has the mapper refine to completion (see
  /// RefineSavedImages).
  void ProcessViewRequest(vtkInformationRequestKey* request, vtkView* view);

protected:
  vtkSAVRRepresentationSettings();
  ~vtkSAVRRepresentationSettings() override;

private:
  vtkSAVRRepresentationSettings(const vtkSAVRRepresentationSettings&) = delete;
  void operator=(const vtkSAVRRepresentationSettings&) = delete;

  void OnMapperProgress();
  void OwnerChanged(); // marks the owner (a vtkPVDataRepresentation) modified

  vtkSmartPointer<vtkSAVRVolumeMapper> Mapper;
  vtkWeakPointer<vtkAlgorithm> Owner; // the representation whose progress the mapper's becomes
  unsigned long MapperObserver = 0;   // the mapper's ProgressEvent, forwarded as StateChangedEvent
  vtkNew<vtkSAVRRefinementDriver> Driver; // re-renders while refinement is incomplete
  bool RefineSavedImages = true;
};

#endif

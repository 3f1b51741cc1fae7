/**
 * @class   vtkSAVRRepresentationSettings
 * @brief   The vtkSAVRVolumeMapper settings and state of a representation.
 *
 * What the plugin's representations have in common: the mapper's settings (forwarded to it) and
 * its state after the last render (for read-only information properties, among them whether
 * another render would refine the image, which vtkSMSAVRRefinementScheduler asks on the client
 * before it renders the view again).
 *
 * Each representation owns one for its mapper. The plugin's XML defines the properties once, on
 * the "SAVRSettings" proxy, which each representation proxy holds as a sub-proxy: ParaView creates
 * this object for it and hands it to the representation's SetSAVRSettings(), which connects it to
 * the representation's mapper, so the properties reach that mapper.
 */
#ifndef vtkSAVRRepresentationSettings_h
#define vtkSAVRRepresentationSettings_h

#include "vtkCommand.h" // For vtkCommand::UserEvent
#include "vtkObject.h"
#include "vtkSAVRParaViewModule.h" // For export macro
#include "vtkSAVRVolumeMapper.h"   // For vtkSmartPointer<vtkSAVRVolumeMapper>
#include "vtkSmartPointer.h"       // For vtkSmartPointer
#include "vtkWeakPointer.h"        // For vtkWeakPointer

#include <functional> // For std::function
#include <map>        // For std::map
#include <string>     // For std::string

class vtkAlgorithm;
class vtkInformation;
class vtkInformationRequestKey;
class vtkMatrix4x4;
class vtkPVDataRepresentation;
class vtkScalarsToColors;
class vtkView;
class vtkVolumeProperty;

class VTKSAVRPARAVIEW_EXPORT vtkSAVRRepresentationSettings : public vtkObject
{
public:
  static vtkSAVRRepresentationSettings* New();
  vtkTypeMacro(vtkSAVRRepresentationSettings, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Invoked after every frame of the mapper that sampled or re-blended (its ProgressEvent,
  /// renders made for the plugin's scheduler included): the state the information properties report
  /// has changed. vtkSMSAVRSettingsProxy refreshes them on it, for the Properties panel.
  enum
  {
    StateChangedEvent = vtkCommand::UserEvent + 0x5A8
  };

  /**
   * Makes `settings` (a new one when null) the settings of `mapper` held in `holder`: the
   * settings previously held stop watching their view. Representations call this from
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

  /**
   * The mapper's vector mode as the stock volume representations set vtkSmartVolumeMapper's:
   * with independent components (Map Scalars on, Multi Components Mapping off), the colour map's
   * (`color`: its VectorMode, magnitude or component, and its VectorComponent); otherwise none
   * (dependent components are drawn as colours).
   */
  static void SetVectorMode(
    vtkSAVRVolumeMapper* mapper, vtkVolumeProperty* property, vtkScalarsToColors* color);

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
  void SetMaximumRenderTime(double seconds);
  void SetMeshOpacityAsAttenuation(bool attenuation);
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
  /// The normalization set last (default true), whatever the mapper was given since.
  bool GetParticleNormalized() const { return this->ParticleNormalized; }
  ///@}

  ///@{
  /// Whether a saved screenshot or animation frame is refined to completion within its capture
  /// (default true): during a capture the mapper's CompleteEachRender is set to this.
  vtkSetMacro(RefineSavedImages, bool);
  vtkGetMacro(RefineSavedImages, bool);
  ///@}

  /// MiB (2^20 bytes) the mapper may hold for a view, forwarded to its 64-bit budget in bytes
  /// (rounded to whole bytes, so fractions of a MiB are kept; negative values and NaN mean 0,
  /// which leaves every frame plain ray casting). A double so that the panel shows a number a
  /// person reads (1024) and still holds any budget to the byte.
  void SetMemoryBudget(double mebibytes);

  ///@{
  /// The mapper's state after the last render, for read-only information properties (0 while
  /// no mapper is set).
  int GetNumberOfFramesAccumulated();
  int GetFrameLimit();
  int GetRefinementComplete();
  double GetErrorEstimate();
  double GetLastFrameTime();
  double GetMemoryInUse();
  double GetEffectiveSampleDistance();
  ///@}

  /// Forwarded to vtkSAVRVolumeMapper::SetInteractive: while on, renders are single passes
  /// that store nothing. vtkSMSAVRRefinementScheduler sets it for the renders ParaView makes
  /// while the user drags in a view, and clears it for the still renders after.
  void SetInteractive(int interactive);

  /**
   * 1 when the mapper drew in the latest render of the view the representation is in and left
   * its refinement incomplete: another still render of that view would add a frame. 0 when it
   * is complete, and also when the mapper took no part in that render (the representation is
   * hidden, inactive or has no array to draw: nothing to wait for).
   */
  int GetRefinementPending();

  /**
   * Representations pass each view request here (with their view): a render request starts
   * watching the view's renders (see GetRefinementPending) and, while the view captures a
   * screenshot, has the mapper refine to completion (see RefineSavedImages).
   */
  void ProcessViewRequest(vtkInformationRequestKey* request, vtkView* view);

  /// Representations call this when they leave their view: its renders are no longer watched.
  void ForgetView();

protected:
  vtkSAVRRepresentationSettings();
  ~vtkSAVRRepresentationSettings() override;

private:
  vtkSAVRRepresentationSettings(const vtkSAVRRepresentationSettings&) = delete;
  void operator=(const vtkSAVRRepresentationSettings&) = delete;

  void OnMapperProgress();
  void OnViewRenderStart();
  /// Sets `value` on the mapper with `setter` (the setting `name`), and again on any mapper set
  /// later.
  template <typename Value>
  void Keep(const char* name, void (vtkSAVRVolumeMapper::*setter)(Value), Value value)
  {
    this->Kept[name] = [setter, value](vtkSAVRVolumeMapper* mapper) { (mapper->*setter)(value); };
    if (this->Mapper)
    {
      (this->Mapper->*setter)(value);
    }
  }
  void OwnerChanged(); // marks the owner (a vtkPVDataRepresentation) modified

  vtkSmartPointer<vtkSAVRVolumeMapper> Mapper;
  vtkWeakPointer<vtkAlgorithm> Owner; // the representation whose progress the mapper's becomes
  unsigned long MapperObserver = 0;   // the mapper's ProgressEvent, forwarded as StateChangedEvent
  bool ParticleNormalized = true;
  std::map<std::string, std::function<void(vtkSAVRVolumeMapper*)>> Kept; // by name
  vtkWeakPointer<vtkObject> WatchedRenderer; // the view's renderer, whose renders are counted
  unsigned long RendererObserver = 0;
  vtkTypeUInt64 RendersBeforeViewRender = 0; // the mapper's count when the view's last began
  bool RefineSavedImages = true;
};

#endif

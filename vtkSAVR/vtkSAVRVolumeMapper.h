/**
 * @class   vtkSAVRVolumeMapper
 * @brief   Progressive CPU volume mapper: Sample-Accumulation Volume Rendering (SAVR).
 *
 * Every Render() samples each pixel's ray at the base step SampleDistance from a new offset
 * (van der Corput, rotated per pixel), keeps every sample taken since the view last changed and
 * blends the whole depth-ordered set through the transfer functions. After K frames (a power of
 * two) the image equals this mapper's one-frame image at SampleDistance / K, to float round-off:
 * each pixel's samples lie on a lattice anchored at a phase of its own measured in the default
 * step, whatever SampleDistance is. When only the transfer functions change, the stored
 * samples are blended again without resampling; when nothing changed after the last frame, the
 * last image is drawn again. A change of view, viewport, volume matrix, input, sampling settings
 * or blend mode starts over.
 *
 * Rendering is on the CPU with TBB threads; images do not depend on the thread count. Rays stop
 * at the depth of opaque geometry already drawn. Use vtkSAVRRefinementDriver to keep refining in
 * an interactive window.
 *
 * Input, point or cell scalars of any numeric type (images: one to four components,
 * independent or dependent; other inputs: one) on:
 * - vtkImageData (vtkSAVRImageSampler),
 * - vtkOverlappingAMR, sampled on the finest level present at each point (vtkSAVRAMRSampler),
 * - vtkUnstructuredGrid of tetrahedra, hexahedra, voxels, wedges and pyramids, walked cell to
 *   cell along each ray (vtkSAVRUnstructuredSampler),
 * - vtkStructuredGrid (curvilinear) and vtkRectilinearGrid, walked the same way through their
 *   hexahedra and voxels (blanked cells are transparent),
 * - vtkPolyData, whose points are particles sampled through a kernel (vtkSAVRParticleSampler;
 *   see ParticleRadius).
 * The default SampleDistance is the smallest voxel edge for images, the coarsest level's cell
 * edge for AMR (refinement then reaches a quarter of the finest level's), and the typical cell
 * size for unstructured grids, but no more than a 16th of the mesh's diagonal (refinement then
 * reaches a quarter of the cell, and no more than a 128th of the diagonal: a mesh of few large
 * cells gets clean silhouettes).
 *
 * Honors the volume property's color (RGB or gray) and scalar opacity functions,
 * ScalarOpacityUnitDistance, InterpolationType, shading (Shade, Ambient, Diffuse, Specular,
 * SpecularPower, the renderer's lights), gradient opacity and isosurface values; the mapper's
 * cropping, clipping planes and scalar selection; and the blend modes COMPOSITE,
 * MAXIMUM_INTENSITY, MINIMUM_INTENSITY, AVERAGE_INTENSITY, ADDITIVE and ISOSURFACE.
 *
 * After each frame that added samples or re-blended them, the mapper invokes
 * vtkSAVRVolumeMapper::RefinementFrameEvent with a FrameInfo as call data, then
 * vtkCommand::ProgressEvent with the progress (frames accumulated over the frame limit, 1 once
 * refinement is complete) as a double. VTK 9.1 names no event beyond its own, so Python callbacks
 * see RefinementFrameEvent as "NoEvent" and cannot read a FrameInfo: from Python, observe
 * "ProgressEvent" (with `@calldata_type(VTK_DOUBLE)` to receive the progress) and read the rest
 * from the getters. During a vtkHardwareSelector's passes the mapper draws nothing.
 */
#ifndef vtkSAVRVolumeMapper_h
#define vtkSAVRVolumeMapper_h

#include "vtkCommand.h"
#include "vtkSAVRModule.h" // For export macro
#include "vtkVolumeMapper.h"

#include <memory> // For std::unique_ptr
#include <string> // For std::string

class vtkOverlappingAMR;
class vtkUnstructuredGrid;

class VTKSAVR_EXPORT vtkSAVRVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkSAVRVolumeMapper* New();
  vtkTypeMacro(vtkSAVRVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Invoked after every frame that sampled or re-blended (not for a reused image), with a
  /// pointer to a FrameInfo as call data.
  enum
  {
    RefinementFrameEvent = vtkCommand::UserEvent + 0x5A7
  };

  /// What RefinementFrameEvent reports.
  struct FrameInfo
  {
    int FramesAccumulated;
    int FrameLimit;
    double ErrorEstimate; // as GetErrorEstimate()
    double FrameTime;     // seconds
    bool Complete;
  };

  ///@{
  /**
   * Base distance between one frame's samples along a ray, in world units. 0 (the default)
   * means the smallest voxel spacing, measured in world units.
   */
  vtkSetClampMacro(SampleDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(SampleDistance, double);
  ///@}

  ///@{
  /**
   * Frames to accumulate before the image is final. 0 (the default) chooses the smallest power
   * of two whose effective step, SampleDistance / frames, is at most a quarter of the smallest
   * voxel spacing (so the final image samples each voxel at least four times); for unstructured
   * grids a quarter of the typical cell, and no more than a 128th of the mesh's diagonal.
   */
  vtkSetClampMacro(MaximumNumberOfFrames, int, 0, 1 << 16);
  vtkGetMacro(MaximumNumberOfFrames, int);
  ///@}

  ///@{
  /**
   * Bytes the mapper may hold for a view (default 1 GiB): its images, ray tables, display
   * texture and scratch (GetImageMemoryInUse()), and the stored samples, which have what
   * remains. When the frames asked for do not fit, fewer frames are accumulated; when not even
   * one fits, every frame is plain ray casting. When the images alone do not fit, Render reports
   * an error and draws nothing. While shading or gradient opacity is on, image data's per-voxel
   * gradients (6 bytes per point, computed once per data change on first use) count with the
   * images. What the stored samples leave holds unstructured and curvilinear grids' ray paths
   * (what each ray crosses, recorded by the first frame, so that later frames need not walk the
   * mesh again; freed when refinement completes). The samplers' own structures (the
   * unstructured sampler's copy of a mesh) are not counted.
   */
  vtkSetMacro(MemoryBudget, vtkTypeUInt64);
  vtkGetMacro(MemoryBudget, vtkTypeUInt64);
  ///@}

  ///@{
  /**
   * While true, frames are single passes at SampleDistance that store nothing (the camera is
   * moving; what would be stored is lost at the next change). Accumulation restarts when it is
   * set back to false. Default false; vtkSAVRRefinementDriver sets it during interaction.
   */
  vtkSetMacro(Interactive, bool);
  vtkGetMacro(Interactive, bool);
  vtkBooleanMacro(Interactive, bool);
  ///@}

  ///@{
  /**
   * While Interactive, keep single passes within the time VTK allocates the volume
   * (vtkProp::GetAllocatedRenderTime, from the window's DesiredUpdateRate, which VTK's
   * interactor styles raise during a drag), as vtkFixedPointVolumeRayCastMapper's option of the
   * same name does: a pass that took longer than its time coarsens the next one by as many
   * halvings of its cost as it was over: first the step, doubled up to 8 times the base step
   * (on the frames' lattice), then the pixels, one ray for every 2x2, 4x4 and at most 8x8 pixels
   * (as the fixed-point mapper's image sample distance does); one that took well under refines
   * by one level, the pixels first, then the step. Still frames are not affected. Default
   * true.
   */
  vtkSetMacro(AutoAdjustSampleDistances, bool);
  vtkGetMacro(AutoAdjustSampleDistances, bool);
  vtkBooleanMacro(AutoAdjustSampleDistances, bool);
  ///@}

  ///@{
  /**
   * What AVERAGE_INTENSITY_BLEND and ADDITIVE_BLEND draw. True (the default): VTK's definitions,
   * as its GPU mapper draws them (vtkVolumeMapper's documentation; the fixed-point mapper has
   * neither): opaque grey over the volume, for average the mean over the ray of the scalar
   * opacity times the value normalized over the data's range (VTK's AverageIPScalarRange is not
   * applied), for additive the integral over the ray of the scalar opacity per
   * ScalarOpacityUnitDistance times the normalized value, clamped to 1. False: average draws the
   * transfer function's colour and opacity at the ray's length-weighted mean value, additive
   * the sum of the intervals' opacities times their colours.
   */
  vtkSetMacro(IntensityAsGrey, bool);
  vtkGetMacro(IntensityAsGrey, bool);
  vtkBooleanMacro(IntensityAsGrey, bool);
  ///@}

  /// The step of the next single pass while Interactive (world units): the effective sample
  /// distance times what AutoAdjustSampleDistances has made of it.
  double GetInteractiveSampleDistance() const;

  /// The pixels per ray, across and up, of the next single pass while Interactive (1, 2, 4 or
  /// 8): what AutoAdjustSampleDistances has made of them.
  int GetInteractivePixelStride() const;

  ///@{
  /**
   * While true, each Render refines to completion (the frame limit, or ErrorTolerance) before
   * it draws, instead of adding one frame: for a saved image that must be the refined one (the
   * ParaView plugin sets it while a screenshot or an animation frame is captured). Every frame
   * still invokes its events. Default false. No effect while Interactive.
   */
  vtkSetMacro(CompleteEachRender, bool);
  vtkGetMacro(CompleteEachRender, bool);
  vtkBooleanMacro(CompleteEachRender, bool);
  ///@}

  ///@{
  /**
   * Seconds a Render() that accumulates may spend sampling (0, the default, for no bound): a
   * frame that needs longer is continued by the next renders, tile by tile in a fixed order,
   * each tile's pixels showing the frames it has, so that the caller (an event loop) is never
   * held for long. The frame counts in GetNumberOfFramesAccumulated() once its last tile is
   * done, and the image then is the same as unbounded, whatever the timing. The bound is passed
   * by at most one tile per thread. Single passes while
   * Interactive and renders with CompleteEachRender are not bounded. The ParaView plugin's
   * default is 0.2.
   */
  vtkSetClampMacro(MaximumRenderTime, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumRenderTime, double);
  ///@}

  ///@{
  /**
   * How the scalar opacity of unstructured and curvilinear grids (not particles) is read. True
   * (the default): as VTK's unstructured mappers (vtkProjectedTetrahedraMapper,
   * vtkUnstructuredGridVolumeRayCastMapper, and so ParaView's stock "Volume" of such grids)
   * read it, an attenuation coefficient per ScalarOpacityUnitDistance: a segment of length L has
   * opacity 1 - exp(-opacity L / unit distance), so opacity 1 is not opaque. False: as the image
   * mappers read it, the opacity of a segment one unit distance long (the rule for image data,
   * AMR and particles whatever this is), so a grid renders as the same values on an image do.
   */
  vtkSetMacro(MeshOpacityAsAttenuation, bool);
  vtkGetMacro(MeshOpacityAsAttenuation, bool);
  vtkBooleanMacro(MeshOpacityAsAttenuation, bool);
  ///@}

  ///@{
  /**
   * Refinement stops early once GetErrorEstimate() falls below this (premultiplied RGBA in
   * [0, 1], root mean square over the image); before that, each 16x16 tile of the image whose
   * own estimate (the same measure over its pixels) is below it stops taking samples while the
   * others go on, and resumes if a transfer-function edit makes it change again. 0 (the
   * default) refines every tile to the frame limit.
   */
  vtkSetClampMacro(ErrorTolerance, double, 0.0, 1.0);
  vtkGetMacro(ErrorTolerance, double);
  ///@}

  ///@{
  /**
   * Composite blending pre-integrates the segment between each pair of consecutive stored
   * samples (the value varying linearly along it) instead of giving each sample an interval.
   * Far more accurate for stiff transfer functions (narrow peaks); slower to blend. Changing it
   * re-blends the stored samples. Default false.
   */
  vtkSetMacro(PreIntegration, bool);
  vtkGetMacro(PreIntegration, bool);
  vtkBooleanMacro(PreIntegration, bool);
  ///@}

  ///@{
  /**
   * Composite blending of one component pre-integrates by itself (as PreIntegration does) while
   * the transfer functions have features narrower than one level of integral data, a spike that
   * point samples would hit only by chance, speckling the image, and gradient opacity is not in
   * use. Default true. GetPreIntegrating() says whether the last frame pre-integrated.
   */
  vtkSetMacro(AutoPreIntegration, bool);
  vtkGetMacro(AutoPreIntegration, bool);
  vtkBooleanMacro(AutoPreIntegration, bool);
  bool GetPreIntegrating() const;
  ///@}

  ///@{
  /**
   * Vector arrays, as vtkSmartVolumeMapper's VectorMode: DISABLED (-1, the default) draws an
   * array of several components as it always has (independent components, each through its own
   * functions, or dependent ones as colours); MAGNITUDE (0) draws its magnitude and COMPONENT (1)
   * its component VectorComponent (clamped to the array's), each as one component through the
   * functions of component 0, on every kind of input. Applies while the volume property's
   * components are independent (dependent components are colours), and to arrays of several
   * components only. Changing either starts over.
   */
  enum VectorModeType
  {
    DISABLED = -1,
    MAGNITUDE = 0,
    COMPONENT = 1
  };
  vtkSetClampMacro(VectorMode, int, DISABLED, COMPONENT);
  vtkGetMacro(VectorMode, int);
  vtkSetClampMacro(VectorComponent, int, 0, VTK_INT_MAX);
  vtkGetMacro(VectorComponent, int);
  ///@}

  ///@{
  /**
   * Particles: with a vtkPolyData input every point is a particle carrying its scalar, sampled
   * through a kernel of radius h (see vtkSAVRParticleSampler): ParticleRadius for every particle
   * (0, the default, picks the mean distance between particles) unless the point array named
   * ParticleRadiusArrayName gives each its own; ParticleKernel GAUSSIAN (exp(-r^2 / 2h^2) cut at
   * 3h, the default), SPH_CUBIC or SPH_QUINTIC (vtkSPHCubicKernel's and vtkSPHQuinticKernel's
   * splines); ParticleNormalized (default true) draws the kernel-weighted mean of the values,
   * false their weighted sum; false without a scalar array, the particles' density (each
   * particle 1). The default SampleDistance is half the median radius.
   * Changing any of them rebuilds the particles' index and starts over.
   */
  vtkSetMacro(ParticleRadius, double);
  vtkGetMacro(ParticleRadius, double);
  vtkSetStringMacro(ParticleRadiusArrayName);
  vtkGetStringMacro(ParticleRadiusArrayName);
  vtkSetClampMacro(ParticleKernel, int, 0, 2);
  vtkGetMacro(ParticleKernel, int);
  vtkSetMacro(ParticleNormalized, bool);
  vtkGetMacro(ParticleNormalized, bool);
  vtkBooleanMacro(ParticleNormalized, bool);
  ///@}

  ///@{
  /// Threads to render with; 0 (the default) uses all cores. Images do not depend on it.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /// Frames whose samples are stored and blended in the current image.
  int GetNumberOfFramesAccumulated() const;
  /// The fraction of the next frame that earlier renders have done (see MaximumRenderTime); 0
  /// when no frame is under way.
  double GetFrameInProgress() const;
  /// Frames the current view will accumulate (the setting, capped by the memory budget).
  int GetFrameLimit() const;
  /// True when no further frame would add samples for the current view and the image shown is
  /// the blend of all of them (also true when the input cannot be drawn at all).
  bool GetRefinementComplete() const;
  /// Bytes allocated for stored samples now: room for four frames from the first on, grown
  /// fourfold at a time, never past the frame limit (at most four times the samples stored;
  /// exactly them once refinement is complete).
  vtkTypeUInt64 GetMemoryInUse() const;
  /// Bytes of MemoryBudget held for the current view besides stored samples: the images (float
  /// and 8-bit), the error estimate's earlier image, the ray tables, the display's copy and
  /// texture, the depth buffer when read, and per-thread scratch. 0 when Render refused a view
  /// whose images do not fit (its error names the bytes they need).
  vtkTypeUInt64 GetImageMemoryInUse() const;
  /// Samples stored now: the rows kept per ray (from its front to its opacity horizon, or
  /// whole), times the frames accumulated.
  vtkTypeUInt64 GetNumberOfStoredSamples() const;
  /// Samples read from the data since the mapper was created, by stored frames and single
  /// passes alike: unchanged by a render that only re-blends or redraws.
  vtkTypeUInt64 GetNumberOfSamplesTaken() const;
  /**
   * The image's estimated remaining error: the root mean square, over the premultiplied RGBA of
   * every pixel, of the change between the image at K frames and at the largest power of two of
   * frames below K. Negative until two frames exist. When the image converges at least linearly
   * in the step, this is about the error left, or more.
   */
  double GetErrorEstimate() const;
  /// Render() calls that made a frame so far (not those of a hardware selector, nor dual depth
  /// peeling's later stages of the same frame): lets a caller tell whether the mapper took part
  /// in a given render of its window.
  vtkTypeUInt64 GetNumberOfRenders() const { return this->NumberOfRenders; }
  /// Wall-clock seconds the last Render() took.
  double GetLastFrameTime() const { return this->LastFrameTime; }
  /// The base step in effect (world units), after the default is resolved and, when one frame
  /// at that step would take more than 2^26 samples, coarsened by a power of two (with a warning
  /// when SampleDistance was set; a default the mapper coarsens is reported here only); the
  /// refined image's step is this divided by the frames accumulated.
  double GetEffectiveSampleDistance() const;

  ///@{
  /**
   * The input: vtkImageData (as for every volume mapper), vtkUnstructuredGrid,
   * vtkStructuredGrid or vtkRectilinearGrid (SetInputData of a vtkDataSet) or vtkOverlappingAMR;
   * or connect any of them with SetInputConnection.
   */
  using vtkVolumeMapper::SetInputData;
  void SetInputData(vtkDataSet* input) override;
  void SetInputData(vtkUnstructuredGrid* grid);
  void SetInputData(vtkOverlappingAMR* amr);
  ///@}

  /// Bounds of the input, for any input type.
  double* GetBounds() VTK_SIZEHINT(6) override;
  void GetBounds(double bounds[6]) override { this->Superclass::GetBounds(bounds); }

  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow*) override;

protected:
  vtkSAVRVolumeMapper();
  ~vtkSAVRVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  double SampleDistance = 0.0;
  int MaximumNumberOfFrames = 0;
  vtkTypeUInt64 MemoryBudget = vtkTypeUInt64(1) << 30;
  bool Interactive = false;
  bool CompleteEachRender = false;
  int NumberOfThreads = 0;
  double ErrorTolerance = 0.0;
  double MaximumRenderTime = 0.0;
  bool MeshOpacityAsAttenuation = true;
  bool AutoAdjustSampleDistances = true;
  bool IntensityAsGrey = true;
  bool PreIntegration = false;
  bool AutoPreIntegration = true;
  double LastFrameTime = 0.0;
  vtkTypeUInt64 NumberOfRenders = 0;
  int VectorMode = DISABLED;
  int VectorComponent = 0;
  double ParticleRadius = 0.0;
  char* ParticleRadiusArrayName = nullptr;
  int ParticleKernel = 0;
  bool ParticleNormalized = true;

private:
  vtkSAVRVolumeMapper(const vtkSAVRVolumeMapper&) = delete;
  void operator=(const vtkSAVRVolumeMapper&) = delete;

  struct Internals;
  std::unique_ptr<Internals> State;

  ///@{
  /**
   * The stages of Render(), in order. Each that can find the frame impossible returns false
   * (after Fail, when the reason is the input or the settings).
   */
  struct Frame; // what one Render() works on
  bool UpdateSampler(Frame& frame);
  bool BuildSampler(Frame& frame);
  bool ResolveSettings(Frame& frame);
  bool UpdateView(Frame& frame);
  void UpdateTables(Frame& frame);
  bool SampleOrBlend(Frame& frame);
  void PreviewFirstFrame(Frame& frame);
  bool RefineToCompletion(Frame& frame, bool imageChanged);
  void DisplayImage(Frame& frame, bool imageChanged);
  void DrawPeelingStage(vtkRenderer* ren);
  void FinishFrame(Frame& frame, bool imageChanged);
  /// After an interactive single pass: the step factor of the next (AutoAdjustSampleDistances).
  void AdaptInteractiveStep(Frame& frame);
  ///@}
  /// Reports `message` (once while it repeats) and forgets the image: nothing can be drawn.
  void Fail(Frame& frame, const std::string& message);
  /// Reports `message` once while it repeats.
  void ReportError(const std::string& message);
  /// True when no input is connected (nothing to wait for).
  bool HasNoInput() const;
  /// The input's bounds as VTK computes them (AMR included), with no check.
  double* InputBounds();
};

#endif

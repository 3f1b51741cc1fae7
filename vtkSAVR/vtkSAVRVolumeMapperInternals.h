// Private to the module: the mapper's state between renders (Internals) and what one Render()
// works on (Frame), shared by vtkSAVRVolumeMapper.cxx (the render and its display) and
// vtkSAVRVolumeMapperFrame.cxx (the VTK state turned into the engine's input, view and tables).
#ifndef vtkSAVRVolumeMapperInternals_h
#define vtkSAVRVolumeMapperInternals_h

#include "vtkSAVRVolumeMapper.h"

#include "frame/FrameLoop.h"
#include "vtkSAVRDualPeeling.h"
#include "vtkSAVRFrameChanges.h"
#include "vtkSAVRImageDisplay.h"
#include "vtkSAVRInputSamplers.h"
#include "vtkSAVRMapperSettings.h"
#include "vtkSAVRPropertyTables.h"
#include "vtkSAVRVectorSelection.h"

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

class vtkDataArray;
class vtkDataObject;
class vtkRenderer;
class vtkVolume;
class vtkVolumeProperty;

/// The settings of `mapper` that the private helpers read (vtkSAVRVolumeMapperFrame.cxx).
vtkSAVRMapperSettings vtkSAVRMapperSettingsOf(vtkSAVRVolumeMapper* mapper);

struct vtkSAVRVolumeMapper::Internals
{
  savr::FrameLoop Loop;
  vtkSAVRPropertyTables Tables;
  vtkSAVRFrameChanges Changes;
  vtkSAVRImageDisplay Display;
  // Dual depth peeling for volumes: the stage calling Render, and what its later stages draw
  // from (the frame of the first stage: its blend mode, and whether it made an image).
  vtkSAVRDualPeeling Peeling;
  savr::BlendMode PeelingMode = savr::BlendMode::Composite;
  bool PeelingImage = false;
  vtkSAVRInputSamplers Inputs;
  vtkSAVRVectorSelection::Cache Vectors;            // a vector array as the component it draws
  std::shared_ptr<const savr::Sampler> DataSampler; // the input's, as built
  std::shared_ptr<const savr::Sampler> Sampler;     // the image's, cropped when cropping is on
  std::vector<unsigned char> Bytes;
  std::string LastError;
  double Step = 0.0;
  double SmallestSpacing = 0.0; // the finest cell edge, in world units
  double DefaultStep = 0.0;     // SampleDistance's default
  double FinestStep = 0.0;      // the step automatic refinement reaches
  double CoarsenedStep = 0.0;   // the step asked that was last reported coarsened
  bool HaveImage = false;
  bool PreIntegrating = false; // the last frame's composite was pre-integrated
  // The step of interactive single passes, in base steps (a power of two, 1 to 8).
  double InteractiveStepFactor = 1.0;
  // Pixels per ray, across and up, of interactive single passes (1 to 8), once the step is at
  // its coarsest.
  int InteractivePixelStride = 1;
  // Nothing can be drawn (bad input, empty viewport): further frames would add nothing.
  bool NothingToRefine = false;
  // The input's bounds leave nothing to draw (found by GetBounds: VTK then never calls Render).
  bool UnusableBounds = false;
  // The particles' support bounds (GetBounds), as Changes.ParticleBoundsChanged last found them.
  double ParticleBounds[6] = { 0, 0, 0, 0, 0, 0 };

  // Every frame is taken, or the error estimate is below the tolerance, and the image shown is
  // their blend (not an interacting pass).
  bool Complete(double tolerance) const
  {
    const double estimate = this->Loop.ErrorEstimate();
    return (this->Loop.Complete() || (tolerance > 0.0 && estimate >= 0.0 && estimate < tolerance));
  }

  void ClearImage()
  {
    this->Loop.Reset(savr::View(), nullptr, savr::FrameSettings());
    this->Changes.ForgetView();
    this->HaveImage = false;
  }
};

struct vtkSAVRVolumeMapper::Frame
{
  vtkRenderer* Renderer = nullptr;
  vtkVolume* Volume = nullptr;
  vtkVolumeProperty* Property = nullptr;
  vtkSAVRMapperSettings Mapper; // the mapper's settings, read once at the render's start
  std::chrono::steady_clock::time_point Start = std::chrono::steady_clock::now();
  /// Seconds since Start.
  double Seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }
  vtkDataObject* Input = nullptr;
  vtkDataArray* Scalars = nullptr; // of an image or a mesh
  int CellFlag = 0;
  savr::BlendMode Mode = savr::BlendMode::Composite;
  int Components = 1;
  bool GradientOpacity = false;
  savr::FrameSettings Settings; // as vtkSAVRFrameSettings resolved them, and the view's reserve
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  double Diagonal = 0.0;    // of Bounds
  int Origin[2] = { 0, 0 }; // of the viewport in the window
  savr::View View;
  bool Peeling = false; // made at dual depth peeling's first volume stage
};

#endif

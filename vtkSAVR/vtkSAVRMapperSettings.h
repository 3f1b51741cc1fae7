// Private to the module: the mapper's settings that its private helpers read (what decides the
// frame's mode, sampling and inputs), copied from the mapper at each render, so that the helpers
// depend on these values and not on the public mapper class.
#ifndef vtkSAVRMapperSettings_h
#define vtkSAVRMapperSettings_h

#include "vtkType.h"

#include <array>
#include <string>

struct vtkSAVRMapperSettings
{
  // vtkVolumeMapper's
  int BlendMode = 0;
  bool Cropping = false;
  std::array<double, 6> CroppingRegionPlanes{};
  int CroppingRegionFlags = 0;
  // vtkAbstractMapper's scalar selection
  int ScalarMode = 0;
  int ArrayAccessMode = 0;
  int ArrayId = -1;
  std::string ArrayName; // empty when none is set
  // vtkSAVRVolumeMapper's
  double SampleDistance = 0.0;
  int MaximumNumberOfFrames = 0;
  vtkTypeUInt64 MemoryBudget = 0;
  int NumberOfThreads = 0;
  bool IntensityAsGrey = false;
  bool PreIntegration = false;
  bool AutoPreIntegration = false;
  int VectorMode = -1; // as the volume property lets it apply (vtkSAVRVectorSelection::Effective)
  int VectorComponent = 0;
  double ParticleRadius = 0.0;
  std::string ParticleRadiusArrayName; // empty when none is set
  int ParticleKernel = 0;
  bool ParticleNormalized = false;
};

#endif

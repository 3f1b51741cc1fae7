#include "vtkSAVRUnstructuredVolumeRepresentation.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSAVRViewRefinement.h"
#include "vtkSAVRVolumeMapper.h"

#include <algorithm>

namespace
{
const char* const MapperName = "SAVR";
}

vtkStandardNewMacro(vtkSAVRUnstructuredVolumeRepresentation);

vtkSAVRUnstructuredVolumeRepresentation::vtkSAVRUnstructuredVolumeRepresentation()
{
  vtkNew<vtkSAVRVolumeMapper> mapper;
  this->Mapper = mapper;
  this->AddVolumeMapper(MapperName, mapper);
  this->Superclass::SetActiveVolumeMapper(MapperName);
  this->Driver = vtkSAVRRefinementDriver::New();
  this->Driver->SetMapper(this->Mapper);
}

vtkSAVRUnstructuredVolumeRepresentation::~vtkSAVRUnstructuredVolumeRepresentation()
{
  this->Driver->Delete();
}

int vtkSAVRUnstructuredVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  const int result = this->Superclass::ProcessViewRequest(request, inInfo, outInfo);
  if (request == vtkPVView::REQUEST_RENDER())
  {
    vtkSAVRAttachRefinementDriver(this->Driver, this->GetView());
  }
  return result;
}

void vtkSAVRUnstructuredVolumeRepresentation::SetActiveVolumeMapper(const char*)
{
  // The stock SelectMapper property sets its default here at creation; keep SAVR.
}

void vtkSAVRUnstructuredVolumeRepresentation::SetSampleDistance(double distance)
{
  this->Mapper->SetSampleDistance(distance);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetMaximumNumberOfFrames(int frames)
{
  this->Mapper->SetMaximumNumberOfFrames(frames);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetErrorTolerance(double tolerance)
{
  this->Mapper->SetErrorTolerance(tolerance);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetPreIntegration(bool preIntegrate)
{
  this->Mapper->SetPreIntegration(preIntegrate);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetNumberOfThreads(int threads)
{
  this->Mapper->SetNumberOfThreads(threads);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetMemoryBudget(vtkIdType bytes)
{
  this->Mapper->SetMemoryBudget(static_cast<vtkTypeUInt64>(std::max<vtkIdType>(bytes, 0)));
}

int vtkSAVRUnstructuredVolumeRepresentation::GetNumberOfFramesAccumulated()
{
  return this->Mapper->GetNumberOfFramesAccumulated();
}

int vtkSAVRUnstructuredVolumeRepresentation::GetFrameLimit()
{
  return this->Mapper->GetFrameLimit();
}

int vtkSAVRUnstructuredVolumeRepresentation::GetRefinementComplete()
{
  return this->Mapper->GetRefinementComplete() ? 1 : 0;
}

double vtkSAVRUnstructuredVolumeRepresentation::GetErrorEstimate()
{
  return this->Mapper->GetErrorEstimate();
}

double vtkSAVRUnstructuredVolumeRepresentation::GetLastFrameTime()
{
  return this->Mapper->GetLastFrameTime();
}

double vtkSAVRUnstructuredVolumeRepresentation::GetMemoryInUse()
{
  return static_cast<double>(this->Mapper->GetMemoryInUse());
}

void vtkSAVRUnstructuredVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRVolumeMapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

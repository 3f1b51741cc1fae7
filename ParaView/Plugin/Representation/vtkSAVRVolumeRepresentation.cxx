#include "vtkSAVRVolumeRepresentation.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSAVRViewRefinement.h"
#include "vtkSAVRVolumeMapper.h"

#include <algorithm>

vtkStandardNewMacro(vtkSAVRVolumeRepresentation);

vtkSAVRVolumeRepresentation::vtkSAVRVolumeRepresentation()
{
  // The superclass uses only vtkVolumeMapper's interface on its mapper (and down-casts for the
  // mapper-specific settings), so replacing it here is all it takes.
  vtkNew<vtkSAVRVolumeMapper> mapper;
  this->Mapper = mapper;
  this->VolumeMapper = mapper.GetPointer();
  this->Driver = vtkSAVRRefinementDriver::New();
  this->Driver->SetMapper(this->Mapper);
}

vtkSAVRVolumeRepresentation::~vtkSAVRVolumeRepresentation()
{
  this->Driver->Delete();
}

int vtkSAVRVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  const int result = this->Superclass::ProcessViewRequest(request, inInfo, outInfo);
  if (request == vtkPVView::REQUEST_RENDER())
  {
    vtkSAVRAttachRefinementDriver(this->Driver, this->GetView());
  }
  return result;
}

void vtkSAVRVolumeRepresentation::SetSampleDistance(double distance)
{
  this->Mapper->SetSampleDistance(distance);
}

void vtkSAVRVolumeRepresentation::SetMaximumNumberOfFrames(int frames)
{
  this->Mapper->SetMaximumNumberOfFrames(frames);
}

void vtkSAVRVolumeRepresentation::SetErrorTolerance(double tolerance)
{
  this->Mapper->SetErrorTolerance(tolerance);
}

void vtkSAVRVolumeRepresentation::SetPreIntegration(bool preIntegrate)
{
  this->Mapper->SetPreIntegration(preIntegrate);
}

void vtkSAVRVolumeRepresentation::SetNumberOfThreads(int threads)
{
  this->Mapper->SetNumberOfThreads(threads);
}

void vtkSAVRVolumeRepresentation::SetMemoryBudget(vtkIdType bytes)
{
  this->Mapper->SetMemoryBudget(static_cast<vtkTypeUInt64>(std::max<vtkIdType>(bytes, 0)));
}

int vtkSAVRVolumeRepresentation::GetNumberOfFramesAccumulated()
{
  return this->Mapper->GetNumberOfFramesAccumulated();
}

int vtkSAVRVolumeRepresentation::GetFrameLimit()
{
  return this->Mapper->GetFrameLimit();
}

int vtkSAVRVolumeRepresentation::GetRefinementComplete()
{
  return this->Mapper->GetRefinementComplete() ? 1 : 0;
}

double vtkSAVRVolumeRepresentation::GetErrorEstimate()
{
  return this->Mapper->GetErrorEstimate();
}

double vtkSAVRVolumeRepresentation::GetLastFrameTime()
{
  return this->Mapper->GetLastFrameTime();
}

double vtkSAVRVolumeRepresentation::GetMemoryInUse()
{
  return static_cast<double>(this->Mapper->GetMemoryInUse());
}

void vtkSAVRVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRVolumeMapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

#include "vtkSAVRVolumeRepresentation.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVView.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"

vtkStandardNewMacro(vtkSAVRVolumeRepresentation);

vtkSAVRVolumeRepresentation::vtkSAVRVolumeRepresentation()
{
  // The superclass uses only vtkVolumeMapper's interface on its mapper (and down-casts for the
  // mapper-specific settings), so replacing it here is all it takes.
  vtkNew<vtkSAVRVolumeMapper> mapper;
  this->Mapper = mapper;
  this->VolumeMapper = mapper.GetPointer();
  this->SetSAVRSettings(nullptr);
}

vtkSAVRVolumeRepresentation::~vtkSAVRVolumeRepresentation() = default;

int vtkSAVRVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  const int result = this->Superclass::ProcessViewRequest(request, inInfo, outInfo);
  if (request == vtkPVView::REQUEST_RENDER())
  {
    this->Settings->AttachRefinementDriver(this->GetView());
  }
  return result;
}

void vtkSAVRVolumeRepresentation::SetSAVRSettings(vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(this->Settings, settings, this->Mapper);
}

void vtkSAVRVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRVolumeMapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

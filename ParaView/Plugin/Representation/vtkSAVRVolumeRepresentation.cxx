#include "vtkSAVRVolumeRepresentation.h"

#include "vtkColorTransferFunction.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkVolumeProperty.h"

vtkStandardNewMacro(vtkSAVRVolumeRepresentation);

vtkSAVRVolumeRepresentation::vtkSAVRVolumeRepresentation()
{
  // The superclass uses only vtkVolumeMapper's interface on its mapper (and down-casts for the
  // mapper-specific settings), so replacing it here is all it takes.
  vtkNew<vtkSAVRVolumeMapper> mapper;
  this->VolumeMapper = mapper.GetPointer();
  vtkSAVRRepresentationSettings::Install(this->Settings, nullptr, mapper, this);
}

vtkSAVRVolumeRepresentation::~vtkSAVRVolumeRepresentation() = default;

int vtkSAVRVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  const int result = this->Superclass::ProcessViewRequest(request, inInfo, outInfo);
  this->Settings->ProcessViewRequest(request, this->GetView());
  return result;
}

void vtkSAVRVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  vtkSAVRRepresentationSettings::SetVectorMode(
    this->Settings->GetMapper(), this->Property, this->Property->GetRGBTransferFunction(0));
}

void vtkSAVRVolumeRepresentation::SetSAVRSettings(vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(
    this->Settings, settings, this->Settings->GetMapper(), this);
}

void vtkSAVRVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRSettings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
}

#include "vtkSAVRUnstructuredVolumeRepresentation.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVView.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"

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
  this->SetSAVRSettings(nullptr);
}

vtkSAVRUnstructuredVolumeRepresentation::~vtkSAVRUnstructuredVolumeRepresentation() = default;

int vtkSAVRUnstructuredVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  const int result = this->Superclass::ProcessViewRequest(request, inInfo, outInfo);
  if (request == vtkPVView::REQUEST_RENDER())
  {
    this->Settings->AttachRefinementDriver(this->GetView());
  }
  return result;
}

void vtkSAVRUnstructuredVolumeRepresentation::SetActiveVolumeMapper(const char*)
{
  // The stock SelectMapper property sets its default here at creation; keep SAVR.
}

void vtkSAVRUnstructuredVolumeRepresentation::SetSAVRSettings(
  vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(this->Settings, settings, this->Mapper);
}

void vtkSAVRUnstructuredVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRVolumeMapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

#include "vtkSAVRUnstructuredVolumeRepresentation.h"

#include "vtkAlgorithm.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
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
  this->AddVolumeMapper(MapperName, mapper);
  this->Superclass::SetActiveVolumeMapper(MapperName);
  vtkSAVRRepresentationSettings::Install(this->Settings, nullptr, mapper);
}

vtkSAVRUnstructuredVolumeRepresentation::~vtkSAVRUnstructuredVolumeRepresentation() = default;

int vtkSAVRUnstructuredVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  const int result = this->Superclass::ProcessViewRequest(request, inInfo, outInfo);
  this->Settings->ProcessViewRequest(request, this->GetView());
  return result;
}

int vtkSAVRUnstructuredVolumeRepresentation::FillInputPortInformation(
  int port, vtkInformation* info)
{
  this->Superclass::FillInputPortInformation(port, info);
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkStructuredGrid");
  return 1;
}

void vtkSAVRUnstructuredVolumeRepresentation::SetActiveVolumeMapper(const char*)
{
  // The stock SelectMapper property sets its default here at creation; keep SAVR.
}

void vtkSAVRUnstructuredVolumeRepresentation::SetSAVRSettings(
  vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(this->Settings, settings, this->Settings->GetMapper());
}

void vtkSAVRUnstructuredVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRSettings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
}

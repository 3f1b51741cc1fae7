#include "vtkSAVRUnstructuredVolumeRepresentation.h"

#include "vtkAlgorithm.h"
#include "vtkAppendFilter.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolumeProperty.h"
#include "vtkVolumeRepresentationPreprocessor.h"

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
  vtkSAVRRepresentationSettings::Install(this->Settings, nullptr, mapper, this);
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

int vtkSAVRUnstructuredVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    return 0;
  }
  // The preprocessor's output is what the view delivers, redistributes across ranks and hands the
  // mapper: put the input's own cells there in place of its tetrahedra. (A composite input keeps
  // the stock path, which picks one of its blocks; so does a separate opacity array, which the
  // preprocessing appends.)
  auto* delivered = vtkUnstructuredGrid::SafeDownCast(this->Preprocessor->GetOutputDataObject(0));
  vtkDataSet* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                        ? vtkDataSet::GetData(inputVector[0], 0)
                        : nullptr;
  if (delivered && input && !this->UseSeparateOpacityArray)
  {
    vtkNew<vtkAppendFilter> cells; // any data set as an unstructured grid of its own cells
    cells->AddInputData(input);
    cells->Update();
    delivered->ShallowCopy(cells->GetOutput());
    delivered->RemoveGhostCells();
  }
  // A grid of vertices is a point cloud, which fills the box its kernels reach beyond its points:
  // the view's bounds (and so its clipping range) must hold that box.
  vtkSAVRVolumeMapper* mapper = this->Settings->GetMapper();
  if (vtkPointSet* particles = vtkSAVRParticleSampler::Particles(delivered))
  {
    vtkSAVRParticleSampler::SupportBounds(particles, mapper->GetParticleRadius(),
      mapper->GetParticleRadiusArrayName(), mapper->GetParticleKernel(), this->DataBounds);
  }
  return 1;
}

void vtkSAVRUnstructuredVolumeRepresentation::UpdateMapperParameters()
{
  this->Superclass::UpdateMapperParameters();
  vtkSAVRRepresentationSettings::SetVectorMode(
    this->Settings->GetMapper(), this->Property, this->Property->GetRGBTransferFunction(0));
}

void vtkSAVRUnstructuredVolumeRepresentation::SetActiveVolumeMapper(const char*)
{
  // The stock SelectMapper property sets its default here at creation; keep SAVR.
}

void vtkSAVRUnstructuredVolumeRepresentation::SetParticleRadiusArray(const char* name)
{
  this->Settings->SetParticleRadiusArray(name);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetShade(bool shade)
{
  this->Property->SetShade(shade ? 1 : 0);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetAmbient(double value)
{
  this->Property->SetAmbient(value);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetDiffuse(double value)
{
  this->Property->SetDiffuse(value);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetSpecular(double value)
{
  this->Property->SetSpecular(value);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetSpecularPower(double value)
{
  this->Property->SetSpecularPower(value);
}

void vtkSAVRUnstructuredVolumeRepresentation::SetSAVRSettings(
  vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(
    this->Settings, settings, this->Settings->GetMapper(), this);
}

void vtkSAVRUnstructuredVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SAVRSettings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
}

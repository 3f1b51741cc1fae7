#include "vtkSAVRAMRVolumeRepresentation.h"

#include "vtkColorTransferFunction.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkPVRenderView.h"
#include "vtkPiecewiseFunction.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <cstring>

vtkStandardNewMacro(vtkSAVRAMRVolumeRepresentation);

vtkSAVRAMRVolumeRepresentation::vtkSAVRAMRVolumeRepresentation()
{
  this->Cache = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkMath::UninitializeBounds(this->DataBounds);
  this->Mapper = vtkSAVRVolumeMapper::New();
  this->Property = vtkVolumeProperty::New();
  this->Property->SetInterpolationTypeToLinear();
  this->Actor = vtkVolume::New();
  this->Actor->SetMapper(this->Mapper);
  this->Actor->SetProperty(this->Property);
  this->Actor->SetVisibility(this->GetVisibility() ? 1 : 0);
  vtkSAVRRepresentationSettings::Install(this->Settings, nullptr, this->Mapper, this);
}

vtkSAVRAMRVolumeRepresentation::~vtkSAVRAMRVolumeRepresentation()
{
  this->Actor->Delete();
  this->Property->Delete();
  this->Mapper->Delete();
}

int vtkSAVRAMRVolumeRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkOverlappingAMR");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkSAVRAMRVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A shallow copy of the hierarchy is what the view delivers: later pipeline updates do not
  // change what is being drawn until the next REQUEST_UPDATE hands a new one over.
  auto copy = vtkSmartPointer<vtkOverlappingAMR>::New();
  vtkMath::UninitializeBounds(this->DataBounds);
  this->DataSize = 0;
  if (inputVector[0]->GetNumberOfInformationObjects() == 1)
  {
    if (auto* input = vtkOverlappingAMR::GetData(inputVector[0], 0))
    {
      copy->ShallowCopy(input);
      if (copy->GetNumberOfLevels() > 0)
      {
        copy->GetBounds(this->DataBounds);
      }
      this->DataSize = copy->GetActualMemorySize();
    }
  }
  this->Cache = copy;
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

int vtkSAVRAMRVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    // The hierarchy itself is the piece the view delivers (no resampling).
    vtkPVView::SetPiece(inInfo, this, this->Cache, this->DataSize);
    vtkPVRenderView::SetGeometryBounds(inInfo, this, this->DataBounds, this->Actor->GetMatrix());
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // The delivered vtkOverlappingAMR (SetInputConnection does nothing when already connected).
    this->Mapper->SetInputConnection(vtkPVRenderView::GetPieceProducer(inInfo, this));
    this->UpdateMapperParameters();
    this->Settings->AttachRefinementDriver(this->GetView());
    auto* controller = vtkMultiProcessController::GetGlobalController();
    if (!this->WarnedParallel && controller && controller->GetNumberOfProcesses() > 1)
    {
      this->WarnedParallel = true;
      vtkWarningMacro(
        "SAVR Volume of AMR data supports one process only: with "
        << controller->GetNumberOfProcesses()
        << " ranks each rank draws its own blocks, and blocks of different ranks interleave "
           "in depth, so the composited image is not ordered correctly.");
    }
  }
  return 1;
}

void vtkSAVRAMRVolumeRepresentation::UpdateMapperParameters()
{
  // The colored array (ColorArrayName: SetInputArrayToProcess(0, ...)) picks the scalars.
  vtkInformation* info = this->GetInputArrayInformation(0);
  const char* name = (info && info->Has(vtkDataObject::FIELD_NAME()))
                       ? info->Get(vtkDataObject::FIELD_NAME())
                       : nullptr;
  const int association = (info && info->Has(vtkDataObject::FIELD_ASSOCIATION()))
                            ? info->Get(vtkDataObject::FIELD_ASSOCIATION())
                            : vtkDataObject::FIELD_ASSOCIATION_POINTS;
  const bool haveArray = name && *name;
  if (haveArray)
  {
    this->Mapper->SelectScalarArray(name);
    if (association == vtkDataObject::FIELD_ASSOCIATION_CELLS)
    {
      this->Mapper->SetScalarModeToUseCellFieldData();
    }
    else
    {
      this->Mapper->SetScalarModeToUsePointFieldData();
    }
  }
  // Without a colored array (Solid Color) there is nothing to draw.
  this->Actor->SetVisibility(this->GetVisibility() && haveArray ? 1 : 0);
}

bool vtkSAVRAMRVolumeRepresentation::AddToView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->AddPropToRenderer(this->Actor);
    return this->Superclass::AddToView(view);
  }
  return false;
}

bool vtkSAVRAMRVolumeRepresentation::RemoveFromView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->RemovePropFromRenderer(this->Actor);
    this->Settings->AttachRefinementDriver(nullptr);
    return this->Superclass::RemoveFromView(view);
  }
  return false;
}

void vtkSAVRAMRVolumeRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Actor->SetVisibility(visible ? 1 : 0);
}

void vtkSAVRAMRVolumeRepresentation::SetPosition(double x, double y, double z)
{
  this->Actor->SetPosition(x, y, z);
}

void vtkSAVRAMRVolumeRepresentation::SetScale(double x, double y, double z)
{
  this->Actor->SetScale(x, y, z);
}

void vtkSAVRAMRVolumeRepresentation::SetOrientation(double x, double y, double z)
{
  this->Actor->SetOrientation(x, y, z);
}

void vtkSAVRAMRVolumeRepresentation::SetOrigin(double x, double y, double z)
{
  this->Actor->SetOrigin(x, y, z);
}

void vtkSAVRAMRVolumeRepresentation::SetPickable(int pickable)
{
  this->Actor->SetPickable(pickable);
}

void vtkSAVRAMRVolumeRepresentation::SetColor(vtkColorTransferFunction* lut)
{
  this->Property->SetColor(lut);
}

void vtkSAVRAMRVolumeRepresentation::SetScalarOpacity(vtkPiecewiseFunction* pwf)
{
  this->Property->SetScalarOpacity(pwf);
}

void vtkSAVRAMRVolumeRepresentation::SetScalarOpacityUnitDistance(double distance)
{
  this->Property->SetScalarOpacityUnitDistance(distance);
}

void vtkSAVRAMRVolumeRepresentation::SetInterpolationType(int type)
{
  // Nearest (0) or linear (anything else: ParaView's volumes offer cubic too).
  this->Property->SetInterpolationType(
    type == 0 ? VTK_NEAREST_INTERPOLATION : VTK_LINEAR_INTERPOLATION);
}

void vtkSAVRAMRVolumeRepresentation::SetAmbient(double value)
{
  this->Property->SetAmbient(value);
}

void vtkSAVRAMRVolumeRepresentation::SetDiffuse(double value)
{
  this->Property->SetDiffuse(value);
}

void vtkSAVRAMRVolumeRepresentation::SetSpecular(double value)
{
  this->Property->SetSpecular(value);
}

void vtkSAVRAMRVolumeRepresentation::SetSpecularPower(double value)
{
  this->Property->SetSpecularPower(value);
}

void vtkSAVRAMRVolumeRepresentation::SetShade(bool shade)
{
  this->Property->SetShade(shade ? 1 : 0);
}

void vtkSAVRAMRVolumeRepresentation::SetSAVRSettings(vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(
    this->Settings, settings, this->Settings->GetMapper(), this);
}

void vtkSAVRAMRVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DataSize: " << this->DataSize << " KiB\n";
  os << indent << "SAVRVolumeMapper:\n";
  this->Mapper->PrintSelf(os, indent.GetNextIndent());
}

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
#include "vtkSAVRAMRDistribution.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cstring>
#include <string>

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
  // Hidden until the first render connects the delivered hierarchy: the view asks visible
  // volumes for their bounds before that, and a mapper without input reports an error.
  this->Actor->SetVisibility(0);
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
  this->Distributed = false;
  this->DrawsNothing = false;
  auto* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                  ? vtkOverlappingAMR::GetData(inputVector[0], 0)
                  : nullptr;
  if (input)
  {
    copy->ShallowCopy(input);
    if (copy->GetNumberOfLevels() > 0)
    {
      copy->GetBounds(this->DataBounds);
    }
  }
  // On several ranks (every rank runs this, the call is collective): each rank gets the blocks
  // its region of the domain needs from the others.
  auto* controller = vtkMultiProcessController::GetGlobalController();
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    vtkSAVRAMRDistribution::Result spread;
    std::string error;
    // Blend modes that do not composite front to back are drawn by the first rank alone.
    this->Gathered = this->Mapper->GetBlendMode() != vtkVolumeMapper::COMPOSITE_BLEND;
    if (vtkSAVRAMRDistribution::Distribute(copy, controller, this->Gathered, spread, error))
    {
      copy = spread.Hierarchy;
      std::copy(spread.Region.begin(), spread.Region.end(), this->Region);
      this->Distributed = true;
      this->DrawsNothing = spread.Empty;
    }
    else
    {
      vtkErrorMacro(
        "SAVR Volume of AMR data on " << controller->GetNumberOfProcesses() << " ranks: " << error);
    }
  }
  this->DataSize = input ? copy->GetActualMemorySize() : 0;
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
    // On several ranks, each rank's own region (the whole domain on the first rank and an empty
    // box on the others while gathered), whose union is the data's box; composited in their
    // order even while gathered.
    vtkSAVRRepresentationSettings::DeclareVolumeInPlace(inInfo, outInfo, this,
      this->Distributed ? this->Region : nullptr, this->DataBounds, this->Actor->GetMatrix());
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // The delivered vtkOverlappingAMR (SetInputConnection does nothing when already connected).
    this->Mapper->SetInputConnection(vtkPVRenderView::GetPieceProducer(inInfo, this));
    this->UpdateMapperParameters();
    this->Settings->ProcessViewRequest(request, this->GetView());
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
  vtkSAVRRepresentationSettings::SetVectorMode(
    this->Mapper, this->Property, this->Property->GetRGBTransferFunction(0));
  // On several ranks this rank samples its region only (its blocks reach a cell beyond it).
  this->Mapper->SetCropping(this->Distributed && !this->Gathered ? 1 : 0);
  if (this->Distributed && !this->Gathered)
  {
    this->Mapper->SetCroppingRegionPlanes(this->Region);
    this->Mapper->SetCroppingRegionFlagsToSubVolume();
  }
  // Without a colored array (Solid Color) there is nothing to draw.
  this->Actor->SetVisibility(this->GetVisibility() && haveArray && !this->DrawsNothing ? 1 : 0);
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
    this->Settings->ForgetView();
    return this->Superclass::RemoveFromView(view);
  }
  return false;
}

void vtkSAVRAMRVolumeRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Actor->SetVisibility(
    visible && !this->DrawsNothing && this->Mapper->GetNumberOfInputConnections(0) > 0 ? 1 : 0);
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

void vtkSAVRAMRVolumeRepresentation::SetBlendMode(int mode)
{
  if (mode != this->Mapper->GetBlendMode())
  {
    this->Mapper->SetBlendMode(mode);
    // On several ranks the blocks go elsewhere when the mode starts or stops compositing.
    this->MarkModified();
  }
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

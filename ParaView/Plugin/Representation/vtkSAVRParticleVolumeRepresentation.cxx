#include "vtkSAVRParticleVolumeRepresentation.h"

#include "vtkAlgorithm.h"
#include "vtkAppendPolyData.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODVolume.h"
#include "vtkPVRenderView.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkRenderer.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkSAVRRepresentationSettings.h"
#include "vtkSAVRVolumeMapper.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkSAVRParticleVolumeRepresentation);

namespace
{
// Each particle's 1, added to the delivered points: what Solid Color draws with Particle
// Normalized off (their density). ParaView renders a volume only when its mapper finds scalars.
constexpr const char* kDensityArray = "SAVR particle density";
// Solid Color's attenuation per unit distance at the bound on the density, and the points of
// its opacity function.
constexpr double kDensityAttenuation = 6.0;
constexpr int kDensityOpacityPoints = 32;

// The points and their point data, without cells: all the mapper reads, and all a gather sends.
vtkSmartPointer<vtkPolyData> PointsOf(vtkPolyData* input)
{
  auto points = vtkSmartPointer<vtkPolyData>::New();
  if (input && input->GetPoints())
  {
    points->SetPoints(input->GetPoints());
    points->GetPointData()->ShallowCopy(input->GetPointData());
  }
  return points;
}

// Every rank's points on rank 0 (collective); the other ranks get an empty cloud.
vtkSmartPointer<vtkPolyData> Gather(vtkPolyData* local, vtkMultiProcessController* controller)
{
  std::vector<vtkSmartPointer<vtkDataObject>> pieces;
  controller->Gather(local, pieces, 0);
  if (controller->GetLocalProcessId() != 0)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  vtkNew<vtkAppendPolyData> append;
  for (const auto& piece : pieces)
  {
    auto* cloud = vtkPolyData::SafeDownCast(piece);
    if (cloud && cloud->GetNumberOfPoints() > 0)
    {
      append->AddInputData(cloud);
    }
  }
  if (append->GetNumberOfInputConnections(0) == 0)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  append->Update();
  return PointsOf(append->GetOutput());
}
} // namespace

vtkSAVRParticleVolumeRepresentation::vtkSAVRParticleVolumeRepresentation()
{
  this->Cache = vtkSmartPointer<vtkPolyData>::New();
  this->Mapper = vtkSmartPointer<vtkSAVRVolumeMapper>::New();
  this->Property->SetInterpolationTypeToLinear();
  this->DensityColor = vtkSmartPointer<vtkColorTransferFunction>::New();
  this->DensityOpacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  vtkMath::UninitializeBounds(this->Region);
  // Connected to the mapper at the first render, once the delivered points exist: the view asks
  // visible volumes for their bounds before that, and a mapper without input reports an error.
  this->Actor->SetVisibility(0);
  vtkSAVRRepresentationSettings::Install(this->Settings, nullptr, this->Mapper, this);
}

vtkSAVRParticleVolumeRepresentation::~vtkSAVRParticleVolumeRepresentation() = default;

int vtkSAVRParticleVolumeRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkSAVRParticleVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A copy of the points is what the view delivers: later pipeline updates do not change what
  // is drawn until the next REQUEST_UPDATE hands a new one over.
  auto* input = inputVector[0]->GetNumberOfInformationObjects() == 1
                  ? vtkPolyData::GetData(inputVector[0], 0)
                  : nullptr;
  vtkSmartPointer<vtkPolyData> cloud = PointsOf(input);
  this->Gathered = false;
  this->DrawsNothing = false;
  // On several ranks (every rank runs this: the gather is collective) the first rank draws
  // every point: a kernel reaches across any split of the domain.
  auto* controller = vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  if (ranks > 1)
  {
    cloud = Gather(cloud, controller);
    this->Gathered = true;
    this->DrawsNothing = controller->GetLocalProcessId() != 0;
  }
  vtkNew<vtkUnsignedCharArray> ones;
  ones->SetName(kDensityArray);
  ones->SetNumberOfTuples(cloud->GetNumberOfPoints());
  ones->FillValue(1);
  cloud->GetPointData()->AddArray(ones);
  this->Cache = cloud;
  vtkSAVRParticleSampler::SupportBounds(cloud, this->Mapper->GetParticleRadius(),
    this->Mapper->GetParticleRadiusArrayName(), this->Mapper->GetParticleKernel(),
    this->DataBounds);
  if (this->Gathered)
  {
    this->ShareBounds();
  }
  this->DataSize = cloud->GetActualMemorySize();
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

void vtkSAVRParticleVolumeRepresentation::ShareBounds()
{
  auto* controller = vtkMultiProcessController::GetGlobalController();
  double box[7] = { 0.0 };
  const bool valid = vtkMath::AreBoundsInitialized(this->DataBounds);
  std::copy(this->DataBounds, this->DataBounds + 6, box);
  box[6] = valid ? 1.0 : 0.0;
  controller->Broadcast(box, 7, 0);
  if (box[6] == 0.0)
  {
    vtkMath::UninitializeBounds(this->DataBounds);
    vtkMath::UninitializeBounds(this->Region);
    return;
  }
  std::copy(box, box + 6, this->DataBounds);
  // The first rank's region is the cloud's reach; the others' are empty boxes at its corner.
  for (int a = 0; a < 3; ++a)
  {
    this->Region[2 * a] = box[2 * a];
    this->Region[2 * a + 1] = this->DrawsNothing ? box[2 * a] : box[2 * a + 1];
  }
}

int vtkSAVRParticleVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request, inInfo, outInfo))
  {
    return 0;
  }
  if (request == vtkPVView::REQUEST_UPDATE())
  {
    vtkPVView::SetPiece(inInfo, this, this->Cache, this->DataSize);
    // While gathered each rank declares its own region (the cloud's on the first rank, an empty
    // box on the others), composited in that order.
    const bool regions = this->Gathered && vtkMath::AreBoundsInitialized(this->Region);
    vtkSAVRRepresentationSettings::DeclareVolumeInPlace(inInfo, outInfo, this,
      regions ? this->Region : nullptr, this->DataBounds, this->Actor->GetMatrix());
  }
  else if (request == vtkPVView::REQUEST_RENDER())
  {
    // The delivered points (SetInputConnection does nothing when already connected).
    this->Mapper->SetInputConnection(vtkPVRenderView::GetPieceProducer(inInfo, this));
    this->UpdateMapperParameters();
  }
  this->Settings->ProcessViewRequest(request, this->GetView());
  return 1;
}

void vtkSAVRParticleVolumeRepresentation::UpdateMapperParameters()
{
  // The colored array (ColorArrayName: SetInputArrayToProcess(0, ...)) is the particles' value.
  vtkInformation* info = this->GetInputArrayInformation(0);
  const char* name = (info && info->Has(vtkDataObject::FIELD_NAME()))
                       ? info->Get(vtkDataObject::FIELD_NAME())
                       : nullptr;
  const bool haveArray = name && *name;
  // Without a colored array (Solid Color): the particles' density (summed kernels of 1), whatever
  // ParticleNormalized says (a mean of no values says nothing); with one, the normalization set.
  const bool density = !haveArray;
  this->Mapper->SetParticleNormalized(!density && this->Settings->GetParticleNormalized());
  if (haveArray || density)
  {
    this->Mapper->SelectScalarArray(haveArray ? name : kDensityArray);
    this->Mapper->SetScalarModeToUsePointFieldData();
  }
  if (density)
  {
    this->UpdateDensityFunctions();
    this->Property->SetColor(this->DensityColor);
    this->Property->SetScalarOpacity(this->DensityOpacity);
  }
  else
  {
    this->Property->SetColor(this->LookupTable);
    this->Property->SetScalarOpacity(this->OpacityFunction);
  }
  vtkSAVRRepresentationSettings::SetVectorMode(
    this->Mapper, this->Property, this->Property->GetRGBTransferFunction(0));
  this->Actor->SetMapper(this->Mapper);
  this->Actor->SetVisibility(
    this->GetVisibility() && (haveArray || density) && !this->DrawsNothing ? 1 : 0);
}

void vtkSAVRParticleVolumeRepresentation::UpdateDensityFunctions()
{
  // (Changed only when they change: a changed function re-blends the samples.)
  double rgb[3] = { -1.0, -1.0, -1.0 };
  if (this->DensityColor->GetSize() == 1)
  {
    this->DensityColor->GetColor(0.0, rgb);
  }
  if (!std::equal(rgb, rgb + 3, this->DensityRGB))
  {
    this->DensityColor->RemoveAllPoints();
    this->DensityColor->AddRGBPoint(
      0.0, this->DensityRGB[0], this->DensityRGB[1], this->DensityRGB[2]);
  }
  auto* cloud = vtkPolyData::SafeDownCast(this->Mapper->GetInputDataObject(0, 0));
  if (!cloud || cloud->GetNumberOfPoints() == 0)
  {
    return;
  }
  const char* radii = this->Mapper->GetParticleRadiusArrayName();
  std::ostringstream key;
  key << cloud << ' ' << cloud->GetMTime() << ' ' << this->Mapper->GetParticleRadius() << ' '
      << this->Mapper->GetParticleKernel() << ' ' << (radii ? radii : "");
  if (key.str() == this->DensityKey)
  {
    return;
  }
  this->DensityKey = key.str();
  // An attenuation in proportion to the density, as a cloud of that density attenuates light:
  // opacity 1 - exp(-k density) per unit distance. k is set from the mapper's own bound on the
  // summed field (the sampler it will build; 2 to 3.3 times the largest density sampled), so
  // that the densest places attenuate by about e^-2 per unit distance.
  vtkNew<vtkSAVRParticleSampler> sampler;
  double bound = 1.0;
  if (sampler->Build(cloud, cloud->GetPointData()->GetArray(kDensityArray),
        this->Mapper->GetParticleRadius(), radii, this->Mapper->GetParticleKernel(), false,
        nullptr))
  {
    double range[2];
    sampler->GetFieldRange(range);
    if (std::isfinite(range[1]) && range[1] > 0.0)
    {
      bound = range[1];
    }
  }
  this->DensityOpacity->RemoveAllPoints();
  for (int i = 0; i <= kDensityOpacityPoints; ++i)
  {
    const double density = bound * i / kDensityOpacityPoints;
    this->DensityOpacity->AddPoint(density, -std::expm1(-kDensityAttenuation * density / bound));
  }
}

void vtkSAVRParticleVolumeRepresentation::SetLookupTable(vtkColorTransferFunction* lut)
{
  this->LookupTable = lut;
}

void vtkSAVRParticleVolumeRepresentation::SetScalarOpacityFunction(vtkPiecewiseFunction* function)
{
  this->OpacityFunction = function;
}

void vtkSAVRParticleVolumeRepresentation::SetDensityColor(double r, double g, double b)
{
  this->DensityRGB[0] = r;
  this->DensityRGB[1] = g;
  this->DensityRGB[2] = b;
}

bool vtkSAVRParticleVolumeRepresentation::AddToView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->AddActor(this->Actor);
    return this->Superclass::AddToView(view);
  }
  return false;
}

bool vtkSAVRParticleVolumeRepresentation::RemoveFromView(vtkView* view)
{
  if (auto* renderView = vtkPVRenderView::SafeDownCast(view))
  {
    renderView->GetRenderer()->RemoveActor(this->Actor);
    this->Settings->ForgetView();
    return this->Superclass::RemoveFromView(view);
  }
  return false;
}

void vtkSAVRParticleVolumeRepresentation::SetVisibility(bool visible)
{
  this->Superclass::SetVisibility(visible);
  this->Actor->SetVisibility(
    visible && !this->DrawsNothing && this->Mapper->GetNumberOfInputConnections(0) > 0 ? 1 : 0);
}

void vtkSAVRParticleVolumeRepresentation::SetAmbient(double value)
{
  this->Property->SetAmbient(value);
}

void vtkSAVRParticleVolumeRepresentation::SetDiffuse(double value)
{
  this->Property->SetDiffuse(value);
}

void vtkSAVRParticleVolumeRepresentation::SetSpecular(double value)
{
  this->Property->SetSpecular(value);
}

void vtkSAVRParticleVolumeRepresentation::SetSpecularPower(double value)
{
  this->Property->SetSpecularPower(value);
}

void vtkSAVRParticleVolumeRepresentation::SetShade(bool shade)
{
  this->Property->SetShade(shade ? 1 : 0);
}

void vtkSAVRParticleVolumeRepresentation::SetBlendMode(int mode)
{
  this->Mapper->SetBlendMode(mode);
}

void vtkSAVRParticleVolumeRepresentation::SetParticleRadiusArray(const char* name)
{
  this->Settings->SetParticleRadiusArray(name);
}

void vtkSAVRParticleVolumeRepresentation::SetSAVRSettings(vtkSAVRRepresentationSettings* settings)
{
  vtkSAVRRepresentationSettings::Install(
    this->Settings, settings, this->Settings->GetMapper(), this);
}

void vtkSAVRParticleVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Gathered: " << this->Gathered << "\n";
  os << indent << "SAVRSettings:\n";
  this->Settings->PrintSelf(os, indent.GetNextIndent());
}

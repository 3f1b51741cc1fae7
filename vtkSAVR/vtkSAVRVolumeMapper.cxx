#include "vtkSAVRVolumeMapper.h"

#include "ComponentSampler.h"
#include "CroppingSampler.h"
#include "FrameLoop.h"
#include "ShadingTable.h"
#include "TransferFunctionTable.h"
#include "vtkSAVRAMRSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRImageSampler.h"
#include "vtkSAVRUnstructuredSampler.h"

#include "vtkAlgorithm.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPropCollection.h"
#include "vtkRayCastImageDisplayHelper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkSAVRVolumeMapper);

namespace
{
// Rays longer than this many base steps are refused: the frame would take unbounded time.
constexpr double kMaxStepsPerRay = double(1 << 22);

void AppendMatrix(std::vector<double>& key, vtkMatrix4x4* m)
{
  for (int i = 0; i < 16; ++i)
  {
    key.push_back(m ? m->GetElement(i / 4, i % 4) : (i % 5 == 0 ? 1.0 : 0.0));
  }
}

// Whether the renderer's depth buffer may hold anything but its clear value when its volumes
// render: opaque geometry of its own props, a depth buffer kept from an earlier renderer, or a
// render pass (ParaView's among them) that may fill it its own way. When not, there is no need
// to read it back.
bool DepthMayHoldGeometry(vtkRenderer* ren)
{
  if (ren->GetPass() || ren->GetPreserveDepthBuffer() || !ren->GetErase() ||
      !ren->GetRenderWindow()->GetErase())
  {
    return true;
  }
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    // Volumes drawn by this mapper test against depth but do not write it; of others (a GPU
    // mapper, say) this is not known.
    vtkVolume* volume = vtkVolume::SafeDownCast(prop);
    const bool savrVolume = volume && vtkSAVRVolumeMapper::SafeDownCast(volume->GetMapper());
    if (prop->GetVisibility() && !savrVolume)
    {
      return true;
    }
  }
  return false;
}

template <typename T>
bool NearlyEqual(const std::vector<T>& a, const std::vector<T>& b, double tolerance)
{
  if (a.size() != b.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (!(std::abs(a[i] - b[i]) <= tolerance))
    {
      return false;
    }
  }
  return true;
}

// Several components. Independent: each through its own functions, with extinctions s_c
// (-log(1 - opacity) per the component's ScalarOpacityUnitDistance, times its ComponentWeight)
// combined as VTK's fixed-point mapper combines them per sample, in the limit of a fine step:
// emission adds (the sum of s_c times the component's colour) and absorption is the
// extinctions' own weighted mean (the sum of s_c^2 over the sum of s_c). The combined colour,
// emission over absorption, is not clamped to 1: the fixed-point mapper clamps only each step's
// summed emission, which a fine step never reaches. Dependent: two components are luminance (the
// first's colour function) and alpha (the first's opacity function at the second); four are RGBA,
// the colour the first three normalized as a texture would be (integers over their type's maximum,
// floating point as is), the opacity the first's opacity function at the fourth.
struct ComponentTables
{
  // Per component, at each of its 8-bit levels: the value, extinction per world unit, colour.
  std::vector<double> Value[4];
  std::vector<double> Sigma[4];
  std::vector<double> RGB[4];
};

ComponentTables TabulateComponents(
  vtkVolumeProperty* property, const savr::ComponentSampler& sampler, double colorScale)
{
  ComponentTables t;
  const bool independent = property->GetIndependentComponents() != 0;
  const int n = sampler.NumberOfComponents();
  for (int c = 0; c < n; ++c)
  {
    // Components are quantized as the first or the second of a pair.
    const int levels =
      c % 2 == 0 ? savr::ComponentSampler::kFirstLevels : savr::ComponentSampler::kSecondLevels;
    const std::array<double, 2> range = sampler.Range(c);
    t.Value[c].resize(levels);
    t.Sigma[c].assign(levels, 0.0);
    t.RGB[c].assign(3 * levels, 0.0);
    for (int q = 0; q < levels; ++q)
    {
      t.Value[c][q] = range[0] + (range[1] - range[0]) * q / (levels - 1.0);
    }
    // Which functions apply to this component, if any.
    const bool opaque = independent || c == n - 1;
    const int function = independent ? c : 0;
    const double unit = std::max(property->GetScalarOpacityUnitDistance(function), 1e-300);
    const double weight = independent ? property->GetComponentWeight(c) : 1.0;
    for (int q = 0; q < levels; ++q)
    {
      const double v = t.Value[c][q];
      double* rgb = &t.RGB[c][3 * q];
      if (independent || (n == 2 && c == 0))
      {
        if (property->GetColorChannels(function) == 1)
        {
          rgb[0] = rgb[1] = rgb[2] = property->GetGrayTransferFunction(function)->GetValue(v);
        }
        else
        {
          property->GetRGBTransferFunction(function)->GetColor(v, rgb);
        }
      }
      else if (n == 4 && c < 3)
      {
        rgb[c] = std::min(std::max(v * colorScale, 0.0), 1.0);
      }
      if (opaque)
      {
        const double a =
          std::min(std::max(property->GetScalarOpacity(function)->GetValue(v), 0.0), 1.0);
        // Opacity 1 is opaque: a large finite extinction keeps the sums finite.
        t.Sigma[c][q] = weight * (a < 1.0 ? -std::log1p(-a) : 745.0) / unit;
      }
    }
  }
  return t;
}

// The terms (sum of extinctions, sum of their squares, colour term: 5 per code) of every packed
// code of components `first` and `first` + 1, for TransferFunctionTable::SetComponentTerms.
std::vector<double> PairTerms(const ComponentTables& t, int first, int n, bool independent)
{
  const std::uint32_t codes = savr::ComponentSampler::kPairCodes;
  std::vector<double> terms(5 * static_cast<std::size_t>(codes), 0.0);
  for (std::uint32_t k = 0; k < codes; ++k)
  {
    const int q[2] = { static_cast<int>(k % savr::ComponentSampler::kFirstLevels),
      static_cast<int>(k / savr::ComponentSampler::kFirstLevels) };
    double* out = &terms[5 * static_cast<std::size_t>(k)];
    for (int i = 0; i < 2 && first + i < n; ++i)
    {
      const int c = first + i;
      const double sigma = t.Sigma[c][q[i]];
      const double* rgb = &t.RGB[c][3 * q[i]];
      out[0] += sigma;
      out[1] += sigma * sigma;
      for (int j = 0; j < 3; ++j)
      {
        out[2 + j] += independent ? sigma * rgb[j] : rgb[j];
      }
    }
  }
  return terms;
}

// The colour and opacity (per the first component's ScalarOpacityUnitDistance) of every code of
// the first pair, as the pair alone would have them: the whole answer for two components.
void PairTable(vtkVolumeProperty* property, const ComponentTables& t,
  const std::vector<double>& terms, const savr::SampleEncoding& encoding, std::vector<double>& rgb,
  std::vector<double>& opacity)
{
  const bool independent = property->GetIndependentComponents() != 0;
  const double unit = property->GetScalarOpacityUnitDistance(0);
  for (std::uint32_t k = 0; k < encoding.Levels; ++k)
  {
    double* out = rgb.data() + 3 * k;
    if (k >= savr::ComponentSampler::kPairCodes)
    {
      // Codes no pair packs to.
      std::fill_n(out, 3, 0.0);
      opacity[k] = 0.0;
      continue;
    }
    const int q[2] = { static_cast<int>(k % savr::ComponentSampler::kFirstLevels),
      static_cast<int>(k / savr::ComponentSampler::kFirstLevels) };
    if (!independent)
    {
      // Luminance and alpha: the second component's extinction, the first's colour.
      std::copy_n(&t.RGB[0][3 * q[0]], 3, out);
      opacity[k] = -std::expm1(-t.Sigma[1][q[1]] * unit);
      continue;
    }
    const double* term = &terms[5 * static_cast<std::size_t>(k)];
    const double absorption = term[0] > 0.0 ? term[1] / term[0] : 0.0;
    for (int i = 0; i < 3; ++i)
    {
      out[i] = absorption > 0.0 ? term[2 + i] / absorption : 0.0;
    }
    opacity[k] = -std::expm1(-absorption * unit);
  }
}

bool ToBlendMode(int vtkMode, savr::BlendMode& mode)
{
  switch (vtkMode)
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      mode = savr::BlendMode::Composite;
      return true;
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      mode = savr::BlendMode::Maximum;
      return true;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      mode = savr::BlendMode::Minimum;
      return true;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      mode = savr::BlendMode::Average;
      return true;
    case vtkVolumeMapper::ADDITIVE_BLEND:
      mode = savr::BlendMode::Additive;
      return true;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      mode = savr::BlendMode::Isosurface;
      return true;
    default:
      return false;
  }
}
} // namespace

struct vtkSAVRVolumeMapper::Internals
{
  savr::FrameLoop Loop;
  savr::TransferFunctionTable Table;
  savr::ShadingTable Shading;
  std::vector<double> ShadingKey;
  savr::GradientOpacityTable GradientOpacity;
  std::vector<double> GradientOpacityKey;
  savr::IsoSurfaces Isos;
  std::vector<double> IsoKey;
  vtkNew<vtkSAVRImageSampler> ImageSampler;
  vtkNew<vtkSAVRAMRSampler> AMRSampler;
  vtkNew<vtkSAVRUnstructuredSampler> UnstructuredSampler;
  std::shared_ptr<const savr::Sampler> DataSampler; // the input's, as built
  vtkSmartPointer<vtkRayCastImageDisplayHelper> Display;
  std::vector<double> DataKey;
  std::vector<double> CroppingKey;
  std::shared_ptr<const savr::Sampler> Sampler; // the image's, cropped when cropping is on
  std::vector<double> SettingsKey;
  std::vector<double> ViewKey;
  std::vector<double> TableKey;
  std::vector<float> Depth;
  std::vector<unsigned char> Bytes;
  // The smallest rectangle of Bytes holding every pixel that is not fully transparent, with
  // each pixel doubled in x and y, for display; its origin and size in (undoubled) pixels.
  std::vector<unsigned char> Doubled;
  int Shown[4] = { 0, 0, 0, 0 };
  std::string LastError;
  double Step = 0.0;
  double SmallestSpacing = 0.0; // the finest cell edge, in world units
  double DefaultStep = 0.0;     // SampleDistance's default
  bool HaveImage = false;
  // Nothing can be drawn (bad input, empty viewport): further frames would add nothing.
  bool NothingToRefine = false;
  std::vector<double> FailedDataKey; // input that failed to build, not to be rescanned

  // Every frame is taken, or the error estimate is below the tolerance, and the image shown is
  // their blend (not an interacting pass).
  bool Refined(double tolerance) const
  {
    const double estimate = this->Loop.ErrorEstimate();
    return (this->Loop.Complete() || (tolerance > 0.0 && estimate >= 0.0 && estimate < tolerance));
  }

  void ClearImage()
  {
    this->Loop.Reset(savr::View(), nullptr, savr::FrameSettings());
    this->SettingsKey.clear();
    this->ViewKey.clear();
    this->HaveImage = false;
  }
};

vtkSAVRVolumeMapper::vtkSAVRVolumeMapper()
  : State(new Internals)
{
  this->State->Display =
    vtkSmartPointer<vtkRayCastImageDisplayHelper>::Take(vtkRayCastImageDisplayHelper::New());
  if (this->State->Display)
  {
    this->State->Display->SetPreMultipliedColors(1);
  }
}

vtkSAVRVolumeMapper::~vtkSAVRVolumeMapper() = default;

int vtkSAVRVolumeMapper::GetNumberOfFramesAccumulated() const
{
  return this->State->Loop.FrameLimit() > 0 ? this->State->Loop.Frames() : 0;
}

int vtkSAVRVolumeMapper::GetFrameLimit() const
{
  return this->State->Loop.FrameLimit();
}

bool vtkSAVRVolumeMapper::GetRefinementComplete() const
{
  const Internals& s = *this->State;
  if (s.NothingToRefine)
  {
    return true;
  }
  return s.HaveImage && !this->Interactive && s.Loop.CurrentPhase() != savr::Phase::Interacting &&
         s.Refined(this->ErrorTolerance);
}

double vtkSAVRVolumeMapper::GetErrorEstimate() const
{
  return this->State->Loop.ErrorEstimate();
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetMemoryInUse() const
{
  return this->State->Loop.MemoryInUse();
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetNumberOfSamplesTaken() const
{
  return static_cast<vtkTypeUInt64>(this->State->Loop.SamplesTaken());
}

vtkTypeUInt64 vtkSAVRVolumeMapper::GetNumberOfStoredSamples() const
{
  return static_cast<vtkTypeUInt64>(this->State->Loop.SamplesPerFrame()) *
         this->GetNumberOfFramesAccumulated();
}

double vtkSAVRVolumeMapper::GetEffectiveSampleDistance() const
{
  return this->State->Step;
}

void vtkSAVRVolumeMapper::SetInputData(vtkOverlappingAMR* amr)
{
  this->SetInputDataInternal(0, amr);
}

int vtkSAVRVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
  {
    return 0;
  }
  info->Remove(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE());
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkOverlappingAMR");
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  return 1;
}

double* vtkSAVRVolumeMapper::GetBounds()
{
  if (vtkOverlappingAMR::SafeDownCast(this->GetInputDataObject(0, 0)))
  {
    vtkAlgorithm* producer = this->GetInputAlgorithm();
    if (producer)
    {
      producer->Update();
    }
    auto* amr = vtkOverlappingAMR::SafeDownCast(this->GetInputDataObject(0, 0));
    if (amr && amr->GetAMRInfo() && amr->GetNumberOfLevels() > 0)
    {
      amr->GetBounds(this->Bounds);
    }
    else
    {
      vtkMath::UninitializeBounds(this->Bounds); // an empty hierarchy (VTK would crash)
    }
    return this->Bounds;
  }
  return this->Superclass::GetBounds();
}

void vtkSAVRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->State->Display)
  {
    this->State->Display->ReleaseGraphicsResources(window);
  }
}

void vtkSAVRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  const auto start = std::chrono::steady_clock::now();
  Internals& s = *this->State;
  auto fail = [&](const std::string& message)
  {
    if (message != s.LastError)
    {
      vtkErrorMacro(<< message);
      s.LastError = message;
    }
    s.ClearImage();
    s.NothingToRefine = true;
    this->LastFrameTime =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  if (!ren || !vol || !ren->GetActiveCamera() || !ren->GetRenderWindow())
  {
    return;
  }
  if (this->GetNumberOfInputConnections(0) == 0 && !this->GetInput())
  {
    fail("no input: call SetInputData or SetInputConnection");
    return;
  }
  if (vtkAlgorithm* producer = this->GetInputAlgorithm())
  {
    producer->Update();
  }
  vtkDataObject* input = this->GetInputDataObject(0, 0);
  vtkImageData* image = vtkImageData::SafeDownCast(input);
  vtkOverlappingAMR* amr = vtkOverlappingAMR::SafeDownCast(input);
  vtkUnstructuredGrid* mesh = vtkUnstructuredGrid::SafeDownCast(input);
  if (!image && !amr && !mesh)
  {
    fail(std::string(
           "the input must be vtkImageData, vtkOverlappingAMR or vtkUnstructuredGrid, not ") +
         (input ? input->GetClassName() : "nothing"));
    return;
  }
  vtkVolumeProperty* property = vol->GetProperty();
  savr::BlendMode mode;
  if (!ToBlendMode(this->BlendMode, mode))
  {
    fail("blend mode " + std::to_string(this->BlendMode) + " is not supported");
    return;
  }
  if (mode == savr::BlendMode::Composite && this->PreIntegration)
  {
    mode = savr::BlendMode::PreIntegrated;
  }

  // Data: rebuild the sampler when the input, its scalars, the volume's placement or the
  // interpolation change.
  vtkMatrix4x4* volumeMatrix = vol->GetMatrix();
  std::vector<double> dataKey = { static_cast<double>(reinterpret_cast<std::uintptr_t>(input)),
    static_cast<double>(input->GetMTime()), static_cast<double>(property->GetInterpolationType()) };
  int cellFlag = 0;
  vtkDataArray* scalars = nullptr;
  if (image || mesh)
  {
    scalars = vtkAbstractMapper::GetScalars(vtkDataSet::SafeDownCast(input), this->ScalarMode,
      this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
    dataKey.insert(dataKey.end(),
      { static_cast<double>(reinterpret_cast<std::uintptr_t>(scalars)),
        scalars ? static_cast<double>(scalars->GetMTime()) : 0.0, static_cast<double>(cellFlag),
        static_cast<double>(property->GetIndependentComponents()) });
  }
  else
  {
    // Each block's array is chosen by these settings.
    dataKey.insert(dataKey.end(),
      { static_cast<double>(this->ScalarMode), static_cast<double>(this->ArrayAccessMode),
        static_cast<double>(this->ArrayId),
        static_cast<double>(std::hash<std::string>()(this->ArrayName ? this->ArrayName : "")) });
  }
  AppendMatrix(dataKey, volumeMatrix);
  if (dataKey == s.FailedDataKey)
  {
    fail(s.LastError); // the same input again: fail without rescanning it
    return;
  }
  if (dataKey != s.DataKey)
  {
    std::string error;
    if (image)
    {
      if (s.ImageSampler->Build(image, scalars, cellFlag == 1, volumeMatrix,
            property->GetInterpolationType(), property->GetIndependentComponents() != 0))
      {
        s.DataSampler = s.ImageSampler->GetSampler();
        // The smallest voxel edge, in world units, sets the default step.
        double smallest = VTK_DOUBLE_MAX;
        const double* spacing = image->GetSpacing();
        vtkMatrix3x3* direction = image->GetDirectionMatrix();
        for (int a = 0; a < 3; ++a)
        {
          double edge[4] = { 0, 0, 0, 0 };
          for (int r = 0; r < 3; ++r)
          {
            edge[r] = direction->GetElement(r, a) * spacing[a];
          }
          double world[4];
          vtkMatrix4x4* m = volumeMatrix;
          for (int r = 0; r < 4; ++r)
          {
            world[r] = m->GetElement(r, 0) * edge[0] + m->GetElement(r, 1) * edge[1] +
                       m->GetElement(r, 2) * edge[2];
          }
          smallest = std::min(
            smallest, std::sqrt(world[0] * world[0] + world[1] * world[1] + world[2] * world[2]));
        }
        s.SmallestSpacing = smallest;
        s.DefaultStep = smallest;
      }
      else
      {
        error = s.ImageSampler->GetErrorMessage();
      }
    }
    else if (mesh)
    {
      if (s.UnstructuredSampler->Build(mesh, scalars, cellFlag == 1, volumeMatrix))
      {
        s.DataSampler = s.UnstructuredSampler->GetSampler();
        s.SmallestSpacing = s.UnstructuredSampler->GetTypicalCellSize();
        s.DefaultStep = s.SmallestSpacing;
        if (s.UnstructuredSampler->GetNumberOfSkippedCells() > 0)
        {
          vtkErrorMacro(<< s.UnstructuredSampler->GetNumberOfSkippedCells()
                        << " cells are left out: only tetrahedra, hexahedra, voxels, wedges and "
                           "pyramids with finite points are rendered");
        }
      }
      else
      {
        error = s.UnstructuredSampler->GetErrorMessage();
      }
    }
    else if (s.AMRSampler->Build(amr, this->ScalarMode, this->ArrayAccessMode, this->ArrayId,
               this->ArrayName, volumeMatrix, property->GetInterpolationType()))
    {
      // A frame samples at the coarsest level's spacing; refinement reaches the finest level's.
      s.DataSampler = s.AMRSampler->GetSampler();
      s.SmallestSpacing = s.AMRSampler->GetFinestSpacing();
      s.DefaultStep = s.AMRSampler->GetCoarsestSpacing();
    }
    else
    {
      error = s.AMRSampler->GetErrorMessage();
    }
    if (!error.empty())
    {
      fail("cannot render this input: " + error);
      s.FailedDataKey = dataKey;
      s.DataKey.clear();
      s.DataSampler.reset();
      return;
    }
    s.FailedDataKey.clear();
    s.DataKey = dataKey;
    s.CroppingKey.clear(); // wrap the new sampler
    s.ViewKey.clear();
    s.LastError.clear();
  }

  // Several components are composited only (their packed codes have no order for the other
  // modes).
  const int components = image ? s.ImageSampler->GetNumberOfComponents() : 1;
  const bool pair = components > 1;
  if (pair && (mode != savr::BlendMode::Composite || this->PreIntegration))
  {
    fail("multi-component scalars render with composite blending only (not with pre-integration, "
         "maximum, minimum, average, additive or isosurface blending)");
    return;
  }

  // Cropping wraps the image's sampler; changing it does not rescan the data.
  // Planes and flags matter only while cropping is on.
  std::vector<double> croppingKey = { static_cast<double>(this->Cropping) };
  if (this->Cropping)
  {
    croppingKey.push_back(static_cast<double>(this->CroppingRegionFlags));
    croppingKey.insert(
      croppingKey.end(), this->CroppingRegionPlanes, this->CroppingRegionPlanes + 6);
    AppendMatrix(croppingKey, volumeMatrix);
  }
  if (croppingKey != s.CroppingKey)
  {
    s.Sampler = s.DataSampler;
    if (this->Cropping)
    {
      s.Sampler = std::make_shared<savr::CroppingSampler>(s.Sampler,
        Eigen::Affine3d(vtkSAVRConversions::ToEigen(volumeMatrix)).inverse(),
        this->CroppingRegionPlanes, static_cast<std::uint32_t>(this->CroppingRegionFlags));
    }
    s.CroppingKey = croppingKey;
  }

  // Sampling settings.
  const double step = this->SampleDistance > 0.0 ? this->SampleDistance : s.DefaultStep;
  int frames = this->MaximumNumberOfFrames;
  if (frames <= 0)
  {
    frames = 1;
    while (step / frames > 0.25 * s.SmallestSpacing && frames < (1 << 16))
    {
      frames *= 2;
    }
  }
  const double* bounds = vol->GetBounds();
  const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
                                    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
                                    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  if (!(step > 0.0) || !std::isfinite(step) || diagonal / step > kMaxStepsPerRay)
  {
    fail("the sample distance " + std::to_string(step) + " would take more than " +
         std::to_string(static_cast<long long>(kMaxStepsPerRay)) + " samples per ray");
    return;
  }
  s.Step = step;

  // View: rebuild the rays when anything that moves them changes.
  int width = 0;
  int height = 0;
  int x0 = 0;
  int y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  if (width <= 0 || height <= 0)
  {
    s.NothingToRefine = true;
    return;
  }
  s.NothingToRefine = false;
  vtkCamera* camera = ren->GetActiveCamera();
  vtkNew<vtkMatrix4x4> worldToNDC;
  worldToNDC->DeepCopy(
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1));
  savr::View view;
  view.Width = width;
  view.Height = height;
  view.NDCToWorld = vtkSAVRConversions::ToEigen(worldToNDC).inverse();
  if (!view.NDCToWorld.allFinite())
  {
    fail("the camera's projection cannot be inverted (is the view-up parallel to the view "
         "direction?)");
    return;
  }
  if (DepthMayHoldGeometry(ren))
  {
    view.Depth.resize(static_cast<std::size_t>(width) * height);
    ren->GetRenderWindow()->GetZbufferData(
      x0, y0, x0 + width - 1, y0 + height - 1, view.Depth.data());
  }

  // Clipping planes keep the side their normal points to.
  if (this->ClippingPlanes)
  {
    this->ClippingPlanes->InitTraversal();
    while (vtkPlane* plane = this->ClippingPlanes->GetNextItem())
    {
      const double* n = plane->GetNormal();
      const double* o = plane->GetOrigin();
      view.ClippingPlanes.emplace_back(
        n[0], n[1], n[2], -(n[0] * o[0] + n[1] * o[1] + n[2] * o[2]));
    }
  }

  // Gradient opacity needs gradient magnitudes: 256 codes up to the steepest gradient the data
  // can have (its range over the smallest spacing, along a diagonal).
  // It is on when a function is set, enabled, and not 1 everywhere (VTK creates a constant
  // default for anyone who asks for the function, the fixed-point mapper among them).
  const auto valueRange = s.Sampler ? s.Sampler->ValueRange() : std::array<double, 2>{ 0.0, 1.0 };
  const double steepest = std::max(valueRange[1] - valueRange[0], 1e-300) /
                          std::max(s.SmallestSpacing, 1e-300) * std::sqrt(3.0);
  const double magnitudeScale = 255.0 / steepest;
  double gradientFactors[256];
  bool gradientOpacity = false;
  if (!pair && property->HasGradientOpacity(0) && !property->GetDisableGradientOpacity(0))
  {
    property->GetGradientOpacity(0)->GetTable(0.0, 255.0 / magnitudeScale, 256, gradientFactors);
    for (double f : gradientFactors)
    {
      gradientOpacity = gradientOpacity || !(f >= 1.0);
    }
  }

  std::vector<double> settingsKey = dataKey;
  settingsKey.insert(settingsKey.end(), croppingKey.begin(), croppingKey.end());
  for (const Eigen::Vector4d& plane : view.ClippingPlanes)
  {
    settingsKey.insert(settingsKey.end(), plane.data(), plane.data() + 4);
  }
  settingsKey.insert(settingsKey.end(),
    { static_cast<double>(width), static_cast<double>(height), static_cast<double>(x0),
      static_cast<double>(y0), step, static_cast<double>(frames),
      static_cast<double>(this->MemoryBudget), static_cast<double>(this->BlendMode),
      static_cast<double>(this->NumberOfThreads), static_cast<double>(property->GetShade(0)),
      static_cast<double>(gradientOpacity), gradientOpacity ? magnitudeScale : 0.0 });
  std::vector<double> viewKey;
  AppendMatrix(viewKey, worldToNDC);
  // The same camera can give matrices that differ by 1e-7 relative (vtkWindowToImageFilter, for
  // one, saves and restores it in single precision), and geometry's depth moves when the
  // clipping range is recomputed: compare these with tolerances far below a pixel (relative to
  // the matrix's largest element, so that any unit of length works), the settings exactly.
  double scale = 0.0;
  for (double e : viewKey)
  {
    scale = std::max(scale, std::abs(e));
  }
  if (settingsKey != s.SettingsKey || !NearlyEqual(viewKey, s.ViewKey, 1e-6 * scale) ||
      !NearlyEqual(view.Depth, s.Depth, 1e-5))
  {
    savr::FrameSettings settings;
    settings.SampleDistance = step;
    settings.MaximumFrames = frames;
    settings.MemoryBudget = static_cast<std::size_t>(this->MemoryBudget);
    settings.Threads = this->NumberOfThreads;
    settings.Shade = property->GetShade(0) != 0;
    settings.GradientMagnitudes = gradientOpacity;
    settings.MagnitudeScale = magnitudeScale;
    s.Loop.Reset(view, s.Sampler, settings);
    s.SettingsKey = settingsKey;
    s.ViewKey = viewKey;
    s.Depth = view.Depth;
    s.HaveImage = false;
  }

  // Transfer functions: retabulate when the property or the stored encoding change.
  const savr::SampleEncoding& encoding = s.Loop.Encoding();
  vtkObject* colorFunction = property->GetColorChannels(0) == 1
                               ? static_cast<vtkObject*>(property->GetGrayTransferFunction(0))
                               : static_cast<vtkObject*>(property->GetRGBTransferFunction(0));
  vtkPiecewiseFunction* opacityFunction = property->GetScalarOpacity(0);
  std::vector<double> tableKey = { static_cast<double>(
                                     reinterpret_cast<std::uintptr_t>(colorFunction)),
    static_cast<double>(colorFunction->GetMTime()),
    static_cast<double>(reinterpret_cast<std::uintptr_t>(opacityFunction)),
    static_cast<double>(opacityFunction->GetMTime()), property->GetScalarOpacityUnitDistance(0),
    encoding.Offset, encoding.Scale, static_cast<double>(encoding.Levels),
    static_cast<double>(encoding.HasNaNCode), static_cast<double>(this->PreIntegration) };
  // Dependent RGBA colours are normalized as textures are: integers over their type's maximum.
  const double colorScale =
    scalars && scalars->GetDataType() != VTK_FLOAT && scalars->GetDataType() != VTK_DOUBLE
      ? 1.0 / scalars->GetDataTypeMax()
      : 1.0;
  if (pair)
  {
    // Every component's range (the codes are levels over it: new data with other ranges needs
    // new tables), functions, weight and unit distance, and how they combine.
    tableKey.insert(tableKey.end(), { static_cast<double>(property->GetIndependentComponents()),
                                      static_cast<double>(components), colorScale });
    const auto& sampler = *static_cast<const savr::ComponentSampler*>(s.DataSampler.get());
    for (int c = 0; c < components; ++c)
    {
      const std::array<double, 2> range = sampler.Range(c);
      tableKey.insert(tableKey.end(), { range[0], range[1] });
      vtkObject* color = property->GetColorChannels(c) == 1
                           ? static_cast<vtkObject*>(property->GetGrayTransferFunction(c))
                           : static_cast<vtkObject*>(property->GetRGBTransferFunction(c));
      vtkPiecewiseFunction* opacity = property->GetScalarOpacity(c);
      tableKey.insert(
        tableKey.end(), { static_cast<double>(reinterpret_cast<std::uintptr_t>(color)),
                          static_cast<double>(color->GetMTime()),
                          static_cast<double>(reinterpret_cast<std::uintptr_t>(opacity)),
                          static_cast<double>(opacity->GetMTime()), property->GetComponentWeight(c),
                          property->GetScalarOpacityUnitDistance(c) });
    }
  }
  const bool tableChanged = tableKey != s.TableKey;
  bool shadingChanged = false;

  // Lighting: the renderer's switched-on lights as directions, the property's coefficients.
  // Tabulated per normal code; a change re-blends the stored samples.
  if (property->GetShade(0))
  {
    std::vector<savr::Light> lights;
    std::vector<double> shadingKey = { property->GetAmbient(0), property->GetDiffuse(0),
      property->GetSpecular(0), property->GetSpecularPower(0) };
    vtkLightCollection* collection = ren->GetLights();
    collection->InitTraversal();
    while (vtkLight* light = collection->GetNextItem())
    {
      if (!light->GetSwitch())
      {
        continue;
      }
      double position[3];
      double focal[3];
      light->GetTransformedPosition(position);
      light->GetTransformedFocalPoint(focal);
      savr::Light l;
      l.Direction =
        Eigen::Vector3d(position[0] - focal[0], position[1] - focal[1], position[2] - focal[2]);
      if (l.Direction.norm() == 0.0)
      {
        continue;
      }
      l.Direction.normalize();
      const double intensity = light->GetIntensity();
      const double* ambientColor = light->GetAmbientColor();
      const double* diffuseColor = light->GetDiffuseColor();
      const double* specularColor = light->GetSpecularColor();
      l.Ambient = intensity * Eigen::Vector3d(ambientColor[0], ambientColor[1], ambientColor[2]);
      l.Diffuse = intensity * Eigen::Vector3d(diffuseColor[0], diffuseColor[1], diffuseColor[2]);
      l.Specular =
        intensity * Eigen::Vector3d(specularColor[0], specularColor[1], specularColor[2]);
      lights.push_back(l);
      for (const Eigen::Vector3d* v : { &l.Direction, &l.Ambient, &l.Diffuse, &l.Specular })
      {
        shadingKey.insert(shadingKey.end(), v->data(), v->data() + 3);
      }
    }
    const double* toward = camera->GetDirectionOfProjection();
    const Eigen::Vector3d toViewer(-toward[0], -toward[1], -toward[2]);
    shadingKey.insert(shadingKey.end(), toViewer.data(), toViewer.data() + 3);
    shadingKey.push_back(static_cast<double>(ren->GetTwoSidedLighting()));
    // Compared with a tolerance, as the view is: the same camera can differ in its last bits.
    if (!NearlyEqual(shadingKey, s.ShadingKey, 1e-9))
    {
      s.Shading.Build(lights, toViewer, property->GetAmbient(0), property->GetDiffuse(0),
        property->GetSpecular(0), property->GetSpecularPower(0), ren->GetTwoSidedLighting() != 0);
      s.ShadingKey = shadingKey;
      shadingChanged = true;
    }
    s.Loop.SetShading(&s.Shading);
  }
  else
  {
    s.Loop.SetShading(nullptr);
  }

  // Isosurfaces: the property's iso values with the transfer functions' colour and opacity at
  // each; a change re-blends.
  if (mode == savr::BlendMode::Isosurface)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    std::vector<double> key = tableKey;
    for (int i = 0; i < values->GetNumberOfContours(); ++i)
    {
      key.push_back(values->GetValue(i));
    }
    if (key != s.IsoKey)
    {
      s.Isos.Values.clear();
      s.Isos.Colors.clear();
      s.Isos.Opacities.clear();
      std::vector<double> sorted(key.begin() + tableKey.size(), key.end());
      std::sort(sorted.begin(), sorted.end());
      for (double v : sorted)
      {
        double rgb[3] = { 0, 0, 0 };
        if (property->GetColorChannels(0) == 1)
        {
          rgb[0] = rgb[1] = rgb[2] = static_cast<vtkPiecewiseFunction*>(colorFunction)->GetValue(v);
        }
        else
        {
          static_cast<vtkColorTransferFunction*>(colorFunction)->GetColor(v, rgb);
        }
        s.Isos.Values.push_back(v);
        s.Isos.Colors.emplace_back(rgb[0], rgb[1], rgb[2]);
        s.Isos.Opacities.push_back(std::min(std::max(opacityFunction->GetValue(v), 0.0), 1.0));
      }
      ++s.Isos.Generation;
      s.IsoKey = key;
      shadingChanged = true;
    }
    s.Loop.SetIsoSurfaces(&s.Isos);
  }
  else
  {
    s.Loop.SetIsoSurfaces(nullptr);
  }

  // Gradient opacity: its function tabulated over the 256 magnitude codes; an edit re-blends.
  if (gradientOpacity)
  {
    vtkPiecewiseFunction* function = property->GetGradientOpacity(0);
    const std::vector<double> key = { static_cast<double>(
                                        reinterpret_cast<std::uintptr_t>(function)),
      static_cast<double>(function->GetMTime()), magnitudeScale };
    if (key != s.GradientOpacityKey)
    {
      s.GradientOpacity.Build(gradientFactors, magnitudeScale);
      s.GradientOpacityKey = key;
      shadingChanged = true;
    }
    s.Loop.SetGradientOpacity(&s.GradientOpacity);
  }
  else
  {
    s.Loop.SetGradientOpacity(nullptr);
  }
  if (tableChanged)
  {
    const int n = static_cast<int>(encoding.Levels);
    const double lo = encoding.Decode(0);
    const double hi = encoding.Decode(encoding.Levels - 1);
    std::vector<double> rgb(3 * n);
    std::vector<double> opacity(n);
    if (property->GetColorChannels(0) == 1)
    {
      std::vector<double> gray(n);
      static_cast<vtkPiecewiseFunction*>(colorFunction)->GetTable(lo, hi, n, gray.data());
      for (int i = 0; i < n; ++i)
      {
        rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = gray[i];
      }
    }
    else
    {
      static_cast<vtkColorTransferFunction*>(colorFunction)->GetTable(lo, hi, n, rgb.data());
    }
    opacityFunction->GetTable(lo, hi, n, opacity.data());
    std::vector<double> firstTerms;
    std::vector<double> secondTerms;
    if (pair)
    {
      const ComponentTables tables = TabulateComponents(
        property, *static_cast<const savr::ComponentSampler*>(s.DataSampler.get()), colorScale);
      const bool independent = property->GetIndependentComponents() != 0;
      firstTerms = PairTerms(tables, 0, components, independent);
      PairTable(property, tables, firstTerms, encoding, rgb, opacity);
      if (components > 2)
      {
        secondTerms = PairTerms(tables, 2, components, independent);
      }
    }
    // Combined independent components may emit more than they absorb (see TabulateComponents).
    const double maxColor = pair && property->GetIndependentComponents() ? components : 1.0;
    s.Table.Build(
      encoding, rgb.data(), opacity.data(), property->GetScalarOpacityUnitDistance(0), maxColor);
    if (!secondTerms.empty())
    {
      // Three or four components: each sample's second code joins its value code in the blend.
      s.Table.SetComponentTerms(
        std::move(firstTerms), std::move(secondTerms), property->GetIndependentComponents() != 0);
    }
    s.TableKey = tableKey;
  }

  // One frame of the current phase.
  bool imageChanged = false;
  const savr::Phase phase =
    this->Interactive
      ? savr::Phase::Interacting
      : (s.Refined(this->ErrorTolerance) ? savr::Phase::Complete : savr::Phase::Accumulating);
  if (phase == savr::Phase::Interacting)
  {
    // Nothing of this frame is kept: skip what the transfer function hides, and stop rays once
    // what lies behind could change a pixel by less than one 8-bit level.
    savr::PassOptions fast;
    fast.SkipTransparent = true;
    fast.Termination = 1.0 / 256.0;
    s.Loop.RenderSinglePass(s.Table, mode, step, 0.0, fast);
    imageChanged = true;
  }
  else if (phase == savr::Phase::Accumulating)
  {
    s.Loop.AccumulateFrame(s.Table, mode);
    imageChanged = true;
  }
  else if (tableChanged || shadingChanged || s.Loop.CurrentPhase() == savr::Phase::Interacting)
  {
    // Complete: new samples would add nothing; blend again only if the image shown is not the
    // blend of the stored samples with the current transfer function.
    s.Loop.Reblend(s.Table, mode);
    imageChanged = true;
  }

  if (imageChanged)
  {
    s.Loop.ImageBytes(s.Bytes);
    // The display helper stretches its texture's first to last texel centre over the rectangle
    // it draws, and filters linearly: an image of the rectangle's size would come out resampled
    // (blurred by up to half a pixel towards the edges). With every pixel doubled in both
    // directions, each window pixel's texture lookup falls between two copies of its own pixel,
    // so the window shows the image exactly. Fully transparent pixels (premultiplied, all four
    // bytes zero) leave the window as it is: only the rectangle around the others is drawn.
    const std::size_t w = static_cast<std::size_t>(width);
    const std::size_t h = static_cast<std::size_t>(height);
    const std::uint32_t* in = reinterpret_cast<const std::uint32_t*>(s.Bytes.data());
    // Pixels outside the loop's rectangle are zero: only it is searched.
    int rectangle[4];
    s.Loop.ImageRectangle(rectangle);
    const std::size_t left = std::min(static_cast<std::size_t>(rectangle[0]), w);
    const std::size_t right = std::min(static_cast<std::size_t>(rectangle[2]), w);
    std::size_t xBegin = w;
    std::size_t xEnd = 0;
    std::size_t yBegin = h;
    std::size_t yEnd = 0;
    for (std::size_t y = static_cast<std::size_t>(rectangle[1]);
         y < std::min(static_cast<std::size_t>(rectangle[3]), h); ++y)
    {
      const std::uint32_t* row = in + y * w;
      std::size_t first = left;
      while (first < right && row[first] == 0)
      {
        ++first;
      }
      if (first >= right)
      {
        continue;
      }
      std::size_t last = right;
      while (row[last - 1] == 0)
      {
        --last;
      }
      xBegin = std::min(xBegin, first);
      xEnd = std::max(xEnd, last);
      yBegin = std::min(yBegin, y);
      yEnd = y + 1;
    }
    const std::size_t sw = xEnd > xBegin ? xEnd - xBegin : 0;
    const std::size_t sh = yEnd > yBegin ? yEnd - yBegin : 0;
    s.Doubled.resize(16 * sw * sh);
    std::uint32_t* out = reinterpret_cast<std::uint32_t*>(s.Doubled.data());
    for (std::size_t y = 0; y < sh; ++y)
    {
      std::uint32_t* row = out + 2 * y * 2 * sw;
      const std::uint32_t* source = in + (yBegin + y) * w + xBegin;
      for (std::size_t x = 0; x < sw; ++x)
      {
        row[2 * x] = row[2 * x + 1] = source[x];
      }
      std::copy(row, row + 2 * sw, row + 2 * sw);
    }
    s.Shown[0] = static_cast<int>(xBegin);
    s.Shown[1] = static_cast<int>(yBegin);
    s.Shown[2] = static_cast<int>(sw);
    s.Shown[3] = static_cast<int>(sh);
    s.HaveImage = true;
  }

  if (s.Display && s.HaveImage && s.Shown[2] > 0 && s.Shown[3] > 0)
  {
    // Draw in front of the volume's nearest corner so that opaque geometry nearer than the
    // volume still hides it; the rays themselves stopped at the depth buffer.
    vtkMatrix4x4* toDepth =
      camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), 0, 1);
    double nearest = 1.0;
    for (int c = 0; c < 8; ++c)
    {
      const double corner[4] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)],
        bounds[4 + ((c >> 2) & 1)], 1.0 };
      double p[4];
      toDepth->MultiplyPoint(corner, p);
      nearest = std::min(nearest, p[3] > 0.0 ? p[2] / p[3] : 0.0);
    }
    const float depth = static_cast<float>(std::min(std::max(nearest, 1e-6), 1.0));
    int viewport[2] = { 2 * width, 2 * height };
    int size[2] = { 2 * s.Shown[2], 2 * s.Shown[3] };
    int origin[2] = { 2 * s.Shown[0], 2 * s.Shown[1] };
    s.Display->RenderTexture(vol, ren, size, viewport, size, origin, depth, s.Doubled.data());
  }

  this->LastFrameTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (imageChanged && !this->Interactive)
  {
    FrameInfo info{ this->GetNumberOfFramesAccumulated(), this->GetFrameLimit(),
      this->GetErrorEstimate(), this->LastFrameTime, this->GetRefinementComplete() };
    this->InvokeEvent(RefinementFrameEvent, &info);
  }
}

void vtkSAVRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "MaximumNumberOfFrames: " << this->MaximumNumberOfFrames << "\n";
  os << indent << "MemoryBudget: " << this->MemoryBudget << "\n";
  os << indent << "Interactive: " << this->Interactive << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "ErrorTolerance: " << this->ErrorTolerance << "\n";
  os << indent << "PreIntegration: " << this->PreIntegration << "\n";
  os << indent << "ErrorEstimate: " << this->GetErrorEstimate() << "\n";
  os << indent << "FramesAccumulated: " << this->GetNumberOfFramesAccumulated() << "\n";
  os << indent << "MemoryInUse: " << this->GetMemoryInUse() << "\n";
  os << indent << "LastFrameTime: " << this->LastFrameTime << "\n";
}

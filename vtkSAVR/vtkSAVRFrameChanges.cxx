#include "vtkSAVRFrameChanges.h"

#include "sampler/ComponentSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRMapperSettings.h"

#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkMatrix4x4.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkSAVRParticleSampler.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>

namespace
{
double Address(const void* object)
{
  return static_cast<double>(reinterpret_cast<std::uintptr_t>(object));
}

void AppendMatrix(std::vector<double>& key, vtkMatrix4x4* m)
{
  for (int i = 0; i < 16; ++i)
  {
    key.push_back(m ? m->GetElement(i / 4, i % 4) : (i % 5 == 0 ? 1.0 : 0.0));
  }
}

// An object by its address and modification time.
void AppendObject(std::vector<double>& key, vtkObject* object)
{
  key.insert(key.end(), { Address(object), static_cast<double>(object->GetMTime()) });
}

// Where the data lies on screen: each corner of its bounds in pixels and window depth. A corner at
// or behind the camera's plane has no pixel: its clip coordinates, scaled to unit length, stand in.
// Positions on screen, unlike the matrix's entries, do not grow with the data's distance from the
// origin.
std::vector<double> ScreenCorners(
  vtkMatrix4x4* worldToNDC, const double bounds[6], int width, int height)
{
  std::vector<double> corners;
  for (int c = 0; c < 8; ++c)
  {
    const double p[4] = { bounds[c & 1], bounds[2 + ((c >> 1) & 1)], bounds[4 + ((c >> 2) & 1)],
      1.0 };
    double clip[4];
    worldToNDC->MultiplyPoint(p, clip);
    const double length =
      std::sqrt(clip[0] * clip[0] + clip[1] * clip[1] + clip[2] * clip[2] + clip[3] * clip[3]);
    if (clip[3] > 1e-9 * length)
    {
      corners.insert(corners.end(),
        { 0.0, (clip[0] / clip[3] + 1.0) * 0.5 * width, (clip[1] / clip[3] + 1.0) * 0.5 * height,
          (clip[2] / clip[3] + 1.0) * 0.5, 0.0 });
    }
    else
    {
      corners.insert(corners.end(),
        { 1.0, clip[0] / length, clip[1] / length, clip[2] / length, clip[3] / length });
    }
  }
  return corners;
}

// The same camera can give matrices that differ by 1e-7 relative (vtkWindowToImageFilter, for one,
// saves and restores it in single precision), and the clipping range is recomputed every render:
// corners count as unmoved within a twentieth of a pixel, depths within the tolerance of the depth
// buffer's comparison.
bool SameScreenCorners(const std::vector<double>& a, const std::vector<double>& b)
{
  if (a.size() != b.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < a.size(); i += 5)
  {
    const bool inFront = a[i] == 0.0;
    // A corner behind the camera is compared by its direction, within the matrices' own noise.
    if (a[i] != b[i] || !(std::abs(a[i + 1] - b[i + 1]) <= (inFront ? 0.05 : 1e-6)) ||
        !(std::abs(a[i + 2] - b[i + 2]) <= (inFront ? 0.05 : 1e-6)) ||
        !(std::abs(a[i + 3] - b[i + 3]) <= (inFront ? 1e-5 : 1e-6)) ||
        !(std::abs(a[i + 4] - b[i + 4]) <= 1e-6))
    {
      return false;
    }
  }
  return true;
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
} // namespace

void vtkSAVRFrameChanges::BeginFrame()
{
  this->BlendChanged = false;
}

vtkSAVRFrameChanges::Input vtkSAVRFrameChanges::CompareInput(const vtkSAVRMapperSettings& mapper,
  vtkDataObject* input, vtkDataArray* scalars, int cellFlag, vtkVolumeProperty* property,
  vtkMatrix4x4* volumeMatrix)
{
  Key key = { Address(input), static_cast<double>(input->GetMTime()),
    static_cast<double>(property->GetInterpolationType()), static_cast<double>(mapper.VectorMode),
    static_cast<double>(mapper.VectorComponent) };
  if (vtkDataSet::SafeDownCast(input))
  {
    key.insert(key.end(),
      { Address(scalars), scalars ? static_cast<double>(scalars->GetMTime()) : 0.0,
        static_cast<double>(cellFlag), static_cast<double>(property->GetIndependentComponents()) });
  }
  if (vtkSAVRParticleSampler::Particles(input))
  {
    // The particles' kernel and radii.
    const std::string& radii = mapper.ParticleRadiusArrayName;
    key.insert(
      key.end(), { mapper.ParticleRadius, static_cast<double>(std::hash<std::string>()(radii)),
                   static_cast<double>(mapper.ParticleKernel),
                   static_cast<double>(mapper.ParticleNormalized) });
  }
  else
  {
    // Each block's array is chosen by these settings.
    const std::string& name = mapper.ArrayName;
    key.insert(key.end(),
      { static_cast<double>(mapper.ScalarMode), static_cast<double>(mapper.ArrayAccessMode),
        static_cast<double>(mapper.ArrayId), static_cast<double>(std::hash<std::string>()(name)) });
  }
  AppendMatrix(key, volumeMatrix);
  if (key == this->FailedDataKey)
  {
    return Input::KnownBad;
  }
  if (key == this->DataKey)
  {
    return Input::Unchanged;
  }
  this->PendingDataKey = std::move(key);
  return Input::Changed;
}

void vtkSAVRFrameChanges::AcceptInput()
{
  this->FailedDataKey.clear();
  this->DataKey = this->PendingDataKey;
  this->CroppingKey.clear(); // wrap the new sampler
  this->ViewKey.clear();
}

void vtkSAVRFrameChanges::RejectInput()
{
  this->FailedDataKey = this->PendingDataKey;
  this->DataKey.clear();
}

bool vtkSAVRFrameChanges::CroppingChanged(
  const vtkSAVRMapperSettings& mapper, vtkMatrix4x4* volumeMatrix)
{
  // Planes and flags matter only while cropping is on.
  Key key = { static_cast<double>(mapper.Cropping) };
  if (mapper.Cropping)
  {
    const double* planes = mapper.CroppingRegionPlanes.data();
    key.push_back(static_cast<double>(mapper.CroppingRegionFlags));
    key.insert(key.end(), planes, planes + 6);
    AppendMatrix(key, volumeMatrix);
  }
  if (key == this->CroppingKey)
  {
    return false;
  }
  this->CroppingKey = std::move(key);
  return true;
}

bool vtkSAVRFrameChanges::ParticleBoundsChanged(
  const vtkSAVRMapperSettings& mapper, vtkObject* particles)
{
  Key key;
  AppendObject(key, particles);
  const std::string& radii = mapper.ParticleRadiusArrayName;
  key.insert(
    key.end(), { mapper.ParticleRadius, static_cast<double>(std::hash<std::string>()(radii)),
                 static_cast<double>(mapper.ParticleKernel) });
  if (key == this->ParticleBoundsKey)
  {
    return false;
  }
  this->ParticleBoundsKey = std::move(key);
  return true;
}

bool vtkSAVRFrameChanges::Sampling::operator==(const Sampling& other) const
{
  return this->Data == other.Data && this->Cropping == other.Cropping &&
         this->ClippingPlanes == other.ClippingPlanes &&
         std::equal(this->Viewport, this->Viewport + 4, other.Viewport) &&
         savr::SameSampling(this->Settings, other.Settings) && this->BlendMode == other.BlendMode &&
         this->SlicePlane == other.SlicePlane;
}

bool vtkSAVRFrameChanges::ViewChanged(const vtkSAVRMapperSettings& mapper,
  vtkVolumeProperty* property, const savr::View& view, vtkMatrix4x4* worldToNDC,
  const double bounds[6], const int origin[2], const savr::FrameSettings& settings)
{
  Sampling sampling;
  sampling.Data = this->DataKey;
  sampling.Cropping = this->CroppingKey;
  for (const Eigen::Vector4d& plane : view.ClippingPlanes)
  {
    sampling.ClippingPlanes.insert(sampling.ClippingPlanes.end(), plane.data(), plane.data() + 4);
  }
  const int viewport[4] = { view.Width, view.Height, origin[0], origin[1] };
  std::copy(viewport, viewport + 4, sampling.Viewport);
  sampling.Settings = settings;
  sampling.BlendMode = mapper.BlendMode;
  // Slice blending draws the plane: moving it starts over (a single frame).
  auto* plane = vtkPlane::SafeDownCast(property->GetSliceFunction());
  if (mapper.BlendMode == vtkVolumeMapper::SLICE_BLEND && plane)
  {
    sampling.SlicePlane.insert(
      sampling.SlicePlane.end(), plane->GetOrigin(), plane->GetOrigin() + 3);
    sampling.SlicePlane.insert(
      sampling.SlicePlane.end(), plane->GetNormal(), plane->GetNormal() + 3);
  }
  Key viewKey = ScreenCorners(worldToNDC, bounds, view.Width, view.Height);
  // Geometry's depth moves when the clipping range is recomputed: compared with a tolerance, as
  // the corners are; the settings exactly.
  if (this->LastSampling && sampling == *this->LastSampling &&
      SameScreenCorners(viewKey, this->ViewKey) && NearlyEqual(view.Depth, this->Depth, 1e-5))
  {
    return false;
  }
  this->LastSampling = std::move(sampling);
  this->ViewKey = std::move(viewKey);
  this->Depth = view.Depth;
  return true;
}

void vtkSAVRFrameChanges::ForgetView()
{
  this->LastSampling.reset();
  this->ViewKey.clear();
}

bool vtkSAVRFrameChanges::TransferFunctionChanged(vtkVolumeProperty* property,
  const savr::SampleEncoding& encoding, bool preIntegration,
  const savr::ComponentSampler* components, double colorScale, bool opacityIsAttenuation)
{
  Key key;
  AppendObject(key, vtkSAVRConversions::ColorFunction(property, 0));
  AppendObject(key, property->GetScalarOpacity(0));
  key.insert(
    key.end(), { property->GetScalarOpacityUnitDistance(0), encoding.Offset, encoding.Scale,
                 static_cast<double>(encoding.Levels), static_cast<double>(encoding.HasNaNCode),
                 static_cast<double>(preIntegration), static_cast<double>(opacityIsAttenuation) });
  if (components)
  {
    // Every component's range (the codes are levels over it: new data with other ranges needs
    // new tables), functions, weight and unit distance, and how they combine.
    const int count = components->NumberOfComponents();
    key.insert(key.end(), { static_cast<double>(property->GetIndependentComponents()),
                            static_cast<double>(count), colorScale });
    for (int c = 0; c < count; ++c)
    {
      const std::array<double, 2> range = components->Range(c);
      key.insert(key.end(), { range[0], range[1] });
      AppendObject(key, vtkSAVRConversions::ColorFunction(property, c));
      AppendObject(key, property->GetScalarOpacity(c));
      key.insert(
        key.end(), { property->GetComponentWeight(c), property->GetScalarOpacityUnitDistance(c) });
    }
  }
  if (key == this->TableKey)
  {
    return false;
  }
  this->TableKey = std::move(key);
  this->BlendChanged = true;
  return true;
}

bool vtkSAVRFrameChanges::ShadingChanged(vtkVolumeProperty* property, int components,
  const std::vector<savr::Light>& lights, const Eigen::Vector3d& toViewer, bool twoSided)
{
  // Every component's coefficients (independent components are lit with their own).
  Key key = { static_cast<double>(components) };
  for (int c = 0; c < 4; ++c)
  {
    key.insert(key.end(), { property->GetAmbient(c), property->GetDiffuse(c),
                            property->GetSpecular(c), property->GetSpecularPower(c) });
  }
  for (const savr::Light& l : lights)
  {
    for (const Eigen::Vector3d* v : { &l.Direction, &l.Ambient, &l.Diffuse, &l.Specular })
    {
      key.insert(key.end(), v->data(), v->data() + 3);
    }
  }
  key.insert(key.end(), toViewer.data(), toViewer.data() + 3);
  key.push_back(static_cast<double>(twoSided));
  // Compared with a tolerance, as the view is: the same camera can differ in its last bits.
  if (NearlyEqual(key, this->ShadingKey, 1e-9))
  {
    return false;
  }
  this->ShadingKey = std::move(key);
  this->BlendChanged = true;
  return true;
}

bool vtkSAVRFrameChanges::IsoSurfacesChanged(vtkVolumeProperty* property)
{
  Key key = this->TableKey;
  vtkContourValues* values = property->GetIsoSurfaceValues();
  for (int i = 0; i < values->GetNumberOfContours(); ++i)
  {
    key.push_back(values->GetValue(i));
  }
  if (key == this->IsoKey)
  {
    return false;
  }
  this->IsoKey = std::move(key);
  this->BlendChanged = true;
  return true;
}

bool vtkSAVRFrameChanges::GradientOpacityChanged(
  const double* factors, const double* magnitudeScales, int sets)
{
  Key key(factors, factors + 256 * static_cast<std::size_t>(sets));
  key.insert(key.end(), magnitudeScales, magnitudeScales + sets);
  if (key == this->GradientOpacityKey)
  {
    return false;
  }
  this->GradientOpacityKey = std::move(key);
  this->BlendChanged = true;
  return true;
}

vtkSAVRFrameChanges::Action vtkSAVRFrameChanges::NextAction(
  bool interactive, bool complete, savr::Phase loopPhase) const
{
  if (interactive)
  {
    return Action::SinglePass;
  }
  if (!complete)
  {
    return Action::Accumulate;
  }
  // Every frame is taken: new samples would add nothing; blend again only if the image shown is
  // not the blend of the stored samples with the current tables.
  return this->BlendChanged || loopPhase == savr::Phase::Interacting ? Action::Reblend
                                                                     : Action::Reuse;
}

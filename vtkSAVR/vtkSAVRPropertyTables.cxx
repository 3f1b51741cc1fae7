#include "vtkSAVRPropertyTables.h"

#include "blend/Composite.h"
#include "encoding/SampleEncoding.h"
#include "frame/FrameLoop.h"
#include "sampler/ComponentSampler.h"
#include "vtkSAVRConversions.h"
#include "vtkSAVRFrameChanges.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace
{
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
  std::vector<double> Alpha[4]; // the opacity function's value, where one applies
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
    t.Alpha[c].assign(levels, 0.0);
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
        t.Alpha[c][q] = a;
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

// Each component's levels for the maximum and minimum blends (see
// savr::TransferFunctionTable::ComponentLevels): independent, each through its own functions,
// weighted by its ComponentWeight; dependent, the colour and opacity each contributes.
savr::TransferFunctionTable::ComponentLevels LevelsOf(
  vtkVolumeProperty* property, const ComponentTables& t, int n)
{
  savr::TransferFunctionTable::ComponentLevels levels;
  levels.Count = n;
  levels.Independent = property->GetIndependentComponents() != 0;
  levels.PairLevels = savr::ComponentSampler::kFirstLevels;
  levels.PairCodes = savr::ComponentSampler::kPairCodes;
  for (int c = 0; c < n; ++c)
  {
    levels.LevelCount[c] = static_cast<int>(t.Value[c].size());
    levels.UnitDistance[c] =
      std::max(property->GetScalarOpacityUnitDistance(levels.Independent ? c : 0), 1e-300);
    const double weight = levels.Independent ? property->GetComponentWeight(c) : 1.0;
    levels.Weight[c] = weight;
    levels.RGBA[c].assign(4 * static_cast<std::size_t>(levels.PairLevels), 0.0f);
    levels.Medium[c].assign(4 * static_cast<std::size_t>(levels.PairLevels), 0.0f);
    for (std::size_t q = 0; q < t.Alpha[c].size(); ++q)
    {
      const double a = t.Alpha[c][q];
      float* out = &levels.RGBA[c][4 * q];
      for (int i = 0; i < 3; ++i)
      {
        const double rgb = t.RGB[c][3 * q + i];
        out[i] = static_cast<float>(levels.Independent ? weight * a * rgb : rgb);
      }
      out[3] = static_cast<float>(weight * a);
      float* medium = &levels.Medium[c][4 * q];
      medium[0] = static_cast<float>(std::min(t.Sigma[c][q], 1e30));
      for (int i = 0; i < 3; ++i)
      {
        medium[1 + i] = static_cast<float>(t.RGB[c][3 * q + i]);
      }
    }
  }
  return levels;
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
      opacity[k] = savr::composite::IntervalOpacity(t.Sigma[1][q[1]], unit);
      continue;
    }
    const double* term = &terms[5 * static_cast<std::size_t>(k)];
    const double absorption = term[0] > 0.0 ? term[1] / term[0] : 0.0;
    for (int i = 0; i < 3; ++i)
    {
      out[i] = absorption > 0.0 ? term[2 + i] / absorption : 0.0;
    }
    opacity[k] = savr::composite::IntervalOpacity(absorption, unit);
  }
}
} // namespace

std::vector<savr::Light> vtkSAVRPropertyTables::Lights(vtkRenderer* renderer)
{
  std::vector<savr::Light> lights;
  vtkLightCollection* collection = renderer->GetLights();
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
    l.Specular = intensity * Eigen::Vector3d(specularColor[0], specularColor[1], specularColor[2]);
    lights.push_back(l);
  }
  return lights;
}

bool vtkSAVRPropertyTables::TabulateGradientOpacity(vtkVolumeProperty* property,
  const savr::ComponentSampler* components, const std::array<double, 2>& valueRange,
  double smallestSpacing)
{
  // Dependent components have no gradient opacity of their own here.
  if (components && !property->GetIndependentComponents())
  {
    return false;
  }
  this->GradientSets = components ? components->NumberOfComponents() : 1;
  bool inUse = false;
  for (int c = 0; c < this->GradientSets; ++c)
  {
    const std::array<double, 2> range = components ? components->Range(c) : valueRange;
    const double steepest =
      std::max(range[1] - range[0], 1e-300) / std::max(smallestSpacing, 1e-300) * std::sqrt(3.0);
    this->MagnitudeScales[c] = 255.0 / steepest;
    double* factors = &this->GradientFactors[256 * c];
    std::fill(factors, factors + 256, 1.0);
    if (property->HasGradientOpacity(c) && !property->GetDisableGradientOpacity(c))
    {
      property->GetGradientOpacity(c)->GetTable(0.0, steepest, 256, factors);
      for (int i = 0; i < 256; ++i)
      {
        inUse = inUse || !(factors[i] >= 1.0);
      }
    }
  }
  return inUse;
}

void vtkSAVRPropertyTables::BuildGradientOpacity()
{
  this->GradientOpacity.Build(
    this->GradientFactors, this->MagnitudeScales.data(), this->GradientSets);
}

void vtkSAVRPropertyTables::BuildShading(vtkVolumeProperty* property,
  const std::vector<savr::Light>& lights, const Eigen::Vector3d& toViewer, bool twoSided,
  int components)
{
  // Independent components are lit each with its own coefficients (one table while they are
  // all the same); others with the first's.
  const int sets = property->GetIndependentComponents() ? std::min(std::max(components, 1), 4) : 1;
  std::vector<savr::ShadingCoefficients> coefficients;
  bool same = true;
  for (int c = 0; c < sets; ++c)
  {
    coefficients.push_back({ property->GetAmbient(c), property->GetDiffuse(c),
      property->GetSpecular(c), property->GetSpecularPower(c) });
    const savr::ShadingCoefficients& k = coefficients.back();
    const savr::ShadingCoefficients& first = coefficients.front();
    same = same && k.Ambient == first.Ambient && k.Diffuse == first.Diffuse &&
           k.Specular == first.Specular && k.SpecularPower == first.SpecularPower;
  }
  if (same)
  {
    coefficients.resize(1);
  }
  this->Shading.Build(lights, toViewer, coefficients, twoSided);
}

void vtkSAVRPropertyTables::BuildIsoSurfaces(vtkVolumeProperty* property)
{
  // Each iso value with the transfer functions' colour and opacity there, in increasing order.
  vtkContourValues* values = property->GetIsoSurfaceValues();
  std::vector<double> sorted;
  for (int i = 0; i < values->GetNumberOfContours(); ++i)
  {
    sorted.push_back(values->GetValue(i));
  }
  std::sort(sorted.begin(), sorted.end());
  vtkObject* colorFunction = vtkSAVRConversions::ColorFunction(property, 0);
  vtkPiecewiseFunction* opacityFunction = property->GetScalarOpacity(0);
  this->Isos.Values.clear();
  this->Isos.Colors.clear();
  this->Isos.Opacities.clear();
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
    this->Isos.Values.push_back(v);
    this->Isos.Colors.emplace_back(rgb[0], rgb[1], rgb[2]);
    this->Isos.Opacities.push_back(std::min(std::max(opacityFunction->GetValue(v), 0.0), 1.0));
  }
  ++this->Isos.Generation;
}

bool vtkSAVRPropertyTables::NeedsFineCodes(
  vtkVolumeProperty* property, const savr::SampleEncoding& encoding)
{
  vtkObject* colorFunction = vtkSAVRConversions::ColorFunction(property, 0);
  vtkPiecewiseFunction* opacityFunction = property->GetScalarOpacity(0);
  const bool gray = property->GetColorChannels(0) == 1;
  std::vector<double> nodes;
  double node[6];
  for (int i = 0; i < opacityFunction->GetSize(); ++i)
  {
    opacityFunction->GetNodeValue(i, node);
    nodes.push_back(node[0]);
  }
  if (gray)
  {
    auto* function = static_cast<vtkPiecewiseFunction*>(colorFunction);
    for (int i = 0; i < function->GetSize(); ++i)
    {
      function->GetNodeValue(i, node);
      nodes.push_back(node[0]);
    }
  }
  else
  {
    auto* function = static_cast<vtkColorTransferFunction*>(colorFunction);
    for (int i = 0; i < function->GetSize(); ++i)
    {
      function->GetNodeValue(i, node);
      nodes.push_back(node[0]);
    }
  }
  return encoding.HasFeaturesBetweenCodes(
    nodes.data(), nodes.size(), [&](double v) { return opacityFunction->GetValue(v); },
    [&](double v, double rgb[3])
    {
      if (gray)
      {
        rgb[0] = rgb[1] = rgb[2] = static_cast<vtkPiecewiseFunction*>(colorFunction)->GetValue(v);
      }
      else
      {
        static_cast<vtkColorTransferFunction*>(colorFunction)->GetColor(v, rgb);
      }
    });
}

void vtkSAVRPropertyTables::BuildTransferFunction(vtkVolumeProperty* property,
  const savr::SampleEncoding& encoding, const savr::ComponentSampler* components, double colorScale,
  bool attenuation)
{
  vtkObject* colorFunction = vtkSAVRConversions::ColorFunction(property, 0);
  vtkPiecewiseFunction* opacityFunction = property->GetScalarOpacity(0);
  // Each code takes the functions' values at the code's value, not their mean over the values
  // that round to it: a feature narrower than a code gets codes of its own (NeedsFineCodes), and
  // elsewhere the functions are nearly linear over a code, where the two agree. (Measured on a
  // spike between two levels of 8-bit data: the mean helps integer codes, RMSE 0.117 -> 0.042,
  // but fractional codes far more, 0.0055 pre-integrated, and on them the mean changes nothing.)
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
  if (attenuation && !components)
  {
    // The table reads opacity as that of one unit distance: the opacity of one unit distance
    // at this attenuation.
    for (double& a : opacity)
    {
      a = -std::expm1(-std::max(a, 0.0));
    }
  }
  const bool independent = property->GetIndependentComponents() != 0;
  const int count = components ? components->NumberOfComponents() : 1;
  std::vector<double> firstTerms;
  std::vector<double> secondTerms;
  savr::TransferFunctionTable::ComponentLevels levels;
  if (components)
  {
    const ComponentTables tables = TabulateComponents(property, *components, colorScale);
    levels = LevelsOf(property, tables, count);
    firstTerms = PairTerms(tables, 0, count, independent);
    PairTable(property, tables, firstTerms, encoding, rgb, opacity);
    if (count > 2)
    {
      secondTerms = PairTerms(tables, 2, count, independent);
    }
  }
  // Combined independent components may emit more than they absorb (see TabulateComponents).
  const double maxColor = components && independent ? count : 1.0;
  this->Table.Build(
    encoding, rgb.data(), opacity.data(), property->GetScalarOpacityUnitDistance(0), maxColor);
  if (components)
  {
    this->Table.SetComponentLevels(std::move(levels));
  }
  if (!secondTerms.empty())
  {
    // Three or four components: each sample's second code joins its value code in the blend.
    this->Table.SetComponentTerms(std::move(firstTerms), std::move(secondTerms), independent);
  }
}

void vtkSAVRPropertyTables::Update(
  const FrameInputs& frame, vtkSAVRFrameChanges& changes, savr::FrameLoop& loop)
{
  vtkVolumeProperty* property = frame.Property;
  vtkRenderer* ren = frame.Renderer;
  const savr::SampleEncoding& encoding = loop.Encoding();
  const bool tableChanged = changes.TransferFunctionChanged(property, encoding,
    frame.PreIntegration, frame.Components, frame.ColorScale, frame.OpacityIsAttenuation);

  // Lighting: the renderer's switched-on lights as directions, the property's coefficients.
  if (property->GetShade(0))
  {
    const std::vector<savr::Light> lights = Lights(ren);
    const double* toward = ren->GetActiveCamera()->GetDirectionOfProjection();
    const Eigen::Vector3d toViewer(-toward[0], -toward[1], -toward[2]);
    const bool twoSided = ren->GetTwoSidedLighting() != 0;
    const int components = frame.Components ? frame.Components->NumberOfComponents() : 1;
    if (changes.ShadingChanged(property, components, lights, toViewer, twoSided))
    {
      this->BuildShading(property, lights, toViewer, twoSided, components);
    }
    loop.SetShading(this->GetShading());
  }
  else
  {
    loop.SetShading(nullptr);
  }

  if (frame.Mode == savr::BlendMode::Isosurface)
  {
    if (changes.IsoSurfacesChanged(property))
    {
      this->BuildIsoSurfaces(property);
    }
    loop.SetIsoSurfaces(this->GetIsoSurfaces());
  }
  else
  {
    loop.SetIsoSurfaces(nullptr);
  }

  // Gradient opacity: its function over the 256 magnitude codes.
  if (frame.GradientOpacity)
  {
    if (changes.GradientOpacityChanged(
          this->GradientFactors, this->MagnitudeScales.data(), this->GradientSets))
    {
      this->BuildGradientOpacity();
    }
    loop.SetGradientOpacity(this->GetGradientOpacity());
  }
  else
  {
    loop.SetGradientOpacity(nullptr);
  }
  if (tableChanged)
  {
    this->BuildTransferFunction(
      property, encoding, frame.Components, frame.ColorScale, frame.OpacityIsAttenuation);
  }
}

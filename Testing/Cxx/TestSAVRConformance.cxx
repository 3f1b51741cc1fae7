// Conformance with VTK's own mappers: scenes of VTK's volume regression tests rebuilt on the
// wavelet (TestGPURayCastCompositeMask..., TestGPURayCastCropping, TestGPURayCastClipping,
// TestGPURayCastPerspectiveParallel, TestGPURayCastCameraInside, TestFixedPointRayCasterNearest,
// TestGPURayCastMIP / MinIP / Additive...), each rendered by vtkGPUVolumeRayCastMapper,
// vtkFixedPointVolumeRayCastMapper and vtkSAVRVolumeMapper (refined) with the same camera,
// volume property and vtkVolumeMapper settings; four-component and RGBA data under maximum and
// minimum intensity. SAVR's mean channel difference from the GPU mapper must be at most twice
// the fixed-point mapper's plus 2 levels: where VTK's two mappers agree, SAVR agrees with them as
// closely. Where the GPU mapper is wrong (a case says why), SAVR is held to within 2 levels of
// the fixed-point mapper. One argument picks the case; each is a ctest of label "conformance".

#include "SAVRImageChecks.h"
#include "SAVRScenes.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkFixedPointVolumeRayCastMapper.h"
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <string>

namespace
{
constexpr int kSize = 160;
constexpr double kStep = 0.25; // the wavelet's spacing is 1: a quarter voxel for all three

struct Case
{
  std::function<void(vtkVolumeMapper*)> Mapper;     // for all three mappers
  std::function<void(vtkVolumeProperty*)> Property; // after the wavelet's
  std::function<void(vtkCamera*)> Camera;           // after the default view
  std::function<void(vtkVolume*)> Volume;           // its matrix
  bool FixedPointDraws = true; // else the bound is 2 levels from the GPU mapper
  // The GPU mapper is wrong here: SAVR is held to within `FixedPointBound` levels of the
  // fixed-point mapper.
  bool AgainstFixedPoint = false;
  double FixedPointBound = 2.0;
  // Other data than the wavelet, with the whole volume property (`Property` then sets it up).
  std::function<vtkSmartPointer<vtkImageData>()> Data;
};

// Several components (TestFixedPointRayCasterNearest's multi-component volumes,
// TestGPURayCastFourComponents*, TestGPURayCastTwoComponentsDependent): four independent ones,
// RGBA, or two dependent ones (luminance and alpha), composited or under maximum, minimum,
// average or additive intensity.
enum class Components
{
  FourIndependent,
  RGBA,
  LuminanceAlpha
};

Case ComponentsCase(int blend, Components kind, bool shade = false)
{
  Case c;
  c.Mapper = [blend](vtkVolumeMapper* m) { m->SetBlendMode(blend); };
  c.Property = [kind, shade](vtkVolumeProperty* p)
  {
    if (shade)
    {
      // TestGPURayCastTwoComponentsDependentGradient's lighting, on every component.
      p->ShadeOn();
      for (int i = 0; i < 4; ++i)
      {
        p->SetAmbient(i, 0.2);
        p->SetDiffuse(i, 0.7);
        p->SetSpecular(i, 0.3);
        p->SetSpecularPower(i, 12.0);
      }
    }
    switch (kind)
    {
      case Components::RGBA:
        savr_scenes::ColorAndAlphaProperty(p);
        break;
      case Components::LuminanceAlpha:
        savr_scenes::DependentComponentsProperty(p);
        break;
      case Components::FourIndependent:
        savr_scenes::IndependentComponentsProperty(p);
        savr_scenes::LastComponentFunctions(p, 0.4);
        break;
    }
  };
  c.Data = [kind]()
  {
    return kind == Components::RGBA
             ? savr_scenes::ColorAndAlphaImage(10)
             : savr_scenes::ComponentImage(kind == Components::LuminanceAlpha ? 2 : 4, 10);
  };
  const int minimum = vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  const bool rgba = kind == Components::RGBA;
  // VTK 9.1's GPU shader for the minimum of independent components keeps each component's
  // maximum (its comparison is the maximum's) and adds the opacity to blue: there SAVR is held
  // to the fixed-point mapper, which takes minima (its images and the GPU's are 19 levels
  // apart).
  c.AgainstFixedPoint = blend == minimum && !rgba;
  // The fixed-point mapper has no average or additive intensity.
  c.FixedPointDraws =
    blend != vtkVolumeMapper::AVERAGE_INTENSITY_BLEND && blend != vtkVolumeMapper::ADDITIVE_BLEND;
  return c;
}

// TestGPURayCastIndependentComponentsLightParameters at half size: three overlapping balls, one
// per independent component (0.33 inside, 0 outside), each green through its own functions and
// lit with its own ambient, diffuse and specular coefficients.
Case LightParametersCase()
{
  Case c;
  c.Data = []()
  {
    constexpr int kDims = 50;
    vtkNew<vtkImageData> image;
    image->SetDimensions(kDims, kDims, kDims);
    image->AllocateScalars(VTK_DOUBLE, 3);
    auto* values = static_cast<double*>(image->GetScalarPointer());
    const double third = kDims / 3;
    const double centres[3][3] = { { third, kDims / 2, kDims / 2 },
      { 2 * third, kDims / 2, kDims / 2 }, { kDims / 2, third, kDims / 2 } };
    for (int z = 0; z < kDims; ++z)
    {
      for (int y = 0; y < kDims; ++y)
      {
        for (int x = 0; x < kDims; ++x)
        {
          for (const auto& centre : centres)
          {
            const double d2 = (x - centre[0]) * (x - centre[0]) +
                              (y - centre[1]) * (y - centre[1]) + (z - centre[2]) * (z - centre[2]);
            *values++ = d2 <= third * third ? 0.33 : 0.0;
          }
        }
      }
    }
    return vtkSmartPointer<vtkImageData>(image.GetPointer());
  };
  c.Property = [](vtkVolumeProperty* p)
  {
    const double coefficients[3][4] = { { 0.2, 0.9, 0.4, 10.0 }, { 0.5, 0.3, 0.1, 1.0 },
      { 0.7, 0.9, 0.4, 10.0 } };
    p->IndependentComponentsOn();
    p->ShadeOn();
    p->SetInterpolationTypeToLinear();
    for (int i = 0; i < 3; ++i)
    {
      vtkNew<vtkColorTransferFunction> color;
      color->AddRGBPoint(0.0, 0.0, 0.0, 0.0);
      color->AddRGBPoint(1.0, 0.0, 1.0, 0.0);
      vtkNew<vtkPiecewiseFunction> opacity;
      opacity->AddPoint(0.0, 0.0);
      opacity->AddPoint(1.0, 0.2);
      p->SetColor(i, color);
      p->SetScalarOpacity(i, opacity);
      p->SetAmbient(i, coefficients[i][0]);
      p->SetDiffuse(i, coefficients[i][1]);
      p->SetSpecular(i, coefficients[i][2]);
      p->SetSpecularPower(i, coefficients[i][3]);
    }
  };
  c.Camera = [](vtkCamera* camera) { camera->Zoom(1.5); };
  // VTK 9.1's GPU shader leaves out the headlight's ambient colour (black by default) and lights
  // the balls' insides, where the gradient is zero, with the ambient coefficient alone: there
  // SAVR is held to the fixed-point mapper, which, as SAVR, takes the light's ambient colour.
  // Each ball is lit by its own component's gradient (1.49 levels from the fixed point, whose
  // per-voxel gradients also light the balls' silhouettes). Lighting every ball by the sum of
  // the components' gradients was 2.06 levels from it, lighting all by the first component's
  // 2.52 (the others black).
  c.AgainstFixedPoint = true;
  c.FixedPointBound = 2.0;
  return c;
}

std::map<std::string, Case> Cases()
{
  std::map<std::string, Case> cases;
  cases["composite"] = {};
  cases["parallel"] = { nullptr, nullptr, [](vtkCamera* c) { c->ParallelProjectionOn(); } };
  cases["maximum"] = { [](vtkVolumeMapper* m) { m->SetBlendModeToMaximumIntensity(); } };
  cases["minimum"] = { [](vtkVolumeMapper* m) { m->SetBlendModeToMinimumIntensity(); } };
  // The fixed-point mapper has no average intensity: SAVR is held to the GPU mapper's grey.
  cases["average"] = { [](vtkVolumeMapper* m) { m->SetBlendModeToAverageIntensity(); }, nullptr,
    nullptr, nullptr, false };
  cases["nearest"] = { nullptr, [](vtkVolumeProperty* p) { p->SetInterpolationTypeToNearest(); } };
  cases["cropping"] = { [](vtkVolumeMapper* m)
    {
      m->CroppingOn();
      m->SetCroppingRegionPlanes(-6.0, 4.0, -8.0, 8.0, -5.0, 7.0);
      m->SetCroppingRegionFlagsToSubVolume();
    } };
  cases["fence"] = { [](vtkVolumeMapper* m)
    {
      m->CroppingOn();
      m->SetCroppingRegionPlanes(-4.0, 4.0, -4.0, 4.0, -4.0, 4.0);
      m->SetCroppingRegionFlagsToInvertedCross();
    },
    nullptr, nullptr, [](vtkVolume* v) { v->RotateWXYZ(30.0, 1.0, 1.0, 0.0); } };
  cases["clipping"] = { [](vtkVolumeMapper* m)
    {
      vtkNew<vtkPlane> plane;
      plane->SetOrigin(1.0, 0.0, 0.0);
      plane->SetNormal(-1.0, 0.3, 0.2);
      m->AddClippingPlane(plane);
    } };
  cases["inside"] = { nullptr, nullptr,
    [](vtkCamera* c)
    {
      c->SetPosition(0.5, -2.0, 1.0);
      c->SetFocalPoint(0.0, 20.0, 0.0);
    } };
  cases["shaded"] = { nullptr, [](vtkVolumeProperty* p)
    {
      p->ShadeOn();
      p->SetAmbient(0.2);
      p->SetDiffuse(0.7);
      p->SetSpecular(0.3);
      p->SetSpecularPower(12.0);
    } };
  // Nor additive intensity (it draws a composite): SAVR is held to the GPU mapper's grey.
  // TestGPURayCastGradientOpacity's reading on the wavelet: opacity where the gradient is steep,
  // shaded, with each interpolation.
  const auto gradientOpacity = [](bool nearest)
  {
    return [nearest](vtkVolumeProperty* p)
    {
      vtkNew<vtkPiecewiseFunction> gradient;
      gradient->AddPoint(0.0, 0.0);
      gradient->AddPoint(8.0, 0.2);
      gradient->AddPoint(20.0, 1.0);
      p->SetGradientOpacity(gradient);
      p->ShadeOn();
      if (nearest)
      {
        p->SetInterpolationTypeToNearest();
      }
    };
  };
  cases["gradientOpacity"] = { nullptr, gradientOpacity(false) };
  cases["gradientOpacityNearest"] = { nullptr, gradientOpacity(true) };
  cases["additive"] = { [](vtkVolumeMapper* m) { m->SetBlendModeToAdditive(); }, nullptr, nullptr,
    nullptr, false };
  const int composite = vtkVolumeMapper::COMPOSITE_BLEND;
  const int maximum = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  const int minimum = vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  cases["composite4"] = ComponentsCase(composite, Components::FourIndependent);
  cases["compositeRGBA"] = ComponentsCase(composite, Components::RGBA);
  cases["compositeLA"] = ComponentsCase(composite, Components::LuminanceAlpha);
  cases["shadedLA"] = ComponentsCase(composite, Components::LuminanceAlpha, true);
  cases["shadedRGBA"] = ComponentsCase(composite, Components::RGBA, true);
  cases["shaded4"] = ComponentsCase(composite, Components::FourIndependent, true);
  cases["maximum4"] = ComponentsCase(maximum, Components::FourIndependent);
  cases["minimum4"] = ComponentsCase(minimum, Components::FourIndependent);
  cases["maximumRGBA"] = ComponentsCase(maximum, Components::RGBA);
  const int average = vtkVolumeMapper::AVERAGE_INTENSITY_BLEND;
  const int additive = vtkVolumeMapper::ADDITIVE_BLEND;
  cases["average4"] = ComponentsCase(average, Components::FourIndependent);
  cases["additive4"] = ComponentsCase(additive, Components::FourIndependent);
  cases["additiveRGBA"] = ComponentsCase(additive, Components::RGBA);
  cases["lightParameters"] = LightParametersCase();
  // TestGPURayCastTwoComponentsGradient's per-component gradient opacity on four independent
  // components: each component's opacity scaled by its own function of its own gradient's
  // magnitude (the third component's shell hidden, the others thinned where they are flat).
  const auto gradientOpacity4 = [composite](bool shade)
  {
    Case gradient4 = ComponentsCase(composite, Components::FourIndependent, shade);
    gradient4.Property = [base = gradient4.Property](vtkVolumeProperty* p)
    {
      base(p);
      // Magnitudes in each component's units per world unit: about 12 for the distances and the
      // slab coordinate, 0 to 20 for the wavelet.
      const double ramps[4][2] = { { 4.0, 16.0 }, { 6.0, 24.0 }, { 14.0, 15.0 }, { 0.0, 12.0 } };
      for (int i = 0; i < 4; ++i)
      {
        vtkNew<vtkPiecewiseFunction> gradient;
        gradient->AddPoint(ramps[i][0], 0.0);
        gradient->AddPoint(ramps[i][1], 1.0);
        p->SetGradientOpacity(i, gradient);
      }
    };
    // VTK 9.1's GPU shader scales each component's opacity by every component's gradient-opacity
    // function and weight, of the component's own gradient (its loop over the components uses
    // one gradient): there SAVR is held to the fixed-point mapper (the GPU's image is 19.7 levels
    // from it).
    gradient4.AgainstFixedPoint = true;
    gradient4.FixedPointBound = 2.0;
    return gradient4;
  };
  cases["gradientOpacity4"] = gradientOpacity4(false);
  cases["shadedGradientOpacity4"] = gradientOpacity4(true);
  return cases;
}

void Configure(const Case& c, vtkVolumeMapper* mapper, vtkVolumeProperty* property)
{
  if (!c.Data)
  {
    savr_scenes::WaveletProperty(property);
  }
  if (c.Property)
  {
    c.Property(property);
  }
  if (c.Mapper)
  {
    c.Mapper(mapper);
  }
}
} // namespace

int TestSAVRConformance(int argc, char* argv[])
{
  savr_scenes::Expectations expect;
  const std::map<std::string, Case> cases = Cases();
  const std::string name = argc > 1 ? argv[1] : "";
  const auto found = cases.find(name);
  if (found == cases.end())
  {
    std::fprintf(stderr, "usage: TestSAVRConformance <case>: one of");
    for (const auto& c : cases)
    {
      std::fprintf(stderr, " %s", c.first.c_str());
    }
    std::fprintf(stderr, "\n");
    return EXIT_FAILURE;
  }
  const Case& c = found->second;
  vtkSmartPointer<vtkImageData> wavelet = c.Data ? c.Data() : savr_scenes::Wavelet(10);

  // SAVR, refined to a quarter voxel; its camera is the one every mapper uses.
  savr_scenes::Scene scene(wavelet, kSize, kSize);
  Configure(c, scene.Mapper, scene.Property);
  scene.Mapper->SetSampleDistance(4 * kStep);
  scene.Mapper->SetMaximumNumberOfFrames(4);
  if (c.Volume)
  {
    c.Volume(scene.Volume);
  }
  vtkCamera* camera = scene.Renderer->GetActiveCamera();
  camera->SetPosition(-30.0, -48.0, 35.0);
  camera->SetFocalPoint(0.0, 0.0, 0.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  scene.Renderer->ResetCamera();
  if (c.Camera)
  {
    c.Camera(camera);
  }
  scene.Renderer->ResetCameraClippingRange();
  scene.RenderUntilComplete();
  vtkSmartPointer<vtkImageData> savr = savr_scenes::Capture(scene.Window);

  vtkSmartPointer<vtkImageData> fixedPointImage;
  if (c.FixedPointDraws)
  {
    savr_scenes::Scene peer(wavelet, kSize, kSize);
    vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
    fixedPoint->SetInputData(wavelet);
    fixedPoint->AutoAdjustSampleDistancesOff();
    fixedPoint->SetSampleDistance(kStep);
    fixedPoint->SetImageSampleDistance(1.0);
    Configure(c, fixedPoint, peer.Property);
    peer.Volume->SetMapper(fixedPoint);
    if (c.Volume)
    {
      c.Volume(peer.Volume);
    }
    peer.Renderer->SetActiveCamera(camera);
    peer.Window->Render();
    fixedPointImage = savr_scenes::Capture(peer.Window);
  }

  bool supported = true;
  vtkSmartPointer<vtkImageData> gpu = savr_scenes::GPUImage(
    wavelet, camera, kSize, kSize,
    [&c](vtkGPUVolumeRayCastMapper* mapper, vtkVolumeProperty* property, vtkRenderer* renderer)
    {
      mapper->AutoAdjustSampleDistancesOff();
      mapper->SetSampleDistance(kStep);
      Configure(c, mapper, property);
      if (c.Volume)
      {
        vtkVolumeCollection* volumes = renderer->GetVolumes();
        volumes->InitTraversal();
        c.Volume(volumes->GetNextVolume());
      }
    },
    &supported);
  if (!supported)
  {
    expect(false, name + ": the GPU mapper renders here");
    return EXIT_FAILURE;
  }
  double ours = savr_scenes::Compare(savr, gpu).Mean;
  double peers = fixedPointImage ? savr_scenes::Compare(fixedPointImage, gpu).Mean : 0.0;
  double bound = 2.0 * peers + 2.0;
  if (c.AgainstFixedPoint)
  {
    std::printf(
      "%s: the GPU mapper is %.2f levels from the fixed-point mapper\n", name.c_str(), peers);
    ours = savr_scenes::Compare(savr, fixedPointImage).Mean;
    peers = 0.0;
    bound = c.FixedPointBound;
  }
  char peerMean[64];
  std::snprintf(peerMean, sizeof(peerMean), "fixed point vs GPU %.2f", peers);
  const std::string peerText = c.AgainstFixedPoint ? "held to the fixed point"
                               : fixedPointImage   ? std::string(peerMean)
                                                   : "the fixed-point mapper has no such mode";
  std::printf("%s: SAVR vs %s mean %.2f levels, %s (bound %.2f)\n", name.c_str(),
    c.AgainstFixedPoint ? "fixed point" : "GPU", ours, peerText.c_str(), bound);
  const double background[3] = { 0.1, 0.1, 0.15 };
  expect(savr_scenes::CoveredFraction(savr, background) > 0.02, name + ": SAVR draws the wavelet");
  expect(ours <= bound, name + ": SAVR within the bound of its reference (mean " +
                          std::to_string(ours) + ", bound " + std::to_string(bound) + ")");
  if (const char* dir = std::getenv("SAVR_CONFORMANCE_OUTPUT"))
  {
    savr_scenes::WritePNG(savr, std::string(dir) + "/" + name + "SAVR.png");
    if (fixedPointImage)
    {
      savr_scenes::WritePNG(fixedPointImage, std::string(dir) + "/" + name + "FixedPoint.png");
    }
    savr_scenes::WritePNG(gpu, std::string(dir) + "/" + name + "GPU.png");
  }
  return expect.Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

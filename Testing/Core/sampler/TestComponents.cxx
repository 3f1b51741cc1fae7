// Three and four components: the third and fourth travel as each sample's second code and join
// the value code in the blend (TransferFunctionTable::SetComponentTerms).

#include "TestHelpers.h"
#include "sampler/ComponentSampler.h"

#include <gtest/gtest.h>

#include <cstring>

using namespace savr_test;

namespace
{
// Per component: extinction (per world unit) and colour at a value in [0, 1] of its range.
double ComponentSigma(int c, double f)
{
  const double centres[4] = { 0.7, 0.3, 0.5, 0.85 };
  const double d = (f - centres[c]) / 0.12;
  return (1.5 + 0.5 * c) * std::exp(-d * d);
}
Eigen::Array3d ComponentColor(int c, double f)
{
  const Eigen::Array3d colors[4] = { { 1.0, 0.8, 0.2 }, { 0.1, 0.9, 0.3 }, { 0.2, 0.3, 1.0 },
    { 1.0, 0.2, 0.1 } };
  return colors[c] * (0.6 + 0.4 * f);
}

// The terms of components `first` and `first` + 1 (of `n`) for every packed pair code; `scale`
// multiplies the extinctions.
std::vector<double> Terms(int first, int n, double scale = 1.0)
{
  using CS = savr::ComponentSampler;
  std::vector<double> terms(5 * static_cast<std::size_t>(CS::kPairCodes), 0.0);
  for (std::uint32_t k = 0; k < CS::kPairCodes; ++k)
  {
    const double f[2] = { (k % CS::kFirstLevels) / (CS::kFirstLevels - 1.0),
      (k / CS::kFirstLevels) / (CS::kSecondLevels - 1.0) };
    for (int i = 0; i < 2 && first + i < n; ++i)
    {
      const double s = scale * ComponentSigma(first + i, f[i]);
      const Eigen::Array3d e = s * ComponentColor(first + i, f[i]);
      terms[5 * k] += s;
      terms[5 * k + 1] += s * s;
      for (int j = 0; j < 3; ++j)
      {
        terms[5 * k + 2 + j] += e[j];
      }
    }
  }
  return terms;
}

savr::TransferFunctionTable Table(const savr::SampleEncoding& e, int n, double scale = 1.0)
{
  savr::TransferFunctionTable table;
  std::vector<double> rgb(3 * e.Levels, 0.0);
  std::vector<double> opacity(e.Levels, 0.0);
  table.Build(e, rgb.data(), opacity.data(), 1.0);
  table.SetComponentTerms(Terms(0, n, scale), Terms(2, n, scale), true);
  return table;
}

// Four smooth fields on one grid, as a ComponentSampler of `n` of them.
struct FourFields
{
  FourFields()
  {
    for (int c = 0; c < 4; ++c)
    {
      this->Grids.emplace_back(new WaveGrid(20));
      for (float& v : this->Grids[c]->Values)
      {
        v = c == 0 ? v : (c == 1 ? -v : (c == 2 ? v * v : std::sin(2.0f * v)));
      }
    }
  }
  std::shared_ptr<const savr::Sampler> Sampler(int n, int gradientFrom = 0) const
  {
    std::vector<std::shared_ptr<const savr::Sampler>> parts;
    for (int c = 0; c < n; ++c)
    {
      parts.push_back(this->Grids[c]->Sampler());
    }
    return std::make_shared<savr::ComponentSampler>(parts, gradientFrom);
  }
  std::vector<std::unique_ptr<WaveGrid>> Grids;
};

savr::View View(int size)
{
  return PerspectiveView(Eigen::Vector3d(0.4, -0.3, 4.0), Eigen::Vector3d(0, 0, 0),
    Eigen::Vector3d(0, 1, 0), 40.0, size, size, 1.0, 10.0);
}
} // namespace

// A homogeneous slab of four constant components: the pixel is the analytic emission-absorption
// integral of the combined medium, extinction sum(s^2) / sum(s) and emission sum(s * colour).
TEST(Components, ConstantComponentsGiveTheCombinedMedium)
{
  const float values[4] = { 0.7f, 0.3f, 0.55f, 0.8f };
  std::vector<std::shared_ptr<const savr::Sampler>> parts;
  for (float v : values)
  {
    parts.push_back(std::make_shared<ConstantSlab>(2.0, v));
  }
  auto sampler = std::make_shared<savr::ComponentSampler>(parts, 0);
  ASSERT_TRUE(sampler->HasSecondCode());
  const savr::View view = ParallelViewAlongX(4, 0.5, -1.0, 4.0);
  savr::FrameSettings settings;
  settings.SampleDistance = 0.3;
  settings.MaximumFrames = 4;
  savr::FrameLoop loop;
  loop.Reset(view, sampler, settings);
  const auto table = Table(loop.Encoding(), 4);
  for (int k = 0; k < 4; ++k)
  {
    loop.AccumulateFrame(table, savr::BlendMode::Composite);
  }
  // The expectation, from the quantized component values.
  double sum = 0.0;
  double squares = 0.0;
  Eigen::Array3d emission = Eigen::Array3d::Zero();
  for (int c = 0; c < 4; ++c)
  {
    const int levels = c % 2 == 0 ? 255 : 254;
    const double f = std::round(static_cast<double>(values[c]) * levels) / levels;
    const double s = ComponentSigma(c, f);
    sum += s;
    squares += s * s;
    emission += s * ComponentColor(c, f);
  }
  const double sigma = squares / sum;
  const double alpha = -std::expm1(-sigma * 2.0);
  const Eigen::Array3d color = (emission / sigma).min(4.0) * alpha;
  const std::vector<float>& image = loop.Image();
  for (int p = 0; p < 16; ++p)
  {
    EXPECT_NEAR(image[4 * p + 3], alpha, 1e-6 * alpha) << "pixel " << p;
    for (int i = 0; i < 3; ++i)
    {
      EXPECT_NEAR(image[4 * p + i], color[i], 1e-6 * color[i]) << "pixel " << p;
    }
  }
  // Without the second code's terms the medium is the first two components': not the same.
  savr::TransferFunctionTable firstTwo;
  {
    std::vector<double> rgb(3 * loop.Encoding().Levels, 0.0);
    std::vector<double> opacity(loop.Encoding().Levels, 0.0);
    firstTwo.Build(loop.Encoding(), rgb.data(), opacity.data(), 1.0);
    firstTwo.SetComponentTerms(Terms(0, 2), Terms(2, 2), true);
  }
  loop.Reblend(firstTwo, savr::BlendMode::Composite);
  EXPECT_GT(std::abs(loop.Image()[3] - alpha), 1e-3);
}

// DESIGN §2 for four components: 2^m frames equal one pass at dt / 2^m.
TEST(Components, PowerOfTwoFramesEqualOneFinePass)
{
  FourFields fields;
  auto sampler = fields.Sampler(4);
  const savr::View view = View(40);
  const double dt = 0.2;
  for (int m = 0; m <= 4; ++m)
  {
    const int frames = 1 << m;
    savr::FrameSettings settings;
    settings.SampleDistance = dt;
    settings.MaximumFrames = frames;
    savr::FrameLoop accumulated;
    accumulated.Reset(view, sampler, settings);
    const auto table = Table(accumulated.Encoding(), 4);
    for (int k = 0; k < frames; ++k)
    {
      accumulated.AccumulateFrame(table, savr::BlendMode::Composite);
    }
    savr::FrameLoop single;
    single.Reset(view, sampler, settings);
    single.RenderSinglePass(table, savr::BlendMode::Composite, dt / frames, 0.0);
    EXPECT_GT(MaxValue(single.Image()), 0.2) << "the scene must not be blank";
    EXPECT_LT(MaxAbsDifference(accumulated.Image(), single.Image()), 1e-5) << "m=" << m;
  }
}

// Three and four components: a re-blend with edited terms equals a fresh render, the third and
// fourth take two bytes more per sample, and images do not depend on the thread count.
TEST(Components, ReblendMemoryAndThreads)
{
  FourFields fields;
  const savr::View view = View(37); // tiles do not divide the image evenly
  for (int n : { 3, 4 })
  {
    auto sampler = fields.Sampler(n);
    std::vector<std::vector<float>> images;
    for (int threads : { 1, 2, 8 })
    {
      savr::FrameSettings settings;
      settings.SampleDistance = 0.15;
      settings.MaximumFrames = 5;
      settings.Threads = threads;
      settings.GradientMagnitudes = true; // ignored: the second codes take their place
      savr::FrameLoop loop;
      loop.Reset(view, sampler, settings);
      const auto table = Table(loop.Encoding(), n);
      for (int k = 0; k < 5; ++k)
      {
        loop.AccumulateFrame(table, savr::BlendMode::Composite);
      }
      images.push_back(loop.Image());
      if (threads == 1)
      {
        EXPECT_EQ(loop.MemoryInUse(), 4 * 5 * loop.SamplesPerFrame()) << n << " components";
        // Edited terms re-blend to a fresh render's image.
        const auto edited = Table(loop.Encoding(), n, 2.5);
        loop.Reblend(edited, savr::BlendMode::Composite);
        savr::FrameLoop fresh;
        fresh.Reset(view, sampler, settings);
        for (int k = 0; k < 5; ++k)
        {
          fresh.AccumulateFrame(edited, savr::BlendMode::Composite);
        }
        EXPECT_EQ(0, std::memcmp(loop.Image().data(), fresh.Image().data(),
                       loop.Image().size() * sizeof(float)));
        EXPECT_GT(MaxAbsDifference(loop.Image(), images.back()), 1e-2) << "the edit shows";
      }
    }
    EXPECT_GT(MaxValue(images[0]), 0.2);
    for (std::size_t i = 1; i < images.size(); ++i)
    {
      ASSERT_EQ(images[i].size(), images[0].size());
      EXPECT_EQ(
        0, std::memcmp(images[i].data(), images[0].data(), images[0].size() * sizeof(float)));
    }
  }
}

// Maximum and minimum intensity of several components: independent, each component's own
// extreme level through its own colour and opacity, weighted and summed; dependent, the levels of
// the sample whose last component is extreme. A sample with a component that has no level
// (not finite) is left out.
TEST(Components, ExtremaPerComponentOrByTheLastOne)
{
  using CS = savr::ComponentSampler;
  savr::SampleEncoding encoding;
  encoding.Levels = 65535;
  encoding.HasNaNCode = true;
  encoding.NaNCode = 65535;
  const std::vector<double> rgb(3 * static_cast<std::size_t>(encoding.TableSize()), 0.5);
  const std::vector<double> opacity(encoding.TableSize(), 0.5);
  // Component c at level q: colour (q / 255) in channel c % 3, opacity 0.1 * (c + 1);
  // independent ones premultiplied.
  const auto levels = [](bool independent)
  {
    savr::TransferFunctionTable::ComponentLevels l;
    l.Count = 4;
    l.Independent = independent;
    l.PairLevels = CS::kFirstLevels;
    l.PairCodes = CS::kPairCodes;
    for (int c = 0; c < 4; ++c)
    {
      l.RGBA[c].assign(4 * CS::kFirstLevels, 0.0f);
      for (int q = 0; q < CS::kFirstLevels; ++q)
      {
        l.RGBA[c][4 * q + c % 3] = q / 255.0f * (independent ? 0.1f * (c + 1) : 1.0f);
        l.RGBA[c][4 * q + 3] = 0.1f * (c + 1);
      }
    }
    return l;
  };
  const auto pack = [](int a, int b)
  { return static_cast<std::uint32_t>(a + CS::kFirstLevels * b); };
  // Three samples (levels of components 0..3) and one whose second pair has no level.
  const int samples[3][4] = { { 10, 200, 30, 40 }, { 90, 20, 60, 10 }, { 50, 50, 5, 120 } };
  const auto blend = [&](bool independent, savr::BlendMode mode)
  {
    savr::TransferFunctionTable tf;
    tf.Build(encoding, rgb.data(), opacity.data(), 1.0);
    tf.SetComponentLevels(levels(independent));
    savr::AlphaCache cache;
    cache.Prepare(tf, 0.5, 1.0);
    auto feed = [&](auto& stream)
    {
      for (int i = 0; i < 3; ++i)
      {
        const int* q = samples[i];
        stream.Push(i + 0.5, pack(q[0], q[1]), pack(q[2], q[3]) << 16 | savr::kNoNormal);
      }
      stream.Push(3.5, pack(255, 254), savr::kNoSecondCode << 16 | savr::kNoNormal);
      stream.Finish(4.0);
    };
    return savr::BlendSamples(feed, tf, cache, mode, 0.0);
  };
  // Independent maxima: levels 90, 200, 60, 120; channel c % 3 gets level / 255 times opacity.
  const savr::Pixel most = blend(true, savr::BlendMode::Maximum);
  EXPECT_NEAR(most[0], 0.1f * 90 / 255 + 0.4f * 120 / 255, 1e-5);
  EXPECT_NEAR(most[1], 0.2f * 200 / 255, 1e-5);
  EXPECT_NEAR(most[2], 0.3f * 60 / 255, 1e-5);
  EXPECT_NEAR(most[3], 1.0f, 1e-5);
  const savr::Pixel least = blend(true, savr::BlendMode::Minimum);
  EXPECT_NEAR(least[0], 0.1f * 10 / 255 + 0.4f * 10 / 255, 1e-5);
  EXPECT_NEAR(least[1], 0.2f * 20 / 255, 1e-5);
  EXPECT_NEAR(least[2], 0.3f * 5 / 255, 1e-5);
  // Dependent: the third sample has the largest last component, the second the smallest; the
  // summed colour is scaled by the summed opacity (here 1, clamped).
  const savr::Pixel byLast = blend(false, savr::BlendMode::Maximum);
  EXPECT_NEAR(byLast[0], 50 / 255.0f + 120 / 255.0f, 1e-5);
  EXPECT_NEAR(byLast[1], 50 / 255.0f, 1e-5);
  EXPECT_NEAR(byLast[2], 5 / 255.0f, 1e-5);
  const savr::Pixel byLeast = blend(false, savr::BlendMode::Minimum);
  EXPECT_NEAR(byLeast[0], 90 / 255.0f + 10 / 255.0f, 1e-5);
  EXPECT_NEAR(byLeast[1], 20 / 255.0f, 1e-5);
  EXPECT_NEAR(byLeast[2], 60 / 255.0f, 1e-5);
}

namespace
{
// Four components' tables with per-level media (ComponentLevels, what the shaded and
// gradient-opacity composite of independent components reads): component c at level q has the
// extinction and colour of ComponentSigma and ComponentColor, weight 1, unit distance 1.
savr::TransferFunctionTable LevelsTable(const savr::SampleEncoding& e)
{
  using CS = savr::ComponentSampler;
  savr::TransferFunctionTable table = Table(e, 4);
  savr::TransferFunctionTable::ComponentLevels l;
  l.Count = 4;
  l.Independent = true;
  l.PairLevels = CS::kFirstLevels;
  l.PairCodes = CS::kPairCodes;
  for (int c = 0; c < 4; ++c)
  {
    l.LevelCount[c] = c % 2 == 0 ? CS::kFirstLevels : CS::kSecondLevels;
    l.RGBA[c].assign(4 * CS::kFirstLevels, 0.0f);
    l.Medium[c].assign(4 * CS::kFirstLevels, 0.0f);
    for (int q = 0; q < l.LevelCount[c]; ++q)
    {
      const double f = q / (l.LevelCount[c] - 1.0);
      const double sigma = ComponentSigma(c, f);
      const Eigen::Array3d rgb = ComponentColor(c, f);
      const double a = -std::expm1(-sigma);
      for (int i = 0; i < 3; ++i)
      {
        l.RGBA[c][4 * q + i] = static_cast<float>(a * rgb[i]);
        l.Medium[c][4 * q + 1 + i] = static_cast<float>(rgb[i]);
      }
      l.RGBA[c][4 * q + 3] = static_cast<float>(a);
      l.Medium[c][4 * q] = static_cast<float>(sigma);
    }
  }
  table.SetComponentLevels(std::move(l));
  return table;
}

// Gradient-opacity factors per component: 1 for all but `hidden`, whose opacity falls to 0
// with its gradient's magnitude code (-1: none hidden).
savr::GradientOpacityTable ComponentGradientOpacity(int hidden)
{
  std::vector<double> factors(4 * 256, 1.0);
  if (hidden >= 0)
  {
    for (int m = 0; m < 256; ++m)
    {
      factors[256 * hidden + m] = std::max(0.0, 1.0 - m / 40.0);
    }
  }
  const double scales[4] = { 40.0, 40.0, 20.0, 60.0 };
  savr::GradientOpacityTable table;
  table.Build(factors.data(), scales, 4);
  return table;
}

// A light and four sets of coefficients, one per component.
savr::ShadingTable FourCoefficientShading()
{
  std::vector<savr::Light> lights(1);
  lights[0].Direction = Eigen::Vector3d(0.3, 0.5, 1.0).normalized();
  savr::ShadingTable shading;
  shading.Build(lights, Eigen::Vector3d::UnitZ(),
    { { 0.2, 0.7, 0.3, 12.0 }, { 0.5, 0.3, 0.1, 1.0 }, { 0.1, 0.9, 0.4, 10.0 },
      { 0.3, 0.6, 0.2, 5.0 } },
    false);
  return shading;
}
} // namespace

// Each component's own gradient (ComponentSampler::ComponentGradientsAlongRay), in its place
// among the twelve floats of a sample, as that component's sampler gives it.
TEST(Components, EachComponentsOwnGradient)
{
  FourFields fields;
  auto sampler = fields.Sampler(4, savr::ComponentSampler::kAllGradients);
  sampler->PrepareGradients();

  const savr::Ray ray{ Eigen::Vector3d(-2.0, 0.1, 0.2),
    Eigen::Vector3d(1.0, 0.05, 0.02).normalized() };
  const int n = 30;
  std::vector<float> values(n);
  sampler->SampleRay(ray, 1.2, 0.05, n, values.data());
  std::vector<float> all(12 * n, -1.0f);
  sampler->ComponentGradientsAlongRay(ray, 1.2, 0.05, 0, n - 1, values.data(), all.data());
  double largest = 0.0;
  for (int c = 0; c < 4; ++c)
  {
    std::vector<float> own(3 * n);
    std::vector<float> ownValues(n);
    fields.Grids[c]->Sampler()->SampleRayGradients(ray, 1.2, 0.05, n, ownValues.data(), own.data());
    for (int i = 0; i < n; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(all[3 * (4 * i + c) + k], own[3 * i + k]) << "component " << c << " sample " << i;
        largest = std::max(largest, std::abs(static_cast<double>(own[3 * i + k])));
      }
    }
  }
  EXPECT_GT(largest, 0.1) << "the fields vary along the ray";
}

// One sample of four independent components by hand: each lit by its own normal with its own
// coefficients, the third's opacity scaled by its gradient opacity before its extinction.
TEST(Components, OneSampleLitAndThinnedPerComponent)
{
  const savr::ShadingTable shading = FourCoefficientShading();
  const savr::GradientOpacityTable thinned = ComponentGradientOpacity(2);
  savr::SampleEncoding encoding;
  encoding.Levels = 65535;
  const auto tf = LevelsTable(encoding);
  savr::AlphaCache cache;
  cache.Prepare(tf, 0.5, 1.0);
  const std::uint32_t q[4] = { 180, 70, 128, 215 };
  const std::uint16_t normals[4] = { 1000, 20000, 40000, 60000 };
  const std::uint32_t magnitudes[4] = { 0, 0, 10, 0 };
  std::uint64_t normalCodes = 0;
  std::uint32_t magnitudeCodes = 0;
  for (int c = 0; c < 4; ++c)
  {
    normalCodes |= static_cast<std::uint64_t>(normals[c]) << (16 * c);
    magnitudeCodes |= magnitudes[c] << (8 * c);
  }
  const savr::SampleAttributes attributes = savr::WithComponentNormals(normalCodes) |
                                            savr::WithComponentMagnitudes(magnitudeCodes) |
                                            savr::SampleAttributes(q[2] + 256 * q[3]) << 16;
  auto feed = [&](auto& stream)
  {
    stream.Push(0.5, q[0] + 256 * q[1], attributes);
    stream.Finish(1.0);
  };
  const savr::Pixel p =
    savr::BlendSamples(feed, tf, cache, savr::BlendMode::Composite, 0.0, &shading, &thinned);
  double sum = 0.0;
  double squares = 0.0;
  Eigen::Array3d emission = Eigen::Array3d::Zero();
  for (int c = 0; c < 4; ++c)
  {
    const double f = q[c] / (c % 2 == 0 ? 255.0 : 254.0);
    double sigma = ComponentSigma(c, f);
    if (c == 2)
    {
      // Opacity scaled by 1 - 10 / 40 before the extinction is derived.
      sigma = -std::log1p(-(-std::expm1(-sigma)) * 0.75);
    }
    const float* k = shading.FactorsOf(normals[c], c);
    const Eigen::Array3d rgb = ComponentColor(c, f);
    sum += sigma;
    squares += sigma * sigma;
    for (int i = 0; i < 3; ++i)
    {
      emission[i] += sigma * (rgb[i] * k[i] + k[3 + i]);
    }
  }
  const double sigma = squares / sum;
  const double alpha = -std::expm1(-sigma);
  EXPECT_NEAR(p[3], alpha, 1e-5);
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(p[i], alpha * std::min(emission[i] / sigma, 4.0), 1e-4) << "channel " << i;
  }
}

// Independent components shaded and with gradient opacity in frames: 2^m frames equal one pass
// at dt / 2^m; images do not depend on the thread count; a gradient-opacity edit re-blends to a
// fresh render's image, and shows.
TEST(Components, EachComponentLitAndThinnedByItsOwnGradient)
{
  FourFields fields;
  auto sampler = fields.Sampler(4, savr::ComponentSampler::kAllGradients);
  sampler->PrepareGradients();

  const savr::View view = View(33);
  const savr::ShadingTable shading = FourCoefficientShading();
  const savr::GradientOpacityTable none = ComponentGradientOpacity(-1);
  const savr::GradientOpacityTable thinned = ComponentGradientOpacity(2);

  const double dt = 0.2;
  const auto settingsFor = [&](int frames, int threads)
  {
    savr::FrameSettings settings;
    settings.SampleDistance = dt;
    settings.MaximumFrames = frames;
    settings.Threads = threads;
    settings.Shade = true;
    settings.ComponentNormals = true;
    settings.ComponentMagnitudes = true;
    for (int c = 0; c < 4; ++c)
    {
      settings.ComponentMagnitudeScales[c] = thinned.Scale(c);
    }
    return settings;
  };
  const auto accumulate =
    [&](savr::FrameLoop& loop, const savr::TransferFunctionTable& tf, int frames)
  {
    for (int k = 0; k < frames; ++k)
    {
      loop.AccumulateFrame(tf, savr::BlendMode::Composite);
    }
  };
  for (int m : { 0, 2 })
  {
    const int frames = 1 << m;
    savr::FrameLoop accumulated;
    accumulated.SetShading(&shading);
    accumulated.SetGradientOpacity(&thinned);
    accumulated.Reset(view, sampler, settingsFor(frames, 0));
    const auto tf = LevelsTable(accumulated.Encoding());
    accumulate(accumulated, tf, frames);
    savr::FrameLoop single;
    single.SetShading(&shading);
    single.SetGradientOpacity(&thinned);
    single.Reset(view, sampler, settingsFor(frames, 0));
    single.RenderSinglePass(tf, savr::BlendMode::Composite, dt / frames, 0.0);
    EXPECT_GT(MaxValue(single.Image()), 0.2) << "the scene must not be blank";
    EXPECT_LT(MaxAbsDifference(accumulated.Image(), single.Image()), 1e-5) << "m=" << m;
  }

  std::vector<std::vector<float>> images;
  for (int threads : { 1, 3, 8 })
  {
    savr::FrameLoop loop;
    loop.SetShading(&shading);
    loop.SetGradientOpacity(&none);
    loop.Reset(view, sampler, settingsFor(4, threads));
    const auto tf = LevelsTable(loop.Encoding());
    accumulate(loop, tf, 4);
    images.push_back(loop.Image());
    if (threads == 1)
    {
      // Ten bytes per sample besides the 2-byte codes and second codes: four normals, four
      // magnitudes.
      EXPECT_EQ(loop.MemoryInUse(), (2 + 2 + 8 + 4) * 4 * loop.SamplesPerFrame());
      loop.SetGradientOpacity(&thinned);
      loop.Reblend(tf, savr::BlendMode::Composite);
      savr::FrameLoop fresh;
      fresh.SetShading(&shading);
      fresh.SetGradientOpacity(&thinned);
      fresh.Reset(view, sampler, settingsFor(4, threads));
      accumulate(fresh, tf, 4);
      EXPECT_EQ(0, std::memcmp(loop.Image().data(), fresh.Image().data(),
                     loop.Image().size() * sizeof(float)));
      EXPECT_GT(MaxAbsDifference(loop.Image(), images.back()), 1e-2) << "the third thins";
    }
  }
  EXPECT_GT(MaxValue(images[0]), 0.2);
  for (std::size_t i = 1; i < images.size(); ++i)
  {
    EXPECT_EQ(0, std::memcmp(images[i].data(), images[0].data(), images[0].size() * sizeof(float)));
  }
}

#pragma once
// Blends one ray's depth-ordered stored samples through a transfer function. Every sample stands
// for the interval between the midpoints to its neighbours (clipped at ray entry and exit), so the
// quadrature is second order and uneven gaps (frame counts that are not powers of two) are exact.

#include "blend/BlendTypes.h"
#include "blend/ProjectionBlends.h"
#include "blend/ShadingTable.h"
#include "blend/TransferFunctionTable.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <vector>

namespace savr
{
namespace detail
{

// Lit selects the shaded and gradient-opacity path at compile time, so that the plain path
// carries no per-sample test for them.
template <bool Lit>
struct CompositeBlendT
{
  const TransferFunctionTable& TF;
  const AlphaCache& Cache;
  double Termination;                          // stop below this transmittance
  const ShadingTable* Shading;                 // null: unshaded
  const GradientOpacityTable* GradientOpacity; // null: none
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();

  bool Add(std::uint32_t code, double h, SampleAttributes attributes)
  {
    if (Lit && (this->Shading || this->GradientOpacity) && this->TF.HasComponentLevels() &&
        this->TF.GetComponentLevels().Independent)
    {
      return this->AddComponents(code, h, attributes);
    }
    if (Lit && this->TF.HasComponentTerms())
    {
      // Several components: the value code and the second code together make the sample's
      // extinction and colour.
      Eigen::Array3d mixed;
      const double sigma = this->TF.Combined(code, SecondCodeOf(attributes), mixed);
      if (sigma == 0.0)
      {
        return true;
      }
      const double a = composite::IntervalOpacity(sigma, h);
      if (this->Shading)
      {
        const float rgb[3] = { static_cast<float>(mixed[0]), static_cast<float>(mixed[1]),
          static_cast<float>(mixed[2]) };
        mixed = this->Shading->Shade(rgb, NormalOf(attributes));
      }
      composite::Over(this->C, this->T, a, mixed);
      return this->T >= this->Termination;
    }
    if (this->TF.Extinction(code) == 0.0)
    {
      return true; // transparent: nothing to add, nothing absorbed
    }
    const float* rgb = this->TF.Color(code);
    double a;
    if (Lit)
    {
      a = this->GradientOpacity
            ? this->GradientOpacity->IntervalAlpha(this->TF, code, MagnitudeOf(attributes), h)
            : this->Cache.Alpha(this->TF, code, h);
      composite::Over(this->C, this->T, a,
        this->Shading ? this->Shading->Shade(rgb, NormalOf(attributes))
                      : Eigen::Array3d(rgb[0], rgb[1], rgb[2]));
    }
    else
    {
      a = this->Cache.Alpha(this->TF, code, h);
      composite::Over(this->C, this->T, a, Eigen::Array3d(rgb[0], rgb[1], rgb[2]));
    }
    return this->T >= this->Termination;
  }
  // Independent components shaded or with gradient opacity: each component's opacity scaled by
  // its gradient opacity at its own gradient's magnitude, its emission lit with its own
  // coefficients (ShadingTable's sets), the extinctions combined as in
  // TransferFunctionTable::Combined.
  bool AddComponents(std::uint32_t code, double h, SampleAttributes attributes)
  {
    const TransferFunctionTable::ComponentLevels& levels = this->TF.GetComponentLevels();
    std::uint32_t q[4];
    if (!levels.Unpack(code, SecondCodeOf(attributes), q))
    {
      return true; // a component without a level (not finite)
    }
    // One normal for all, or each component's own.
    const std::uint16_t normal = NormalOf(attributes);
    const bool own = normal == kComponentNormals;
    const int sets = this->Shading ? this->Shading->Components() : 1;
    const int factors = this->GradientOpacity ? this->GradientOpacity->Sets() : 0;
    double sum = 0.0;
    double squares = 0.0;
    Eigen::Array3d emission = Eigen::Array3d::Zero();
    for (int c = 0; c < levels.Count; ++c)
    {
      const float* m = &levels.Medium[c][4 * static_cast<std::size_t>(q[c])];
      const double sigma =
        c < factors ? levels.ScaledExtinction(c, q[c],
                        this->GradientOpacity->Factor(c, ComponentMagnitudeOf(attributes, c)))
                    : m[0];
      if (sigma == 0.0)
      {
        continue;
      }
      sum += sigma;
      squares += sigma * sigma;
      if (this->Shading)
      {
        emission +=
          sigma * composite::Shaded(
                    m + 1, this->Shading->FactorsOf(own ? ComponentNormalOf(attributes, c) : normal,
                             std::min(c, sets - 1)));
      }
      else
      {
        for (int i = 0; i < 3; ++i)
        {
          emission[i] += sigma * m[1 + i];
        }
      }
    }
    if (!(sum > 0.0))
    {
      return true;
    }
    const double sigma = squares / sum;
    composite::Over(
      this->C, this->T, composite::IntervalOpacity(sigma, h), (emission / sigma).min(4.0));
    return this->T >= this->Termination;
  }

  Pixel Result() const { return composite::FrontToBack(this->C, this->T); }
};

// Composite over the segments between consecutive samples (and the constant pieces from the
// ray entry to the first sample and from the last sample to the exit), each pre-integrated.
struct PreIntegratedBlend
{
  const TransferFunctionTable& TF;
  double Termination;
  const ShadingTable* Shading; // null: unshaded; a segment is lit with its front sample's normal
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();
  bool HavePrev = false;
  double PrevPos = 0.0;
  std::uint32_t PrevCode = 0;
  SampleAttributes PrevNormal = kNoNormal;
  std::uint32_t NaNCode = 0;
  bool HasNaN = false;

  bool IsNaN(std::uint32_t code) const { return this->HasNaN && code == this->NaNCode; }

  bool Composite(std::uint32_t front, std::uint32_t back, double length, SampleAttributes normal)
  {
    if (length <= 0.0)
    {
      return true;
    }
    // A segment with one undefined end: the defined sample holds for half of it, as in the
    // composite blend; with none, nothing.
    if (this->IsNaN(front) || this->IsNaN(back))
    {
      if (this->IsNaN(front) && this->IsNaN(back))
      {
        return true;
      }
      const std::uint32_t known = this->IsNaN(front) ? back : front;
      return this->Composite(known, known, 0.5 * length, normal);
    }
    double a = 0.0;
    Eigen::Array3d color;
    this->TF.Segment(front, back, length, a, color);
    if (this->Shading)
    {
      const float rgb[3] = { static_cast<float>(color[0]), static_cast<float>(color[1]),
        static_cast<float>(color[2]) };
      color = this->Shading->Shade(rgb, NormalOf(normal));
    }
    composite::Over(this->C, this->T, a, color);
    return this->T >= this->Termination;
  }

  // Takes samples directly (not intervals): it is its own stream.
  bool Push(double pos, std::uint32_t code, SampleAttributes normal = kNoNormal)
  {
    const bool more =
      this->HavePrev ? this->Composite(this->PrevCode, code, pos - this->PrevPos, this->PrevNormal)
                     : this->Composite(code, code, pos, normal);
    this->HavePrev = true;
    this->PrevPos = pos;
    this->PrevCode = code;
    this->PrevNormal = normal;
    return more;
  }
  void Finish(double length)
  {
    if (this->HavePrev)
    {
      this->Composite(this->PrevCode, this->PrevCode, length - this->PrevPos, this->PrevNormal);
    }
  }
  Pixel Result() const { return composite::FrontToBack(this->C, this->T); }
};

// Isosurfaces between consecutive samples: where the linear interpolation of the value between
// two samples crosses an iso value, a surface of that value's colour and opacity, lit with the
// normal interpolated between the two samples' normals. More frames, closer samples, closer
// crossings.
struct IsosurfaceBlend
{
  const TransferFunctionTable& TF;
  const IsoSurfaces& Isos;
  const ShadingTable* Shading;
  double Termination;
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();
  bool HavePrev = false;
  std::uint32_t PrevCode = 0;
  SampleAttributes PrevAttributes = kNoNormal;
  std::uint32_t NaNCode = 0;
  bool HasNaN = false;

  bool Push(double, std::uint32_t code, SampleAttributes attributes = kNoNormal)
  {
    const bool nan = this->HasNaN && code == this->NaNCode;
    bool more = true;
    if (this->HavePrev && !nan)
    {
      more = this->Cross(this->PrevCode, code, this->PrevAttributes, attributes);
    }
    this->HavePrev = !nan;
    this->PrevCode = code;
    this->PrevAttributes = attributes;
    return more;
  }
  void Finish(double) {}

  bool Cross(std::uint32_t front, std::uint32_t back, SampleAttributes frontAttributes,
    SampleAttributes backAttributes)
  {
    const double v0 = this->TF.Encoding().Decode(front);
    const double v1 = this->TF.Encoding().Decode(back);
    if (v0 == v1)
    {
      return true;
    }
    // Crossings in the order the ray meets them.
    const std::size_t n = this->Isos.Values.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::size_t i = v1 > v0 ? k : n - 1 - k;
      const double iso = this->Isos.Values[i];
      if (!((v0 < iso && iso <= v1) || (v1 < iso && iso <= v0)))
      {
        continue;
      }
      const double a = this->Isos.Opacities[i];
      Eigen::Array3d color = this->Isos.Colors[i];
      if (this->Shading)
      {
        const double f = (iso - v0) / (v1 - v0);
        const std::uint16_t n0 = NormalOf(frontAttributes);
        const std::uint16_t n1 = NormalOf(backAttributes);
        std::uint16_t normal = kNoNormal;
        if (n0 != kNoNormal && n1 != kNoNormal)
        {
          const Eigen::Vector3f mixed = (1.0f - static_cast<float>(f)) * DecodeNormal(n0) +
                                        static_cast<float>(f) * DecodeNormal(n1);
          normal = EncodeNormal(mixed.data());
        }
        else
        {
          normal = n0 != kNoNormal ? n0 : n1;
        }
        const float rgb[3] = { static_cast<float>(color[0]), static_cast<float>(color[1]),
          static_cast<float>(color[2]) };
        color = this->Shading->Shade(rgb, normal);
      }
      composite::Over(this->C, this->T, a, color);
      if (this->T < this->Termination)
      {
        return false;
      }
    }
    return true;
  }
  Pixel Result() const { return composite::FrontToBack(this->C, this->T); }
};

// The sample-centred interval rule: a sample stands for the part of its ray between the
// midpoints to its neighbours, the first sample from the ray entry (0), the last one to the exit
// (the ray's length). Samples a blend leaves out (NaN) still bound their neighbours' intervals,
// so that the part they stand for stays a gap.
struct SampleInterval
{
  static constexpr double kEntry = 0.0;

  /// Where the interval of the sample at `before` ends and that of the next, at `after`, begins.
  static double Boundary(double before, double after) { return 0.5 * (before + after); }

  /// The length of the interval of the sample at `here`, between the samples at `before` and
  /// `after` unless it is the ray's `first` or `last`, on a ray of `length`.
  static double Length(
    double before, double here, double after, bool first, bool last, double length)
  {
    const double lo = first ? kEntry : Boundary(before, here);
    const double hi = last ? length : Boundary(here, after);
    return hi - lo;
  }
};

/// Turns a depth-ordered stream of samples into (code, interval) pairs for a blend, by the
/// SampleInterval rule; `Windowed`, only the parts of the intervals inside a RayWindow.
template <typename Blend, bool Windowed = false>
class SampleStream
{
public:
  SampleStream(Blend& blend, bool skipNaN, std::uint32_t nanCode, RayWindow window = RayWindow())
    : Target(blend)
    , SkipNaN(skipNaN)
    , NaNCode(nanCode)
    , Window(window)
  {
  }

  /// Feeds the next sample; false once the blend needs no more.
  bool Push(double pos, std::uint32_t code, SampleAttributes normal = kNoNormal)
  {
    if (this->HavePrev)
    {
      const double mid = SampleInterval::Boundary(this->PrevPos, pos);
      if (!this->AddPrevious(mid))
      {
        return false;
      }
      this->Lo = mid;
      if (Windowed && this->Lo >= this->Window.End)
      {
        return false; // the rest lies past the window
      }
    }
    this->PrevPos = pos;
    this->PrevCode = code;
    this->PrevNormal = normal;
    this->HavePrev = true;
    return true;
  }

  /// Ends the ray at `length` (not needed after Push returned false).
  void Finish(double length)
  {
    if (this->HavePrev)
    {
      this->AddPrevious(length);
    }
  }

private:
  // Adds the previous sample over its interval [Lo, hi] (inside the window); false once the
  // blend needs no more.
  bool AddPrevious(double hi)
  {
    if (this->SkipNaN && this->PrevCode == this->NaNCode)
    {
      return true;
    }
    double lo = this->Lo;
    if (Windowed)
    {
      lo = std::max(lo, this->Window.Begin);
      hi = std::min(hi, this->Window.End);
      if (!(hi > lo))
      {
        return true;
      }
    }
    return this->Target.Add(this->PrevCode, hi - lo, this->PrevNormal);
  }

  Blend& Target;
  bool SkipNaN;
  std::uint32_t NaNCode;
  RayWindow Window;
  double Lo = SampleInterval::kEntry;
  double PrevPos = 0.0;
  std::uint32_t PrevCode = 0;
  SampleAttributes PrevNormal = kNoNormal;
  bool HavePrev = false;
};

/// Feeds a stored ray's valid samples to `stream` in depth order; with `Attributes`, also each
/// sample's normal and gradient-magnitude codes (the unshaded loop reads codes only).
/// From row `firstRow` (at least the layout's first row) on: the samples of earlier rows are not
/// pushed.
template <bool Attributes, typename Code, typename Stream>
void PushStoredSamples(const RayLayout<Code>& ray, Stream& stream, int firstRow = 0)
{
  for (int j = std::max(firstRow, ray.FirstRow); j < ray.SamplesPerFrame; ++j)
  {
    const std::size_t rowStart = static_cast<std::size_t>(j) * ray.Capacity;
    const Code* row = ray.Codes + rowStart;
    for (int s = 0; s < ray.Frames; ++s)
    {
      const int slot = ray.Order[s];
      const double pos = (j + ray.U[slot]) * ray.Dt;
      if (pos >= ray.Length)
      {
        break; // the remaining slots of this j lie further along
      }
      SampleAttributes attributes = kNoNormal;
      if (Attributes)
      {
        const std::size_t k = rowStart + slot;
        attributes =
          (ray.ComponentNormals ? WithComponentNormals(ray.ComponentNormals[k])
                                : SampleAttributes(ray.Normals ? ray.Normals[k] : kNoNormal)) |
          (ray.Magnitudes ? SampleAttributes(ray.Magnitudes[k]) << 16 : 0u) |
          (ray.SecondCodes ? SampleAttributes(ray.SecondCodes[k]) << 16 : 0u) |
          (ray.ComponentMagnitudes ? WithComponentMagnitudes(ray.ComponentMagnitudes[k]) : 0u);
      }
      if (!stream.Push(pos, row[slot], attributes))
      {
        return;
      }
    }
  }
  stream.Finish(ray.Length);
}

template <typename Code, typename Stream>
void StreamInDepthOrder(const RayLayout<Code>& ray, Stream& stream, int firstRow = 0)
{
  if (ray.Normals || ray.Magnitudes || ray.SecondCodes || ray.ComponentNormals ||
      ray.ComponentMagnitudes)
  {
    PushStoredSamples<true>(ray, stream, firstRow);
  }
  else
  {
    PushStoredSamples<false>(ray, stream, firstRow);
  }
}

// Feeds `blend` through a sample stream, windowed when `window` is given.
template <typename Blend, typename Feed>
void FeedStream(
  Feed& feed, Blend& blend, bool skipNaN, std::uint32_t nanCode, const RayWindow* window)
{
  if (window)
  {
    SampleStream<Blend, true> stream(blend, skipNaN, nanCode, *window);
    feed(stream);
  }
  else
  {
    SampleStream<Blend> stream(blend, skipNaN, nanCode);
    feed(stream);
  }
}

} // namespace detail

/// Blends the samples that `feed(stream)` pushes into a SampleStream (in depth order, then
/// Finish). `cache` must have been prepared for the ray's interior gaps.
/// A composite blend stops once the transmittance falls below `termination`.
/// With `window`, only that part of the ray (isosurface and pre-integrated blends: nothing; see
/// WindowedBlend).
template <typename Feed>
Pixel BlendSamples(Feed&& feed, const TransferFunctionTable& tf, const AlphaCache& cache,
  BlendMode mode, double termination, const ShadingTable* shading = nullptr,
  const GradientOpacityTable* gradientOpacity = nullptr, const IsoSurfaces* isos = nullptr,
  const RayWindow* window = nullptr)
{
  const SampleEncoding& e = tf.Encoding();
  switch (mode)
  {
    case BlendMode::Composite:
    {
      // The NaN code's table entry is transparent, so composite needs no test for it.
      if (shading || gradientOpacity || tf.HasComponentTerms())
      {
        detail::CompositeBlendT<true> b{ tf, cache, termination, shading, gradientOpacity };
        detail::FeedStream(feed, b, false, e.NaNCode, window);
        return b.Result();
      }
      detail::CompositeBlendT<false> b{ tf, cache, termination, nullptr, nullptr };
      detail::FeedStream(feed, b, false, e.NaNCode, window);
      return b.Result();
    }
    case BlendMode::Maximum:
    case BlendMode::Minimum:
    {
      if (tf.HasComponentLevels())
      {
        detail::ComponentExtremumBlend b{ tf.GetComponentLevels(), mode == BlendMode::Maximum };
        detail::FeedStream(feed, b, e.HasNaNCode, e.NaNCode, window);
        return b.Result();
      }
      detail::ExtremumBlend b{ tf, mode == BlendMode::Maximum };
      detail::FeedStream(feed, b, e.HasNaNCode, e.NaNCode, window);
      return b.Result();
    }
    case BlendMode::Average:
    case BlendMode::AverageGrey:
    {
      if (mode == BlendMode::AverageGrey && tf.HasComponentLevels())
      {
        detail::ComponentGreyBlend b{ tf.GetComponentLevels(), false };
        detail::FeedStream(feed, b, e.HasNaNCode, e.NaNCode, window);
        return b.Result();
      }
      detail::AverageBlend b{ tf, mode == BlendMode::AverageGrey };
      detail::FeedStream(feed, b, e.HasNaNCode, e.NaNCode, window);
      return b.Result();
    }
    case BlendMode::Additive:
    case BlendMode::AdditiveGrey:
    {
      if (mode == BlendMode::AdditiveGrey && tf.HasComponentLevels())
      {
        detail::ComponentGreyBlend b{ tf.GetComponentLevels(), true };
        detail::FeedStream(feed, b, e.HasNaNCode, e.NaNCode, window);
        return b.Result();
      }
      detail::AdditiveBlend b{ tf, cache, mode == BlendMode::AdditiveGrey };
      detail::FeedStream(feed, b, false, e.NaNCode, window);
      return b.Result();
    }
    case BlendMode::Isosurface:
    {
      if (!isos || isos->Values.empty() || window)
      {
        return Pixel::Zero();
      }
      detail::IsosurfaceBlend b{ tf, *isos, shading, termination };
      b.NaNCode = e.NaNCode;
      b.HasNaN = e.HasNaNCode;
      feed(b);
      return b.Result();
    }
    case BlendMode::PreIntegrated:
    {
      if (window)
      {
        return Pixel::Zero();
      }
      // Segments join consecutive samples themselves: the blend is its own stream.
      detail::PreIntegratedBlend b{ tf, termination, shading };
      b.NaNCode = e.NaNCode;
      b.HasNaN = e.HasNaNCode;
      feed(b);
      return b.Result();
    }
    case BlendMode::Slice: // one value per ray, not a stream: SinglePass::RenderSlice
      break;
  }
  return Pixel::Zero();
}

/// Blends one stored ray.
template <typename Code>
Pixel BlendRay(const RayLayout<Code>& ray, const TransferFunctionTable& tf, const AlphaCache& cache,
  BlendMode mode, double termination = kNegligibleTransmittance,
  const ShadingTable* shading = nullptr, const GradientOpacityTable* gradientOpacity = nullptr,
  const IsoSurfaces* isos = nullptr)
{
  return BlendSamples([&ray](auto& stream) { detail::StreamInDepthOrder(ray, stream); }, tf, cache,
    mode, termination, shading, gradientOpacity, isos);
}

/// Whether BlendWindow can blend a part of a ray in `mode` (the blends that take intervals).
inline bool WindowedBlend(BlendMode mode)
{
  return mode != BlendMode::Isosurface && mode != BlendMode::PreIntegrated &&
         mode != BlendMode::Slice;
}

/// Blends the part `window` of one stored ray (see WindowedBlend for the modes), reading only
/// the rows that can reach into it.
template <typename Code>
Pixel BlendWindow(const RayLayout<Code>& ray, const RayWindow& window,
  const TransferFunctionTable& tf, const AlphaCache& cache, BlendMode mode,
  double termination = kNegligibleTransmittance, const ShadingTable* shading = nullptr,
  const GradientOpacityTable* gradientOpacity = nullptr)
{
  if (!(window.End > window.Begin) || window.End <= 0.0 || window.Begin >= ray.Length)
  {
    return Pixel::Zero();
  }
  // The samples of rows before this one end their intervals before the window begins: the
  // first one pushed may take its interval from the entry point, as the window cuts it anyway.
  const int firstRow = static_cast<int>(
    std::max(0.0, std::min(std::floor(window.Begin / ray.Dt) - 1.0, double(ray.SamplesPerFrame))));
  return BlendSamples([&](auto& stream) { detail::StreamInDepthOrder(ray, stream, firstRow); }, tf,
    cache, mode, termination, shading, gradientOpacity, nullptr, &window);
}

} // namespace savr

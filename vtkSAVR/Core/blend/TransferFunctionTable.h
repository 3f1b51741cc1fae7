#pragma once
// The transfer function tabulated per stored sample code, kept in extinction form so that opacity
// correction for any interval h is alpha = -expm1(-sigma h) without cancellation.

#include "encoding/SampleEncoding.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace savr
{

class TransferFunctionTable
{
public:
  /// `rgb` (3 per code) and `opacity` (1 per code, in [0, 1]) are the transfer function evaluated
  /// at SampleEncoding::Decode(code) for every value code. Opacity is per `unitDistance` of world
  /// space, as vtkVolumeProperty's ScalarOpacityUnitDistance. The NaN code is transparent.
  /// Colours are clamped to [0, `maxColor`]: above 1 only for media that combine several
  /// components, whose emission can exceed their absorption.
  void Build(const SampleEncoding& encoding, const double* rgb, const double* opacity,
    double unitDistance, double maxColor = 1.0);

  /// Extinction (per world unit) of a code; finite even for opacity 1.
  double Extinction(std::uint32_t code) const { return this->Sigma[code]; }
  /// Opacity of a code as the transfer function gives it, without correction.
  float Opacity(std::uint32_t code) const { return this->Alpha[code]; }
  const float* Color(std::uint32_t code) const { return &this->RGB[3 * code]; }

  /// Opacity of an interval of length h: -expm1(-sigma h), evaluated in double.
  double IntervalAlpha(std::uint32_t code, double h) const;

  /// Pre-integrated segment between consecutive samples with codes `front` and `back`, `length`
  /// apart, the value assumed to vary linearly between them: its opacity and its colour (such
  /// that the segment adds alpha * colour). Optical depth is exact; attenuation inside the
  /// segment is resolved to pieces (see kPieceDepth).
  void Segment(std::uint32_t front, std::uint32_t back, double length, double& alpha,
    Eigen::Array3d& color) const;

  /// Data with a second code per sample (Sampler::HasSecondCode): a sample's extinction and
  /// colour combine terms of its value code and of its second code, 5 per code each: S, the sum
  /// of the extinctions (per world unit) of the components the code holds; Q, the sum of their
  /// squares; E, a colour term (3). The sample's extinction is Q / S over both codes' sums, as
  /// the weighted mean of the components' extinctions. Its colour is E / (Q / S) with
  /// `emission` (E the sum of extinction times colour: independent components; this can exceed
  /// 1, up to the number of components, where a bright component meets a more absorbing one)
  /// and E without (a colour given directly: dependent components, clamped to 1). `first` has an
  /// entry per value code (Encoding().Levels), `second` one per second code; the NaN value code is
  /// transparent. Build clears the terms; set them after it.
  void SetComponentTerms(std::vector<double> first, std::vector<double> second, bool emission);
  bool HasComponentTerms() const { return !this->FirstTerms.empty(); }

  /// Extinction (per world unit) and colour of a sample with value code `code` and second code
  /// `second`, from the component terms.
  double Combined(std::uint32_t code, std::uint32_t second, Eigen::Array3d& rgb) const
  {
    if (code >= this->Code.Levels || second >= this->SecondLevels)
    {
      rgb.setZero();
      return 0.0;
    }
    const double* a = &this->FirstTerms[5 * static_cast<std::size_t>(code)];
    const double* b = &this->SecondTerms[5 * static_cast<std::size_t>(second)];
    const double sum = a[0] + b[0];
    if (!(sum > 0.0))
    {
      rgb.setZero();
      return 0.0;
    }
    const double sigma = (a[1] + b[1]) / sum;
    const double scale = this->Emission ? 1.0 / sigma : 1.0;
    const double most = this->Emission ? 4.0 : 1.0;
    for (int i = 0; i < 3; ++i)
    {
      rgb[i] = std::min((a[2 + i] + b[2 + i]) * scale, most);
    }
    return sigma;
  }

  /// Each component's colour and opacity per level, for the maximum, minimum, average and
  /// additive blends of data with several components (and the shaded composite of independent
  /// ones), which take extremes per component (independent) or the sample
  /// with the extreme last component (dependent), as VTK's GPU mapper does. A value code packs
  /// the levels of the first two components as first + PairLevels * second; a second code those
  /// of the third and fourth.
  struct ComponentLevels
  {
    int Count = 0;           // components, 2 to 4
    bool Independent = true; // else dependent: luminance-alpha or RGBA
    std::uint32_t PairLevels = 256;
    std::uint32_t PairCodes = 256 * 255; // the second of a pair has a level fewer; codes at or
                                         // above this stand for no levels (not finite)
    /// Per component, 4 per level. Independent: colour times opacity times weight, then
    /// opacity times weight (summed over the components). Dependent: the colour this component
    /// contributes and the opacity it sets (summed, then the colour scaled by the opacity).
    std::vector<float> RGBA[4];
    /// Independent components, per component, 4 per level: extinction per world unit (weighted),
    /// then colour; what a shaded composite lights each component with its own coefficients.
    std::vector<float> Medium[4];
    /// Per component: levels (256 or 255: a value normalized over the component's range is
    /// its level over levels - 1) and ScalarOpacityUnitDistance.
    int LevelCount[4] = { 256, 255, 256, 255 };
    double UnitDistance[4] = { 1.0, 1.0, 1.0, 1.0 };
    /// Per component: ComponentWeight (independent; 1 for dependent ones).
    double Weight[4] = { 1.0, 1.0, 1.0, 1.0 };

    /// Independent component c's extinction per world unit at level q (Medium's) with its
    /// opacity scaled by `factor` (its gradient opacity) before the extinction is derived.
    double ScaledExtinction(int c, std::uint32_t q, double factor) const
    {
      const double sigma = this->Medium[c][4 * static_cast<std::size_t>(q)];
      if (factor >= 1.0 || sigma == 0.0)
      {
        return sigma;
      }
      const double a =
        this->RGBA[c][4 * static_cast<std::size_t>(q) + 3] / this->Weight[c] * factor;
      // Opacity 1 is opaque: a large finite extinction, as Medium's.
      return this->Weight[c] * (a < 1.0 ? -std::log1p(-a) : 745.0) / this->UnitDistance[c];
    }

    /// The components' levels of a sample with value code `code` and second code `second`;
    /// false when a component has none (not finite).
    bool Unpack(std::uint32_t code, std::uint32_t second, std::uint32_t q[4]) const
    {
      if (code >= this->PairCodes || (this->Count > 2 && second >= this->PairCodes))
      {
        return false;
      }
      q[0] = code % this->PairLevels;
      q[1] = code / this->PairLevels;
      q[2] = second % this->PairLevels;
      q[3] = second / this->PairLevels;
      return true;
    }
  };
  void SetComponentLevels(ComponentLevels levels);
  const ComponentLevels& GetComponentLevels() const { return this->Levels; }
  bool HasComponentLevels() const { return this->Levels.Count > 1; }

  /// Opacity unit distance the table was built with.
  double UnitDistance() const { return this->Unit; }

  std::uint32_t Size() const { return static_cast<std::uint32_t>(this->Alpha.size()); }
  const SampleEncoding& Encoding() const { return this->Code; }
  /// Changes on every Build, so that tables derived from this one know when to rebuild.
  std::uint64_t Generation() const { return this->Built; }

  /// Opacity 1 maps to this optical depth per unit distance, so that full opacity stays finite.
  static constexpr double kMaxOpticalDepth = 1000.0;
  /// Pieces a pre-integrated segment is composited in, at most, and the mean optical depth of
  /// a piece below which fewer are taken.
  static constexpr int kSegmentPieces = 16;
  static constexpr double kPieceDepth = 0.02;

private:
  SampleEncoding Code;
  std::vector<float> RGB;
  std::vector<float> Alpha;
  std::vector<double> Sigma;
  // Integrals over the value, from code 0, of the extinction and of extinction times colour
  // (trapezoids between codes): what pre-integration needs.
  std::vector<double> SigmaIntegral;
  std::vector<double> EmissionIntegral; // 3 per code
  std::uint64_t Built = 0;
  double Unit = 1.0;
  std::vector<double> FirstTerms;  // 5 per value code, when the data has second codes
  std::vector<double> SecondTerms; // 5 per second code
  std::uint32_t SecondLevels = 0;
  bool Emission = true;
  ComponentLevels Levels;
};

} // namespace savr

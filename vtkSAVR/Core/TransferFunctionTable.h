#pragma once
// The transfer function tabulated per stored sample code, kept in extinction form so that opacity
// correction for any interval h is alpha = -expm1(-sigma h) without cancellation.

#include "SampleEncoding.h"

#include <Eigen/Core>

#include <vector>

namespace savr
{

class TransferFunctionTable
{
public:
  /// `rgb` (3 per code) and `opacity` (1 per code, in [0, 1]) are the transfer function evaluated
  /// at SampleEncoding::Decode(code) for every value code. Opacity is per `unitDistance` of world
  /// space, as vtkVolumeProperty's ScalarOpacityUnitDistance. The NaN code is transparent.
  void Build(
    const SampleEncoding& encoding, const double* rgb, const double* opacity, double unitDistance);

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
  /// segment is resolved to kSegmentPieces pieces.
  void Segment(std::uint32_t front, std::uint32_t back, double length, double& alpha,
    Eigen::Array3d& color) const;

  /// Opacity unit distance the table was built with.
  double UnitDistance() const { return this->Unit; }

  std::uint32_t Size() const { return static_cast<std::uint32_t>(this->Alpha.size()); }
  const SampleEncoding& Encoding() const { return this->Code; }
  /// Changes on every Build, so that tables derived from this one know when to rebuild.
  std::uint64_t Generation() const { return this->Built; }

  /// Opacity 1 maps to this optical depth per unit distance, so that full opacity stays finite.
  static constexpr double kMaxOpticalDepth = 1000.0;
  /// Pieces a pre-integrated segment is composited in, at most.
  static constexpr int kSegmentPieces = 16;

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
};

} // namespace savr

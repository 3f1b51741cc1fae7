#pragma once
// The blends that project a ray to one value instead of compositing it: maximum and minimum
// intensity, average and additive intensity (VTK's grey or the transfer function's colours), and
// their forms for data with several components.

#include "blend/BlendTypes.h"
#include "blend/ShadingTable.h"

#include <algorithm>

namespace savr
{
namespace detail
{

struct ExtremumBlend
{
  const TransferFunctionTable& TF;
  bool Maximum;
  bool Found = false;
  std::uint32_t Best = 0;

  bool Add(std::uint32_t code, double, SampleAttributes)
  {
    if (!this->Found || (this->Maximum ? code > this->Best : code < this->Best))
    {
      this->Best = code;
      this->Found = true;
    }
    return true;
  }
  Pixel Result() const;
};

// Several components (TransferFunctionTable::ComponentLevels): each component's own extreme
// level (independent), or the levels of the sample whose last component is extreme (dependent).
struct ComponentExtremumBlend
{
  const TransferFunctionTable::ComponentLevels& Levels;
  bool Maximum;
  bool Found = false;
  std::uint32_t Best[4] = { 0, 0, 0, 0 };

  bool Add(std::uint32_t code, double, SampleAttributes attributes)
  {
    std::uint32_t q[4];
    if (!this->Levels.Unpack(code, SecondCodeOf(attributes), q))
    {
      return true; // a component without a level (not finite)
    }
    const auto better = [this](std::uint32_t candidate, std::uint32_t best)
    { return this->Maximum ? candidate > best : candidate < best; };
    const int n = this->Levels.Count;
    if (!this->Levels.Independent)
    {
      if (!this->Found || better(q[n - 1], this->Best[n - 1]))
      {
        std::copy(q, q + n, this->Best);
      }
    }
    else
    {
      for (int c = 0; c < n; ++c)
      {
        if (!this->Found || better(q[c], this->Best[c]))
        {
          this->Best[c] = q[c];
        }
      }
    }
    this->Found = true;
    return true;
  }
  Pixel Result() const;
};

// Average and additive grey of several components (TransferFunctionTable::ComponentLevels), as
// VTK's GPU mapper draws them: per sample, independent components add their weighted opacity
// times their normalized value (additive: the opacity per unit distance); dependent ones take
// the opacity (from the last component) times the first component's normalized value.
struct ComponentGreyBlend
{
  const TransferFunctionTable::ComponentLevels& Levels;
  bool Additive;
  double Sum = 0.0;
  double Length = 0.0;

  bool Add(std::uint32_t code, double h, SampleAttributes attributes)
  {
    std::uint32_t q[4];
    if (!this->Levels.Unpack(code, SecondCodeOf(attributes), q))
    {
      return true; // a component without a level (not finite)
    }
    const auto normalized = [this, &q](int c) { return q[c] / (this->Levels.LevelCount[c] - 1.0); };
    const auto opacity = [this, &q](int c) { return this->Levels.RGBA[c][4 * q[c] + 3]; };
    const int n = this->Levels.Count;
    double grey = 0.0;
    if (this->Levels.Independent)
    {
      for (int c = 0; c < n; ++c)
      {
        grey += opacity(c) * normalized(c) / (this->Additive ? this->Levels.UnitDistance[c] : 1.0);
      }
    }
    else
    {
      grey = opacity(n - 1) * normalized(0) / (this->Additive ? this->Levels.UnitDistance[0] : 1.0);
    }
    this->Sum += grey * h;
    this->Length += h;
    return true;
  }
  Pixel Result() const
  {
    if (!(this->Length > 0.0))
    {
      return Pixel::Zero();
    }
    const double value = this->Additive ? this->Sum : this->Sum / this->Length;
    const float grey = static_cast<float>(std::min(std::max(value, 0.0), 1.0));
    return Pixel(grey, grey, grey, 1.0f);
  }
};

struct AverageBlend
{
  const TransferFunctionTable& TF;
  bool Grey = false; // BlendMode::AverageGrey
  double Sum = 0.0;
  double Length = 0.0;
  // Grey: a code's value normalized over the codes' range (codes are levels spread evenly
  // over it) is code times this.
  double PerCode = 0.0;

  AverageBlend(const TransferFunctionTable& tf, bool grey)
    : TF(tf)
    , Grey(grey)
    , PerCode(tf.Encoding().Levels > 1 ? 1.0 / (tf.Encoding().Levels - 1) : 0.0)
  {
  }

  bool Add(std::uint32_t code, double h, SampleAttributes)
  {
    if (this->Grey)
    {
      this->Sum += this->TF.Opacity(code) * (code * this->PerCode) * h;
    }
    else
    {
      this->Sum += this->TF.Encoding().Decode(code) * h;
    }
    this->Length += h;
    return true;
  }
  Pixel Result() const;
};

struct AdditiveBlend
{
  const TransferFunctionTable& TF;
  const AlphaCache& Cache;
  bool Grey = false; // BlendMode::AdditiveGrey
  Eigen::Array4d Sum = Eigen::Array4d::Zero();
  double Length = 0.0;

  bool Add(std::uint32_t code, double h, SampleAttributes)
  {
    if (this->Grey)
    {
      // As AverageBlend's grey: a code's normalized value is its fraction of the codes.
      const double levels = this->TF.Encoding().Levels > 1 ? this->TF.Encoding().Levels - 1 : 1;
      this->Sum[0] += this->TF.Opacity(code) * (code / levels) * h / this->TF.UnitDistance();
      this->Length += h;
      return true;
    }
    const double a = this->Cache.Alpha(this->TF, code, h);
    const float* rgb = this->TF.Color(code);
    this->Sum += a * Eigen::Array4d(rgb[0], rgb[1], rgb[2], 1.0);
    return true;
  }
  Pixel Result() const
  {
    if (this->Grey)
    {
      const float grey = static_cast<float>(std::min(std::max(this->Sum[0], 0.0), 1.0));
      return this->Length > 0.0 ? Pixel(grey, grey, grey, 1.0f) : Pixel::Zero();
    }
    return this->Sum.min(1.0).cast<float>();
  }
};

} // namespace detail
} // namespace savr

#include "blend/Integrator.h"

#include <algorithm>

namespace savr
{

void AlphaCache::Prepare(
  const TransferFunctionTable& table, double smallStep, double largeStep, double middleStep)
{
  const double steps[3] = { smallStep, largeStep, middleStep };
  const bool sameTable = this->Generation == table.Generation();
  this->Generation = table.Generation();
  for (int i = 0; i < 3; ++i)
  {
    if (sameTable && this->Step[i] == steps[i])
    {
      continue;
    }
    if (i == 2 && !(middleStep > 0.0))
    {
      this->Step[2] = largeStep;
      std::vector<double>().swap(this->Table[2]);
      continue;
    }
    this->Step[i] = steps[i];
    this->Table[i].resize(table.Size());
    for (std::uint32_t c = 0; c < table.Size(); ++c)
    {
      this->Table[i][c] = table.IntervalAlpha(c, steps[i]);
    }
  }
}

namespace detail
{

namespace
{
Pixel ColorOf(const TransferFunctionTable& tf, std::uint32_t code)
{
  const float* rgb = tf.Color(code);
  const float a = tf.Opacity(code);
  Pixel p;
  p << rgb[0] * a, rgb[1] * a, rgb[2] * a, a;
  return p;
}
} // namespace

Pixel ExtremumBlend::Result() const
{
  return this->Found ? ColorOf(this->TF, this->Best) : Pixel::Zero();
}

Pixel ComponentExtremumBlend::Result() const
{
  if (!this->Found)
  {
    return Pixel::Zero();
  }
  Eigen::Array4f sum = Eigen::Array4f::Zero();
  for (int c = 0; c < this->Levels.Count; ++c)
  {
    sum += Eigen::Map<const Eigen::Array4f>(&this->Levels.RGBA[c][4 * this->Best[c]]);
  }
  if (!this->Levels.Independent)
  {
    sum.head<3>() *= sum[3];
  }
  return sum.min(1.0f);
}

Pixel AverageBlend::Result() const
{
  if (!(this->Length > 0.0))
  {
    return Pixel::Zero();
  }
  if (this->Grey)
  {
    const float grey = static_cast<float>(std::min(std::max(this->Sum / this->Length, 0.0), 1.0));
    return Pixel(grey, grey, grey, 1.0f);
  }
  const float mean = static_cast<float>(this->Sum / this->Length);
  return ColorOf(this->TF, this->TF.Encoding().Encode(mean));
}

} // namespace detail
} // namespace savr

// The single pass (see SinglePass.h): a lean loop for the plain composite, the blends of
// Integrator.h fed a chunk at a time otherwise.

#include "frame/SinglePass.h"

#include "blend/PlainComposite.h"
#include "encoding/EncodeAVX2.h"
#include "frame/PassScratch.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

namespace savr
{

namespace
{
// Samples taken at once by a single pass, which stops sampling a ray once it is opaque.
constexpr int kChunk = 64;

// The pixel whose ray stands for `pixel`'s block of `stride` x `stride` pixels: the block's
// middle, kept below the tile's end (x1, y1) (tiles start at multiples of the stride).
int BlockPixel(int width, int stride, int x1, int y1, int pixel)
{
  const int px = pixel % width;
  const int py = pixel / width;
  const int x = std::min(px - px % stride + stride / 2, x1 - 1);
  const int y = std::min(py - py % stride + stride / 2, y1 - 1);
  return x + width * y;
}

// With a stride above 1, the tile's `rays` of one pixel per block (BlockPixel); else none.
template <typename Rays>
Rays BlockRays(const Rays& rays, int width, int stride, int x1, int y1)
{
  Rays kept;
  if (stride <= 1)
  {
    return kept;
  }
  for (const auto& ray : rays)
  {
    if (ray.Pixel == BlockPixel(width, stride, x1, y1, ray.Pixel))
    {
      kept.push_back(ray);
    }
  }
  return kept;
}

// Gives the pixel of each of a tile's `rays` its block's colour (zero where the block's own
// pixel has no ray: pixels without rays are never written).
template <typename Rays>
void FillBlocks(const Rays& rays, int width, int stride, int x1, int y1, float* pixels)
{
  if (stride <= 1)
  {
    return;
  }
  for (const auto& ray : rays)
  {
    const std::size_t from =
      4 * static_cast<std::size_t>(BlockPixel(width, stride, x1, y1, ray.Pixel));
    std::copy(pixels + from, pixels + from + 4, pixels + 4 * static_cast<std::size_t>(ray.Pixel));
  }
}

// The samples a plain pass takes first on a ray, from its first sample outside a skipped block:
// about as many as the most opaque code needs to bring the ray to `termination` (a quarter
// chunk at least, a chunk at most), so that a ray that soon turns opaque takes few samples past
// its end and a clear one is taken in few pieces. `premultiplied`: PremultipliedTable.
int FirstPiece(const std::vector<double>& premultiplied, double termination)
{
  double most = 0.0;
  for (std::size_t k = 0; k < premultiplied.size(); k += 4)
  {
    most = std::max(most, premultiplied[k]);
  }
  if (!(termination > 0.0 && termination < 1.0) || !(most > 0.0))
  {
    return kChunk; // rays never stop early
  }
  const double samples = most < 1.0 ? std::log(termination) / std::log1p(-most) : 1.0;
  int piece = kChunk / 4;
  while (piece < kChunk && piece < samples)
  {
    piece *= 2;
  }
  return piece;
}

// What every plain ray of a pass shares (see PlainRay).
struct PlainPass
{
  const Sampler& Source;
  const SampleEncoding& Encoding;
  const TransferFunctionTable& TF;
  const AlphaCache& Alphas;
  double Step;
  double Termination;
  const SkipMask* Skip;
  std::uint32_t NaNCode;
  const double* Premultiplied; // PremultipliedTable for the step
  int FirstPiece;
};

// A single composite pass's ray without lighting, gradient opacity or second codes: samples
// `step` apart from u * step on, blended as SampleStream feeds CompositeBlendT<false> (intervals
// by the SampleInterval rule), but with no per-sample bookkeeping: interior intervals are one
// step, so an interior sample costs a lookup and a composite without branches (a transparent one
// adds zeros, changing no bit). Sampled a piece at a time (Next, then Take), so that a ray stops
// sampling once it is opaque, and so that two rays' pieces can be sampled together.
class PlainRay
{
public:
  PlainRay(const PlainPass& pass, const Ray& r, double tEnter, double length, double u, int n)
    : Pass(pass)
    , R(r)
    , TEnter(tEnter)
    , Length(length)
    , U(u)
    , Grown(pass.FirstPiece)
  {
    // The last sample inside the ray.
    this->Last = n - 1;
    while (this->Last >= 0 && !(this->Pos(this->Last) < length))
    {
      --this->Last;
    }
    // Samples in skipped blocks add nothing when NaN is transparent: start at the first other.
    if (pass.Skip && pass.TF.Extinction(pass.NaNCode) == 0.0)
    {
      this->J0 =
        pass.Source.FirstUnskipped(r, tEnter + u * pass.Step, pass.Step, this->Last + 1, pass.Skip);
    }
  }

  /// The next piece to sample: `piece`'s ray, start and count (its Out is the caller's); false
  /// when the ray is done.
  bool Next(Sampler::RayPiece& piece)
  {
    if (this->Done || this->J0 > this->Last)
    {
      this->Done = true;
      return false;
    }
    // Growing pieces while the ray stays clear (see FirstPiece); shorter ones as it nears its
    // end, so that few samples are taken past it.
    const double T = this->T;
    const int size = T > 0.5 ? this->Grown : (T > 0.1 ? kChunk / 2 : kChunk / 4);
    this->Grown = std::min(2 * this->Grown, kChunk);
    this->Count = std::min(size, this->Last + 1 - this->J0);
    piece.R = &this->R;
    piece.T0 = this->TEnter + (this->J0 + this->U) * this->Pass.Step;
    piece.Count = this->Count;
    return true;
  }

  /// Blends the piece Next gave, sampled into `values` (`codes`: room for as many).
  void Take(const float* values, std::uint32_t* codes)
  {
    this->Done = this->Blend(values, codes);
    this->J0 += this->Count;
  }

  Pixel Result() const { return composite::FrontToBack(this->C, this->T); }

private:
  double Pos(int k) const { return (k + this->U) * this->Pass.Step; }

  // Returns whether the ray reached the termination transmittance.
  bool Blend(const float* values, std::uint32_t* codes)
  {
    const PlainPass& pass = this->Pass;
    const int j0 = this->J0;
    const int count = this->Count;
    const int last = this->Last;
    // The codes of the piece: as Encode gives them, NaN as nanCode.
    if (detail::HaveAVX2())
    {
      const std::uint32_t infiniteCode = pass.Encoding.HasNaNCode ? pass.Encoding.NaNCode : 0u;
      if (!detail::EncodeAVX2(pass.Encoding.Offset, pass.Encoding.Scale, pass.Encoding.Levels,
            infiniteCode, pass.NaNCode, values, count, codes) &&
          pass.TF.Extinction(pass.NaNCode) == 0.0)
      {
        return false; // all skipped or outside: nothing to add
      }
    }
    else
    {
      for (int i = 0; i < count; ++i)
      {
        const float v = values[i];
        codes[i] = v == v ? pass.Encoding.Encode(v) : pass.NaNCode;
      }
    }
    Eigen::Array3d C = this->C;
    double T = this->T;
    bool stopped = false;
    // Interior samples (not the first or last of the ray) in a tight loop.
    const int interiorBegin = j0 == 0 ? 1 : 0;
    const int interiorEnd = std::max(interiorBegin, std::min(count, last - j0));
    for (int i = 0; i < count && !stopped; ++i)
    {
      if (i == interiorBegin)
      {
        for (; i < interiorEnd; ++i)
        {
          // One step: the opacity and the colour times it, tabulated.
          const double* entry = pass.Premultiplied + 4 * static_cast<std::size_t>(codes[i]);
          detail::CompositeEntry(entry, C, T);
          if (T < pass.Termination)
          {
            stopped = true;
            break;
          }
        }
        if (stopped || i >= count)
        {
          break;
        }
      }
      const std::uint32_t code = codes[i];
      const int k = j0 + i;
      if (pass.TF.Extinction(code) == 0.0)
      {
        continue;
      }
      const double h = detail::SampleInterval::Length(
        this->Pos(k - 1), this->Pos(k), this->Pos(k + 1), k == 0, k == last, this->Length);
      const double a = pass.Alphas.Alpha(pass.TF, code, h);
      const float* rgb = pass.TF.Color(code);
      composite::Over(C, T, a, Eigen::Array3d(rgb[0], rgb[1], rgb[2]));
      stopped = T < pass.Termination;
    }
    this->C = C;
    this->T = T;
    return stopped;
  }

  const PlainPass& Pass;
  const Ray R;
  const double TEnter;
  const double Length;
  const double U;
  int Last = -1;
  int J0 = 0;    // the next piece's first sample
  int Count = 0; // the piece Next gave
  int Grown;
  bool Done = false;
  double T = 1.0;
  Eigen::Array3d C = Eigen::Array3d::Zero();
};

// One plain ray's pixel. Adds the samples taken to `taken`.
Pixel PlainComposite(const PlainPass& pass, PlainRay& ray, std::vector<float>& values,
  std::vector<std::uint32_t>& codes, std::uint64_t& taken)
{
  Sampler::RayPiece piece;
  while (ray.Next(piece))
  {
    pass.Source.SampleRay(*piece.R, piece.T0, pass.Step, piece.Count, values.data(), pass.Skip);
    taken += piece.Count;
    ray.Take(values.data(), codes.data());
  }
  return ray.Result();
}

// Plain rays (`n`, at most Sampler::kMostPieces), their pieces sampled together while they go on
// (Sampler::SampleRays; the pass has no skip mask): the same pixels as PlainComposite on each.
// `values` holds n chunks.
void PlainCompositeGroup(const PlainPass& pass, std::optional<PlainRay>* rays, int n,
  std::vector<float>& values, std::vector<std::uint32_t>& codes, std::uint64_t& taken)
{
  Sampler::RayPiece pieces[Sampler::kMostPieces];
  int of[Sampler::kMostPieces];
  while (true)
  {
    int m = 0;
    for (int i = 0; i < n; ++i)
    {
      if (rays[i]->Next(pieces[m]))
      {
        pieces[m].Out = values.data() + static_cast<std::size_t>(m) * kChunk;
        of[m++] = i;
      }
    }
    if (m == 0)
    {
      return;
    }
    pass.Source.SampleRays(pieces, m, pass.Step);
    for (int k = 0; k < m; ++k)
    {
      taken += pieces[k].Count;
      rays[of[k]]->Take(pieces[k].Out, codes.data());
    }
  }
}

// A tile's rays (`rayOf(ray)`: its PlainRay) through the plain composite, `together` at a time
// (at most Sampler::kMostPieces); `store(ray, pixel)` keeps each pixel.
template <typename Rays, typename RayOf, typename Store>
void PlainTile(const PlainPass& pass, const Rays& rays, int together, const RayOf& rayOf,
  const Store& store, std::vector<float>& values, std::vector<std::uint32_t>& codes,
  std::uint64_t& taken)
{
  std::size_t k = 0;
  std::optional<PlainRay> group[Sampler::kMostPieces];
  for (; together > 1 && k + together <= rays.size(); k += together)
  {
    for (int i = 0; i < together; ++i)
    {
      group[i].emplace(rayOf(rays[k + i]));
    }
    PlainCompositeGroup(pass, group, together, values, codes, taken);
    for (int i = 0; i < together; ++i)
    {
      store(rays[k + i], group[i]->Result());
    }
  }
  for (; k < rays.size(); ++k)
  {
    PlainRay a = rayOf(rays[k]);
    store(rays[k], PlainComposite(pass, a, values, codes, taken));
  }
}
} // namespace

void SinglePass::RenderSlice(const TransferFunctionTable& tf)
{
  const Sampler& source = *this->State.Source;
  const SampleEncoding& encoding = this->State.Encoder;
  const View& view = this->State.CurrentViewData;
  const Eigen::Vector3d normal = this->State.Inputs.SliceNormal;
  const double offset = normal.dot(this->State.Inputs.SliceOrigin);
  // Lit by the gradient at the crossing when shading is on.
  const ShadingTable* shading = this->State.CurrentAttributes().Shading;
  if (shading)
  {
    this->State.PrepareGradients();
  }
  float* pixels = this->State.Pixels.data();
  this->State.ForEachTile(
    [&](Tile& tile, ThreadBuffers&)
    {
      for (const RayInfo& ray : tile.Rays)
      {
        float* out = pixels + 4 * static_cast<std::size_t>(ray.Pixel);
        std::fill(out, out + 4, 0.0f);
        const Ray r = view.PixelRay(ray.Pixel % view.Width, ray.Pixel / view.Width);
        // Where the ray crosses the plane: inside the ray's segment through the data, which
        // ends at opaque geometry.
        const double t = (offset - normal.dot(r.Origin)) / normal.dot(r.Direction);
        if (!(t >= ray.TEnter && t <= ray.TEnter + ray.Length))
        {
          continue; // parallel (NaN or infinite t), or outside the data
        }
        float value = 0.0f;
        source.SampleRay(r, t, 1.0, 1, &value, nullptr);
        if (!(value == value))
        {
          continue;
        }
        const std::uint32_t code = encoding.Encode(value);
        const float alpha = tf.Opacity(code);
        const float* rgb = tf.Color(code);
        Eigen::Array3d color(rgb[0], rgb[1], rgb[2]);
        if (shading)
        {
          float gradient[3];
          source.GradientAt(r, t, gradient);
          color = shading->Shade(rgb, EncodeNormal(gradient));
        }
        for (int c = 0; c < 3; ++c)
        {
          out[c] = static_cast<float>(color[c] * alpha);
        }
        out[3] = alpha;
      }
    });
}

void SinglePass::Chunk(const TransferFunctionTable& tf, BlendMode mode,
  const StoredAttributes& attributes, const Ray& r, double t0, double step, int count,
  std::uint32_t nanCode, ThreadBuffers& buffers) const
{
  const bool hasSecondCodes = this->State.Source->HasSecondCode();
  // Codes first; then the gradients of the run of samples from the first one seen to the last,
  // in one call: nothing of this pass is kept, so only what is seen needs them.
  std::uint32_t* codes = buffers.Codes.data();
  const auto seen = [&](std::uint32_t code)
  {
    return attributes.Any() &&
           (mode == BlendMode::Isosurface || hasSecondCodes || tf.Extinction(code) > 0.0);
  };
  int firstSeen = count;
  int lastSeen = -1;
  for (int i = 0; i < count; ++i)
  {
    const float v = buffers.Values[i];
    const std::uint32_t second = hasSecondCodes ? buffers.SecondCodes[i] : 0u;
    codes[i] = v == v && second != kNoSecondCode ? this->State.Encoder.Encode(v) : nanCode;
    if (seen(codes[i]))
    {
      firstSeen = std::min(firstSeen, i);
      lastSeen = i;
    }
  }
  float* gradients = buffers.Gradients.data();
  if (attributes.Normals || attributes.Magnitudes)
  {
    this->State.Source->GradientsAlongRay(
      r, t0, step, firstSeen, lastSeen, buffers.Values.data(), gradients);
  }
  const float* componentGradients = buffers.ComponentGradients.data();
  if (attributes.AnyComponents())
  {
    this->State.Source->ComponentGradientsAlongRay(
      r, t0, step, firstSeen, lastSeen, buffers.Values.data(), buffers.ComponentGradients.data());
  }
  // Normals alone: encoded four at a time (the same codes as Encode).
  const bool normalsOnly = this->State.Settings.Vectorize && detail::HaveAVX2() &&
                           attributes.Normals && !attributes.Magnitudes && firstSeen <= lastSeen;
  if (normalsOnly)
  {
    detail::EncodeNormalsAVX2(gradients + 3 * static_cast<std::size_t>(firstSeen),
      lastSeen - firstSeen + 1, buffers.Normals.data() + firstSeen);
  }
  for (int i = 0; i < count; ++i)
  {
    SampleAttributes a = kNoNormal;
    if (seen(codes[i]))
    {
      a = normalsOnly ? buffers.Normals[i]
                      : attributes.Encode(gradients + 3 * static_cast<std::size_t>(i));
      if (attributes.AnyComponents())
      {
        a = attributes.WithComponents(a, componentGradients + 12 * static_cast<std::size_t>(i));
      }
    }
    buffers.Attributes[i] = a;
  }
}

void SinglePass::Render(const TransferFunctionTable& tf, BlendMode mode, double step, double offset,
  const PassOptions& options, std::size_t first, const std::vector<std::size_t>* tiles)
{
  this->State.PrepareGradients();
  // Blocks the transfer function makes transparent read as NaN, which blends as transparent.
  std::vector<std::uint8_t> skip;
  std::uint32_t nanCode = this->State.Encoder.HasNaNCode ? this->State.Encoder.NaNCode : 0u;
  const bool skipping = options.SkipTransparent &&
                        (mode == BlendMode::Composite || mode == BlendMode::Additive) &&
                        this->State.TransparentBlocks(tf, skip, nanCode);
  SkipMask mask;
  mask.Skip = &skip;
  const SkipMask* skipMask = skipping ? &mask : nullptr;
  this->Alphas.Prepare(tf, step, 2.0 * step);
  // A pixel's rotation is measured against the loop's phase length (or base step), so a pass at
  // dt / K sees the same rotated lattice as K accumulated frames.
  const Sampler& source = *this->State.Source;
  const SampleEncoding& encoding = this->State.Encoder;
  const AlphaCache& alphas = this->Alphas;
  const View& view = this->State.CurrentViewData;
  const StoredAttributes attributes = this->State.CurrentAttributes();
  const bool hasSecondCodes = source.HasSecondCode();
  const double termination =
    options.Termination > 0.0 ? options.Termination : this->State.Settings.StopTransmittance();
  float* pixels = this->State.Pixels.data();
  std::atomic<std::uint64_t> taken{ 0 };
  // Composite without lighting, gradient opacity or second codes: the lean loop.
  const bool plain = this->State.Settings.FastPaths && mode == BlendMode::Composite &&
                     !attributes.Shading && !attributes.GradientOpacity && !hasSecondCodes &&
                     !tf.HasComponentTerms();
  // Its table: per code, the opacity of one step and the colour times it.
  const double* premultiplied = nullptr;
  int firstPiece = kChunk;
  if (plain)
  {
    const std::vector<double>& table = this->Tables.Step(tf, step);
    premultiplied = table.data();
    // A sampler that walks its data (an unstructured mesh) starts each piece with a search for
    // the cell there: it keeps whole chunks.
    firstPiece = source.TracesPaths() ? kChunk : FirstPiece(table, termination);
  }

  const PlainPass plainPass{ source, encoding, tf, alphas, step, termination, skipMask, nanCode,
    premultiplied, firstPiece };
  // Samplers that walk their data walk two rays at once (SampleRays), each waiting on memory
  // while the other runs. (Tetrahedral wavelet, interacting frame: 0.24-0.25 s one at a time,
  // 0.22 two, 0.24 four, 0.23 eight.)
  const int together = plain && source.TracesPaths() && !skipMask ? 2 : 1;
  const int stride = options.PixelStride > 1 &&
                         (options.PixelStride & (options.PixelStride - 1)) == 0 &&
                         this->State.Settings.TileSize % options.PixelStride == 0
                       ? options.PixelStride
                       : 1;

  this->State.ForEachTile(
    [&](Tile& tile, ThreadBuffers& buffers)
    {
      std::uint64_t tileTaken = 0;
      const auto strided = BlockRays(tile.Rays, view.Width, stride, tile.X1, tile.Y1);
      const auto& rays = stride > 1 ? strided : tile.Rays;
      buffers.Values.resize(static_cast<std::size_t>(Sampler::kMostPieces) * kChunk);
      buffers.SecondCodes.resize(kChunk);
      buffers.Codes.resize(kChunk);
      buffers.Gradients.resize(3 * static_cast<std::size_t>(kChunk));
      if (attributes.AnyComponents())
      {
        buffers.ComponentGradients.resize(12 * static_cast<std::size_t>(kChunk));
      }
      buffers.Normals.resize(kChunk);
      buffers.Attributes.resize(kChunk);
      // A ray's offset along it (in steps, in [0, 1)) and its samples.
      const auto offsetOf = [&](int px, int py)
      {
        const double u = offset + this->State.RotationOf(px, py, step);
        return u - std::floor(u);
      };
      const auto samplesOf = [&](const RayInfo& ray)
      { return static_cast<int>(std::min(std::ceil(ray.Length / step), kMaxSamplesPerRay)); };
      const auto plainRay = [&](const RayInfo& ray)
      {
        const int px = ray.Pixel % view.Width;
        const int py = ray.Pixel / view.Width;
        return PlainRay(plainPass, view.PixelRay(px, py), ray.TEnter, ray.Length, offsetOf(px, py),
          samplesOf(ray));
      };
      const auto store = [&](const RayInfo& ray, const Pixel& p)
      { std::copy(p.data(), p.data() + 4, pixels + 4 * static_cast<std::size_t>(ray.Pixel)); };
      if (plain)
      {
        PlainTile(
          plainPass, rays, together, plainRay, store, buffers.Values, buffers.Codes, tileTaken);
        FillBlocks(tile.Rays, view.Width, stride, tile.X1, tile.Y1, pixels);
        taken += tileTaken;
        return;
      }
      for (const RayInfo& ray : rays)
      {
        const int px = ray.Pixel % view.Width;
        const int py = ray.Pixel / view.Width;
        const Ray r = view.PixelRay(px, py);
        const double u = offsetOf(px, py);
        const int n = samplesOf(ray);
        // Sampled a chunk at a time so that a ray the blend has given up on stops sampling.
        auto feed = [&](auto& stream)
        {
          for (int j0 = 0; j0 < n; j0 += kChunk)
          {
            const int count = std::min(kChunk, n - j0);
            tileTaken += count;
            source.SampleRay(
              r, ray.TEnter + (j0 + u) * step, step, count, buffers.Values.data(), skipMask);
            if (hasSecondCodes)
            {
              source.SampleRaySecond(
                r, ray.TEnter + (j0 + u) * step, step, count, buffers.SecondCodes.data());
            }
            this->Chunk(
              tf, mode, attributes, r, ray.TEnter + (j0 + u) * step, step, count, nanCode, buffers);
            for (int i = 0; i < count; ++i)
            {
              const double pos = (j0 + i + u) * step;
              if (pos >= ray.Length)
              {
                stream.Finish(ray.Length);
                return;
              }
              const SampleAttributes second = hasSecondCodes ? buffers.SecondCodes[i] : 0u;
              if (!stream.Push(pos, buffers.Codes[i], buffers.Attributes[i] | second << 16))
              {
                return;
              }
            }
          }
          stream.Finish(ray.Length);
        };
        const Pixel p = BlendSamples(feed, tf, alphas, mode, termination, attributes.Shading,
          attributes.GradientOpacity, attributes.Isos);
        store(ray, p);
      }
      FillBlocks(tile.Rays, view.Width, stride, tile.X1, tile.Y1, pixels);
      taken += tileTaken;
    },
    first, 0.0, tiles);
  this->State.Taken += taken;
}

} // namespace savr

#pragma once
// The settings of a view's frames (step, frames, memory budget, what is stored with the samples),
// and which of them decide the samples a view takes: a change there starts the view over.

#include "encoding/SampleEncoding.h"

#include <array>
#include <cstddef>
#include <tuple>

namespace savr
{

struct FrameSettings
{
  /// Base step between a frame's samples along a ray, in world units.
  double SampleDistance = 1.0;
  /// Frames to accumulate before the image is final.
  int MaximumFrames = 8;
  /// Bytes the loop may hold for a view: its images, ray tables and per-thread scratch, the
  /// caller's reserved bytes (below), and the stored samples, which have what remains (frames
  /// are capped to fit, counting the copy a store makes while it grows). What the sampler keeps
  /// for gradients (Sampler::GradientBytes) counts while shading or gradient opacity is on;
  /// when that does not fit, the sampler computes gradients where they are asked for instead
  /// (Sampler::ComputeGradientsOnDemand: the same bits, slower). When the rest alone exceed it,
  /// Reset allocates nothing for the view: see OverBudget.
  std::size_t MemoryBudget = std::size_t(1) << 30;
  /// Bytes the caller holds for the view, and per pixel of the image rectangle (ImageRectangle):
  /// counted in the budget before the stored samples.
  std::size_t ReservedBytes = 0;
  std::size_t ReservedBytesPerShownPixel = 0;
  /// Samples one frame may take over the lengths of all rays (each ray may take one more);
  /// 0 for no limit. A finer SampleDistance is coarsened by the smallest power of two that
  /// keeps within it, and MaximumFrames multiplied by the same (up to kMaximumFrames), so that
  /// the frames' offsets still refine towards the step asked.
  std::size_t MaximumSamplesPerFrame = 0;
  /// Rotate each pixel's offsets by a constant of its own (Cranley-Patterson).
  bool RotateOffsets = true;
  /// A length that anchors each pixel's sample lattice whatever the step: the pixel's samples
  /// along its ray lie at PixelPhase(x, y) * PhaseLength plus whole steps, so that K frames at
  /// a step take the samples of one frame at the step / K (K a power of two), as long as both
  /// have the same PhaseLength. 0 anchors it to SampleDistance instead (the rotation is then
  /// PixelRotation at the base step, and a single pass at base / K takes the samples of K frames).
  double PhaseLength = 0.0;
  /// Sample and store gradients (as normals) for shading; without it none are computed or kept.
  bool Shade = false;
  /// Sample and store gradient magnitudes (1 byte, MagnitudeScale codes per scalar unit per
  /// world unit) for gradient opacity. Data of one component only.
  bool GradientMagnitudes = false;
  double MagnitudeScale = 1.0;
  /// Independent components shaded (with Shade): sample and store each component's own normal
  /// (2 bytes per component, 8 per sample) instead of one per sample.
  bool ComponentNormals = false;
  /// Independent components with gradient opacity: sample and store the magnitude of each
  /// component's own gradient (1 byte per component, 4 per sample; component c at
  /// ComponentMagnitudeScales[c] codes per unit of it per world unit).
  bool ComponentMagnitudes = false;
  std::array<double, 4> ComponentMagnitudeScales = { 1.0, 1.0, 1.0, 1.0 };
  /// Store samples of integral data with fractional bits (2 bytes), for transfer functions with
  /// features narrower than one level of the data (SampleEncoding::HasFeaturesBetweenCodes).
  bool FineCodes = false;
  /// The values the transfer functions tell apart (their domain: they are constant beyond it),
  /// which the codes need cover (SampleEncoding::ForSampler). The whole line by default.
  std::array<double, 2> CodedWindow = SampleEncoding::kWholeLine;
  /// Threads to use; 0 lets TBB choose.
  int Threads = 0;
  /// Pixels per tile edge.
  int TileSize = 16;
  /// Encode, file and blend stored samples with AVX2 where the CPU has it (the same bits as
  /// without; off runs the scalar paths, for tests that compare the two).
  bool Vectorize = true;
  /// Stored blends pass over the rows at either end of a ray whose every code is transparent
  /// (the same bits as without; off walks every row, for tests that compare the two).
  bool PassOverTransparentRows = true;
  /// Composite through the fast paths where a blend allows them: per-code tables of interval
  /// opacities, rays four at a time with AVX2, the single pass's lean loop. Off, every sample is
  /// composited by the definition (Integrator.h's blends and Composite.h), for tests that hold
  /// the fast paths to it: images differ by round-off.
  bool FastPaths = true;
  /// Composite frames after a ray's first sample it only up to its opacity horizon: a few
  /// steps past where the first frame's samples have made it opaque, as the transfer function
  /// stands (the blend of its frames is checked there at every blend, and a ray it has not
  /// made opaque, after an edit for instance, is sampled whole): images differ from those of
  /// whole rays by at most Termination (a ray left exactly that light counts as stopped).
  /// Point-sampled composite frames also start each ray at its front: a row before the entry of the
  /// first block the first frame's transfer function does not make transparent (the same bits; an
  /// edit that makes any of those blocks visible samples the rays whole). Off samples whole rays.
  bool OpacityHorizons = true;
  /// Composite blends of stored samples, and single passes unless told otherwise, stop a ray
  /// once less than this much of the light comes through: what lies behind could change a
  /// channel by less than half an 8-bit level. Opacity horizons lie where a ray's first frame
  /// lets through a hundredth of it. Values outside (0, 1) read as 1e-6.
  double Termination = 1.0 / 512.0;
  /// Samplers that walk the data (Sampler::TracesPaths) record each ray's path on its first
  /// frame, within what the budget leaves after the stored samples, and later frames read it
  /// instead of walking again (values equal up to rounding; off walks every frame).
  bool TracePaths = true;

  /// Termination, or 1e-6 where it is outside (0, 1).
  double StopTransmittance() const
  {
    return this->Termination > 0.0 && this->Termination < 1.0 ? this->Termination : 1e-6;
  }

  /// Every field but FineCodes and CodedWindow, in order: the settings that decide which samples
  /// a view takes and how they are kept. (The codes are the caller's to weigh: finer codes, or a
  /// window wider than the codes cover, start over; others re-blend the samples stored.) A field
  /// added above must be added here: the field count is checked below.
  auto Sampling() const
  {
    return std::tie(this->SampleDistance, this->MaximumFrames, this->MemoryBudget,
      this->ReservedBytes, this->ReservedBytesPerShownPixel, this->MaximumSamplesPerFrame,
      this->RotateOffsets, this->PhaseLength, this->Shade, this->GradientMagnitudes,
      this->MagnitudeScale, this->ComponentNormals, this->ComponentMagnitudes,
      this->ComponentMagnitudeScales, this->Threads, this->TileSize, this->Vectorize,
      this->PassOverTransparentRows, this->FastPaths, this->OpacityHorizons, this->Termination,
      this->TracePaths);
  }
};

/// Whether `a` and `b` take the same samples and keep them alike: every field but FineCodes and
/// CodedWindow equal (a view with other such settings starts over).
inline bool SameSampling(const FrameSettings& a, const FrameSettings& b)
{
  return a.Sampling() == b.Sampling();
}

namespace detail
{
// Converts to any field's type: counts an aggregate's fields by how many it can be built from.
struct AnyField
{
  template <typename T>
  operator T() const
  {
    return T();
  }
};

template <typename T, typename... Fields>
constexpr std::size_t CountFields(...)
{
  return sizeof...(Fields) - 1;
}

template <typename T, typename... Fields, typename = decltype(T{ Fields{}... })>
constexpr std::size_t CountFields(int)
{
  return CountFields<T, Fields..., AnyField>(0);
}
} // namespace detail

static_assert(detail::CountFields<FrameSettings>(0) ==
                std::tuple_size<decltype(FrameSettings().Sampling())>::value + 2,
  "FrameSettings::Sampling() must name every field but FineCodes and CodedWindow");

} // namespace savr

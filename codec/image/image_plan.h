#pragma once
// Internal to the image encoder: an image after colour and wavelet transform, partitioned
// into code-blocks, with the container header being built. Shared by the encoding paths of
// every entropy coder (image_encoder.cpp, image_encoder_ht/lc/pc.cpp) and the decoder.

#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/entropy/codeblocks.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_stream.h"
#include "transforms/spec.h"

namespace pupwave {

// Finest quantizer base step, relative to the PSNR peak: float samples hold 24 significant
// bits, so a finer step only codes rounding noise (and integer images are exact far above it).
inline constexpr double kFinestStep = 1.0 / 16777216.0;
// The promise to the user (--psnr help): the PSNR reached is at most this far above the
// target (dB), with every coder's search.
inline constexpr double kPsnrWithin = 0.15;
// Highest PSNR target for float images: the float transform's own rounding sits not far above.
inline constexpr double kMaxFloatPsnr = 120.0;

// A rate target finer than lossy coding can reach; integer images switch to lossless instead.
class TargetRangeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A number for messages, in the shortest form that reads back the same (%.6g).
std::string format_number(double value);

// The most decomposition levels an image of these dimensions takes: levels beyond the point
// where the shortest transformed axis is one sample only rescale it and wreck the quality.
int max_levels(std::size_t width, std::size_t height);

struct ImagePlan {
  StreamHeader header;
  std::vector<Subband> bands;
  std::vector<CodeBlock> blocks;
  std::vector<double> norms;                     // synthesis norm per band
  std::vector<double> weights;                   // output error per unit component error
  std::vector<double> visual;                    // Tune::visual: visual_weights(), else empty
  std::vector<std::vector<float>> coef;          // irreversible: transformed components (or empty)
  std::vector<std::vector<std::int32_t>> icoef;  // reversible: transformed components (or empty)
  // A released component's buffer, reused by the next: first touches of fresh pages cost more
  // than the transform on some machines (about 0.6 ms per MiB here).
  std::vector<float> spare;
  std::vector<std::int32_t> ispare;
  ImageView source;  // the input, alive while the plan is used
  Transform1DPtr transform;
  std::size_t pixels = 0;              // width * height
  std::size_t samples = 0;             // pixels * channels
  double peak = 1.0;                   // PSNR peak of the input
  const Executor* executor = nullptr;  // EncodeOptions::executor, resolved (never null)
  bool measure_psnr = true;            // EncodeOptions::measure_psnr
  EncodeStats* stats = nullptr;        // EncodeOptions::stats (null: none kept)
  // Analysis reach of the transform when components are transformed by strips
  // (EncodeOptions::strip_encode, integer images, local analysis), else 0.
  std::size_t strip_reach = 0;
};

// Validates the image and options and lays out bands and blocks; no coefficients yet.
// The plan refers to `image`, which must outlive it.
ImagePlan plan_image(const ImageView& image, const EncodeOptions& options);

// Fills coef[c] (or icoef[c]) with component c after colour and wavelet transform; the
// encoder holds one component at a time to keep its memory small.
void transform_component(ImagePlan& plan, std::size_t c);
// Transforms every component (for coders that revisit all blocks many times).
void transform_all_components(ImagePlan& plan);

// Sets the quantizer steps of every (component, band) from a base step.
void set_base_step(ImagePlan& plan, double base_step);

// Done with component c for now: its buffer becomes the spare the next component fills.
void release_component(ImagePlan& plan, std::size_t c);
// Frees the transformed components and the spare once every block has been coded for the last time.
void release_coefficients(ImagePlan& plan);

// Index-unit magnitudes and signs of block i under the plan's steps.
void quantize_block(const ImagePlan& plan, std::size_t i, std::vector<float>& magnitude,
                    std::vector<std::uint8_t>& negative);

// The same from block i's coefficients (x fastest), T float or int32_t as the plan's.
template <class T>
void quantize_values(const ImagePlan& plan, std::size_t i, std::span<const T> values,
                     std::vector<float>& magnitude, std::vector<std::uint8_t>& negative);

// The .pw file of the plan with the given per-block index entries and codewords.
std::vector<std::uint8_t> assemble(const ImagePlan& plan, const std::vector<BlockEntry>& entries,
                                   const std::vector<std::vector<std::uint8_t>>& codewords);

// Decodes `bytes` and returns its PSNR (all channels) against `image`: by strips (strip_psnr,
// image_strips.h) where the stream allows, else from whole decoded planes.
double measure_psnr(const ImageView& image, std::span<const std::uint8_t> bytes, const Executor& executor);

// The whole-plane route of measure_psnr (every component plane decoded at full resolution):
// the reference strip_psnr is tested against.
double full_planes_psnr(const ImageView& image, const ParsedStream& s, const Executor& executor);

// The result of an encode: the bytes with their bpp and PSNR and the base step used. The PSNR
// is `known_psnr` if given, else measured when the plan asks for it, else NaN.
EncodeResult make_encode_result(const ImageView& image, const ImagePlan& plan,
                                std::vector<std::uint8_t> bytes, double base_step,
                                std::optional<double> known_psnr = std::nullopt);

// Whether `r` meets the rate target of `options` for an image of `pixels` pixels
// (EncodeResult::target_met): a bpp budget as the encoders round it, a PSNR target measured.
bool meets_target(const EncodeResult& r, const EncodeOptions& options, std::size_t pixels);

}  // namespace pupwave

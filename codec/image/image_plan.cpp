#include "codec/image/image_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "codec/error.h"
#include "codec/image/image_components.h"
#include "codec/image/image_metrics.h"
#include "codec/image/visual_weights.h"
#include "codec/rate/byte_budget.h"
#include "codec/rate/quantizer.h"
#include "transforms/norms.h"
#include "transforms/reach.h"
#include "transforms/separable.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

// Whether every sample of the row is finite and, for integer types, an integer in [0, top]:
// branch-free so it vectorizes (validate_image names the first bad sample otherwise). Adding
// and subtracting 2^23 rounds a float in [0, 2^23) to an integer, so only integers come back.
bool row_is_valid(const std::vector<float>& row, bool integer, float top) {
  constexpr float kRound = 8388608.0f;  // 2^23
  int bad = 0;                          // an int OR of comparisons: GCC vectorizes this form
  if (integer)
    for (float v : row) bad |= int(v < 0.0f) | int(v > top) | int((v + kRound) - kRound != v);
  else
    for (float v : row) bad |= int(v - v != 0.0f);  // NaN for NaN and infinities
  return bad == 0;
}

void validate_image(const ImageView& image) {
  if (image.width == 0 || image.height == 0) throw EncodeError("cannot encode an empty image");
  if (image.width > kMaxAxisExtent || image.height > kMaxAxisExtent)
    throw EncodeError("image dimensions exceed 65536 per axis");
  if (image.channels < 1 || image.channels > kMaxChannels)
    throw EncodeError("images must have 1 to " + std::to_string(kMaxChannels) + " channels");
  if (image.plane_size() * image.channels > kMaxTotalSamples) throw EncodeError("image exceeds 2^31 samples");
  check_view(image);
  if (is_integer(image.type) && image.storage != StorageType::f32 && image.storage != StorageType::f16)
    return;  // integer storage holds only finite values
  // Float storage: every sample must be finite and, for integer types, an integer in range.
  const bool integer = is_integer(image.type);
  const auto top = float(nominal_max(image.type));
  std::vector<float> row(image.width);
  for (std::size_t c = 0; c < image.channels; ++c)
    for (std::size_t y = 0; y < image.height; ++y) {
      image.read_row(c, y, row.data());
      if (row_is_valid(row, integer, top)) continue;
      for (float v : row) {
        if (!std::isfinite(v)) throw EncodeError("image has non-finite samples (NaN or infinity)");
        if (integer && (v < 0.0f || v > top || v != std::nearbyint(v)))
          throw EncodeError(to_string(image.type) + " image has a sample that is not an integer in 0.." +
                            std::to_string(int(top)));
      }
    }
}

void validate_options(const ImageView& image, const EncodeOptions& o) {
  if (o.mode == RateMode::lossless && !is_integer(image.type))
    throw std::invalid_argument(
        "lossless coding needs integer samples (8 or 16 bit); float images are lossy");
  if (o.mode != RateMode::lossless && !(o.target > 0.0 && std::isfinite(o.target)))
    throw std::invalid_argument("rate target must be positive and finite");
  if (o.levels < -1 || o.levels > 32) throw std::invalid_argument("levels must be in [0, 32]");
  if (o.metadata && !o.metadata->channel_names.empty() && o.metadata->channel_names.size() != image.channels)
    throw std::invalid_argument("metadata names " + std::to_string(o.metadata->channel_names.size()) +
                                " channels for an image of " + std::to_string(image.channels));
  const int most = max_levels(image.width, image.height);
  if (o.levels > most)
    throw std::invalid_argument("--levels " + std::to_string(o.levels) + " is more than a " +
                                std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " image takes (at most " + std::to_string(most) + ")");
}

// The colour transform decorrelates R, G, B: images of 3 or 4 channels, or more channels of
// which the first three are named R, G, B (an EXR with extra layers).
ColourTransform colour_of(const ImageView& image, const EncodeOptions& o, bool reversible) {
  if (image.channels <= 4) return colour_for(image.channels, reversible);
  const auto* names = o.metadata ? &o.metadata->channel_names : nullptr;
  const bool rgb = names && !names->empty() && (*names)[0] == "R" && (*names)[1] == "G" && (*names)[2] == "B";
  return rgb ? colour_for(3, reversible) : ColourTransform::none;
}

// Targets finer than lossy coding can express (the peak is the image's PSNR peak).
void check_precision(const ImageView& image, const EncodeOptions& o, double peak) {
  if (o.mode == RateMode::step && o.target < kFinestStep * peak) {
    const std::string finest = format_number(kFinestStep * peak);
    if (is_integer(image.type)) throw TargetRangeError("step finer than " + finest);
    throw std::invalid_argument("--step " + format_number(o.target) +
                                " is finer than float samples resolve; the finest step for this image is " +
                                finest + " (2^-24 of its value range)");
  }
  if (o.mode == RateMode::psnr && !is_integer(image.type) && o.target > kMaxFloatPsnr)
    throw std::invalid_argument("--psnr " + format_number(o.target) +
                                " dB is beyond the precision of float images; the highest target is " +
                                format_number(kMaxFloatPsnr) + " dB");
}

Extent block_log2(const Extent& size) {
  Extent k{};
  for (int a = 0; a < 3; ++a) {
    if (size[a] == 0 || (size[a] & (size[a] - 1)) != 0 || size[a] > 1024)
      throw std::invalid_argument("code-block extents must be powers of two up to 1024");
    while ((std::size_t(1) << k[a]) < size[a]) ++k[a];
  }
  const std::size_t count = size[0] * size[1] * size[2];
  if (count < 1024 || count > (std::size_t(1) << 20))
    throw std::invalid_argument("code-blocks must hold 1024 to 2^20 samples");
  return k;
}

}  // namespace

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

int max_levels(std::size_t width, std::size_t height) {
  // Axes of one sample are not transformed; the shortest other axis limits the levels.
  std::size_t shortest = width > 1 ? width : height;
  if (height > 1) shortest = std::min(shortest, height);
  int levels = 0;
  for (std::size_t m = shortest; m > 1; m = (m + 1) / 2) ++levels;
  return levels;
}

ImagePlan plan_image(const ImageView& image, const EncodeOptions& o) {
  validate_image(image);
  validate_options(image, o);
  auto t = make_transform(o.transform);
  check_stream_spec(t->spec());  // never write a stream the decoder's bounds refuse
  const bool reversible = o.mode == RateMode::lossless;
  if (reversible && !t->is_reversible())
    throw std::invalid_argument("lossless coding needs a reversible transform (cdf53), not " + t->spec());
  ImagePlan plan;
  StreamHeader& h = plan.header;
  h.dims = {image.width, image.height, 1};
  h.channels = std::uint32_t(image.channels);
  h.type = image.type;
  h.colour = colour_of(image, o, reversible);
  if (o.metadata) h.metadata = *o.metadata;
  h.entropy = o.entropy;
  h.reversible = reversible;
  h.levels = o.levels < 0 ? default_levels(h.dims) : o.levels;
  h.block_log2 = block_log2(o.block_size);
  h.delta = reversible ? 0.0 : kDefaultReconstructionDelta;
  h.spec = t->spec();
  plan.bands = subbands(h.dims, h.levels);
  plan.blocks = partition_blocks(plan.bands, h.levels, h.channels, o.block_size);
  plan.weights = component_weights(image.channels, h.colour);
  plan.pixels = image.plane_size();
  plan.samples = plan.pixels * image.channels;
  plan.peak = psnr_peak(image);
  check_precision(image, o, plan.peak);
  plan.executor = o.executor != nullptr ? o.executor : &default_executor();
  plan.measure_psnr = o.measure_psnr;
  plan.stats = o.stats;
  plan.source = image;
  if (reversible)
    h.steps.assign(plan.bands.size() * h.channels, 1.0f);
  else
    plan.norms = synthesis_norms(*t, h.dims, h.levels);
  if (!reversible && o.tune == Tune::visual) plan.visual = visual_weights(plan.bands, h.channels, h.colour);
  if (o.strip_encode && is_integer(image.type)) plan.strip_reach = analysis_reach(*t);
  plan.transform = std::move(t);
  return plan;
}

void transform_component(ImagePlan& plan, std::size_t c) {
  const StreamHeader& h = plan.header;
  if (h.reversible) {
    plan.icoef.resize(h.channels);
    plan.icoef[c].swap(plan.ispare);
    integer_component(plan.source, h.colour, c, plan.icoef[c], *plan.executor);
    forward(*plan.transform, plan.icoef[c].data(), h.dims, h.levels, *plan.executor);
  } else {
    plan.coef.resize(h.channels);
    plan.coef[c].swap(plan.spare);
    float_component(plan.source, h.colour, c, plan.coef[c], *plan.executor);
    forward(*plan.transform, plan.coef[c].data(), h.dims, h.levels, *plan.executor);
  }
}

void transform_all_components(ImagePlan& plan) {
  for (std::size_t c = 0; c < plan.header.channels; ++c) transform_component(plan, c);
}

void set_base_step(ImagePlan& plan, double base_step) {
  plan.header.steps = subband_steps(base_step, plan.norms, plan.weights, plan.visual);
}

void release_component(ImagePlan& plan, std::size_t c) {
  if (c < plan.coef.size() && !plan.coef[c].empty()) {
    plan.spare.swap(plan.coef[c]);
    std::vector<float>().swap(plan.coef[c]);
  }
  if (c < plan.icoef.size() && !plan.icoef[c].empty()) {
    plan.ispare.swap(plan.icoef[c]);
    std::vector<std::int32_t>().swap(plan.icoef[c]);
  }
}

void release_coefficients(ImagePlan& plan) {
  std::vector<float>().swap(plan.spare);
  std::vector<std::int32_t>().swap(plan.ispare);
  std::vector<std::vector<float>>().swap(plan.coef);
  std::vector<std::vector<std::int32_t>>().swap(plan.icoef);
}

template <class T>
void quantize_values(const ImagePlan& plan, std::size_t i, std::span<const T> values,
                     std::vector<float>& magnitude, std::vector<std::uint8_t>& negative) {
  const CodeBlock& b = plan.blocks[i];
  magnitude.resize(b.count());
  negative.resize(b.count());
  if constexpr (std::is_same_v<T, std::int32_t>) {
    for (std::int32_t v : values)
      if (v >= (1 << 24) || v <= -(1 << 24)) throw EncodeError("reversible coefficient out of range");
    quantize<std::int32_t>(values, 1.0f, magnitude, negative);
  } else {
    quantize<float>(values, plan.header.steps[b.component * plan.bands.size() + b.band], magnitude, negative);
  }
}

template void quantize_values<float>(const ImagePlan&, std::size_t, std::span<const float>,
                                     std::vector<float>&, std::vector<std::uint8_t>&);
template void quantize_values<std::int32_t>(const ImagePlan&, std::size_t, std::span<const std::int32_t>,
                                            std::vector<float>&, std::vector<std::uint8_t>&);

void quantize_block(const ImagePlan& plan, std::size_t i, std::vector<float>& magnitude,
                    std::vector<std::uint8_t>& negative) {
  const CodeBlock& b = plan.blocks[i];
  if (plan.header.reversible) {
    std::vector<std::int32_t> values(b.count());
    copy_block_out(plan.icoef[b.component].data(), plan.header.dims, b, values.data());
    quantize_values<std::int32_t>(plan, i, values, magnitude, negative);
  } else {
    std::vector<float> values(b.count());
    copy_block_out(plan.coef[b.component].data(), plan.header.dims, b, values.data());
    quantize_values<float>(plan, i, values, magnitude, negative);
  }
}

std::vector<std::uint8_t> assemble(const ImagePlan& plan, const std::vector<BlockEntry>& entries,
                                   const std::vector<std::vector<std::uint8_t>>& codewords) {
  std::vector<std::vector<std::uint8_t>> data(std::size_t(plan.header.levels) + 1);
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    auto& d = data[std::size_t(plan.blocks[i].resolution)];
    d.insert(d.end(), codewords[i].begin(), codewords[i].end());
  }
  return write_container(plan.header, entries, data);
}

bool meets_target(const EncodeResult& r, const EncodeOptions& options, std::size_t pixels) {
  switch (options.mode) {
    case RateMode::bpp: return double(r.bytes.size()) <= byte_budget(options.target, pixels);
    case RateMode::psnr: return r.psnr >= options.target;  // NaN (not measured) counts as missed
    case RateMode::step:
    case RateMode::lossless: break;
  }
  return true;
}

EncodeResult make_encode_result(const ImageView& image, const ImagePlan& plan,
                                std::vector<std::uint8_t> bytes, double base_step,
                                std::optional<double> known_psnr) {
  EncodeResult r;
  r.bpp = double(bytes.size()) * 8.0 / double(plan.pixels);
  if (known_psnr)
    r.psnr = *known_psnr;
  else
    r.psnr = plan.measure_psnr ? measure_psnr(image, bytes, *plan.executor) : std::nan("");
  r.base_step = base_step;
  r.bytes = std::move(bytes);
  return r;
}

}  // namespace pupwave

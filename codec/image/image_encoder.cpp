// encode_image with the bit-plane coder: every block is coded once at a fine quantizer step,
// then rate control picks each block's truncation point by rate-distortion slope (PCRD).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_encoder.h"
#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_plan.h"
#include "codec/image/transfer.h"
#include "codec/rate/pcrd.h"
#include "codec/rate/rate_guess.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

// Finest base step tried when a target needs more precision than the first guess.
constexpr int kMaxStepRefinements = 4;
// PSNR targets are met from above within this margin (dB) when possible.
constexpr double kPsnrTolerance = 0.05;
constexpr int kMaxPsnrRounds = 6;
// Blocks offered leftover budget after the slope bisection.
constexpr std::size_t kMaxFillCandidates = 64;
// How much finer than the rate model's step to code, so PCRD has truncation points to choose
// from below the target. The model (fitted to the first component) is close to the coded size of
// that component alone; with colour, the chroma components it leaves out are margin enough,
// a grey image gets one bit-plane more. A guess that turns out too coarse is refined below.
double guess_margin(const ImagePlan& plan) { return plan.header.channels >= 3 ? 1.0 : 2.0; }
// Never finer than the old fixed start refined kMaxStepRefinements times (peak / 2^17):
// finer indices would overflow the block coder without improving the result.
constexpr double kFinestBaseStep = 1.0 / 131072.0;

// All blocks coded with every pass; the PCRD inputs.
struct CodedImage {
  std::vector<EncodedBlock> blocks;
  std::vector<std::vector<HullPoint>> hulls;
  double initial_distortion = 0.0;  // index units^2, nothing coded
};

// Codes every block, one component at a time so only one transformed component is held.
CodedImage code_blocks(ImagePlan& plan) {
  CodedImage out;
  out.blocks.resize(plan.blocks.size());
  out.hulls.resize(plan.blocks.size());
  for (std::size_t c = 0; c < plan.header.channels; ++c) {
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (plan.blocks[i].component == c) ids.push_back(i);
    if (plan.coef.size() <= c || plan.coef[c].empty()) transform_component(plan, c);
    plan.executor->run(ids.size(), [&](std::size_t k) {
      const std::size_t i = ids[k];
      std::vector<float> magnitude;
      std::vector<std::uint8_t> negative;
      quantize_block(plan, i, magnitude, negative);
      const CodeBlock& b = plan.blocks[i];
      out.blocks[i] = encode_block(magnitude, negative, b.size, b.orientation, plan.header.delta);
      out.hulls[i] = rd_hull(out.blocks[i]);
    });
    release_component(plan, c);
  }
  release_coefficients(plan);
  for (const auto& b : out.blocks) out.initial_distortion += b.initial_distortion;
  return out;
}

std::vector<BlockEntry> entries_for(const CodedImage& coded, const std::vector<int>& passes) {
  std::vector<BlockEntry> entries(passes.size());
  for (std::size_t i = 0; i < passes.size(); ++i) {
    entries[i].passes = passes[i];
    entries[i].planes = passes[i] > 0 ? coded.blocks[i].planes : 0;
    entries[i].length = std::uint32_t(coded.blocks[i].size(passes[i]));
  }
  return entries;
}

std::size_t stream_size(const ImagePlan& plan, const CodedImage& coded, const std::vector<int>& passes) {
  const auto entries = entries_for(coded, passes);
  std::size_t data = 0;
  for (const auto& e : entries) data += e.length;
  return container_size(plan.header, encode_index(entries).size(), data);
}

double remaining_distortion(const CodedImage& coded, const std::vector<int>& passes) {
  double removed = 0.0;
  for (std::size_t i = 0; i < passes.size(); ++i)
    for (int n = 0; n < passes[i]; ++n) removed += coded.blocks[i].distortion_drop[std::size_t(n)];
  return coded.initial_distortion - removed;
}

std::vector<std::uint8_t> build(const ImagePlan& plan, const CodedImage& coded,
                                const std::vector<int>& passes) {
  std::vector<std::vector<std::uint8_t>> words(passes.size());
  for (std::size_t i = 0; i < passes.size(); ++i) words[i] = coded.blocks[i].codeword(passes[i]);
  return assemble(plan, entries_for(coded, passes), words);
}

std::vector<int> all_passes(const CodedImage& coded) {
  std::vector<int> passes;
  for (const auto& b : coded.blocks) passes.push_back(b.pass_count());
  return passes;
}

// Bisection leaves a little of the budget unused where the next hull points of blocks are
// large; try the best few of them one by one and keep each that still fits.
void fill_budget(const ImagePlan& plan, const CodedImage& coded, std::vector<int>& passes, double budget) {
  struct Candidate {
    double slope;
    std::size_t block;
    int passes;
  };
  std::vector<Candidate> next;
  for (std::size_t i = 0; i < passes.size(); ++i)
    for (const HullPoint& p : coded.hulls[i])
      if (p.passes > passes[i]) {
        next.push_back({p.slope, i, p.passes});
        break;
      }
  std::sort(next.begin(), next.end(),
            [](const Candidate& a, const Candidate& b) { return a.slope > b.slope; });
  if (next.size() > kMaxFillCandidates) next.resize(kMaxFillCandidates);
  for (const Candidate& c : next) {
    const int old = passes[c.block];
    passes[c.block] = c.passes;
    if (double(stream_size(plan, coded, passes)) > budget) passes[c.block] = old;
  }
}

// Best quality within a byte budget; the base step is refined while every pass still fits.
// The first step comes from the rate model of component 0 (coded right after, so it is
// transformed once); the refinement loop catches a guess that was too coarse.
EncodeResult encode_for_size(const ImageView& image, ImagePlan& plan, double bpp) {
  const double budget = std::floor(bpp * double(plan.pixels) / 8.0);
  double base = plan.peak / 512.0;
  if (!plan.header.reversible) {
    transform_component(plan, 0);
    base = std::max(guess_base_step(plan, 0, budget, guess_margin(plan)), kFinestBaseStep * plan.peak);
  }
  for (int round = 0;; ++round, base /= 4.0) {
    set_base_step(plan, base);
    CodedImage coded = code_blocks(plan);
    const bool fits_all = double(stream_size(plan, coded, all_passes(coded))) <= 0.95 * budget;
    if (fits_all && round < kMaxStepRefinements) continue;
    auto passes = allocate_by_slope(coded.hulls, true, [&](const std::vector<int>& p) {
      return double(stream_size(plan, coded, p)) <= budget;
    });
    fill_budget(plan, coded, passes, budget);
    auto bytes = build(plan, coded, passes);
    coded = CodedImage{};  // free the coded blocks before the PSNR check decodes the stream
    return make_encode_result(image, plan, std::move(bytes), base);
  }
}

// Smallest stream whose decoded PSNR reaches the target: PCRD on the estimated distortion,
// corrected by measuring the decoded image.
EncodeResult encode_for_psnr(const ImageView& image, ImagePlan& plan, double psnr) {
  const double target_mse = plan.peak * plan.peak / std::pow(10.0, psnr / 10.0);
  double base = 0.3 * std::sqrt(target_mse);
  for (int round = 0;; ++round, base /= 4.0) {
    set_base_step(plan, base);
    const CodedImage coded = code_blocks(plan);
    double allowed = target_mse * double(plan.samples) / (base * base);
    std::vector<std::uint8_t> best;
    double best_psnr = 0.0;
    for (int k = 0; k < kMaxPsnrRounds; ++k) {
      const auto passes = allocate_by_slope(coded.hulls, false, [&](const std::vector<int>& p) {
        return remaining_distortion(coded, p) <= allowed;
      });
      auto bytes = build(plan, coded, passes);
      const double got = measure_psnr(image, bytes, *plan.executor);
      if (got >= psnr && (best.empty() || bytes.size() < best.size())) {
        best = bytes;
        best_psnr = got;
      }
      if (got >= psnr && got <= psnr + kPsnrTolerance) break;
      const double got_mse = target_mse * std::pow(10.0, (psnr - got) / 10.0);
      allowed *= std::isfinite(got) ? target_mse / got_mse : 2.0;
    }
    if (!best.empty() || round >= kMaxStepRefinements) {
      if (best.empty()) return make_encode_result(image, plan, build(plan, coded, all_passes(coded)), base);
      return make_encode_result(image, plan, std::move(best), base, best_psnr);
    }
  }
}

// What the stream records about the coded domain of a float image (transfer.h).
struct CodedDomain {
  Transfer transfer = Transfer::linear;
  bool nonnegative = false;
  std::vector<NonFiniteSample> nonfinite;
};

EncodeResult encode_with_levels(const ImageView& image, const EncodeOptions& options,
                                const CodedDomain& domain) {
  ImagePlan plan = plan_image(image, options);
  plan.header.transfer = domain.transfer;
  plan.header.nonnegative = domain.nonnegative;
  plan.header.nonfinite = domain.nonfinite;
  if (options.entropy == EntropyCoder::zstd) return encode_zstd(image, plan, options);
  switch (options.mode) {
    case RateMode::lossless: {
      const CodedImage coded = code_blocks(plan);
      return make_encode_result(image, plan, build(plan, coded, all_passes(coded)), 1.0);
    }
    case RateMode::step: {
      set_base_step(plan, options.target);
      const CodedImage coded = code_blocks(plan);
      return make_encode_result(image, plan, build(plan, coded, all_passes(coded)), options.target);
    }
    case RateMode::bpp: return encode_for_size(image, plan, options.target);
    case RateMode::psnr: return encode_for_psnr(image, plan, options.target);
  }
  throw std::invalid_argument("unknown rate mode");
}

EncodeResult encode_in_domain(const ImageView& image, const EncodeOptions& options,
                              const CodedDomain& domain) {
  if (options.levels >= 0 || options.entropy == EntropyCoder::zstd)
    return encode_with_levels(image, options, domain);
  // Unstable banks (pups:cinpact-c3) amplify the coarse band at every level until quantization
  // indices leave the block coder's range; with default levels, use fewer instead of failing.
  EncodeOptions fewer = options;
  fewer.levels = default_levels({image.width, image.height, 1});
  for (;;) {
    try {
      return encode_with_levels(image, fewer, domain);
    } catch (const IndexRangeError&) {
      if (fewer.levels <= 1) throw;
      --fewer.levels;
    }
  }
}

}  // namespace

EncodeResult encode_image(const ImageView& image, const EncodeOptions& options) {
  if (is_integer(image.type)) return encode_in_domain(image, options, CodedDomain{});
  // Float images are coded in the transfer domain, from a copy (non-finite samples taken out).
  check_view(image);
  if (image.channels > kMaxChannels || image.width > kMaxAxisExtent || image.height > kMaxAxisExtent ||
      image.plane_size() * image.channels > kMaxTotalSamples)
    throw EncodeError("image exceeds 65536 per axis, 64 channels or 2^31 samples");
  CodedDomainImage coded = to_coded_domain(image, options.transfer, options.keep_nonfinite);
  ImageView view = view_of(coded.image);
  if (options.transfer == Transfer::log2) view.peak = 1.0;  // log-PSNR: peak 1 stop
  CodedDomain domain{options.transfer, coded.nonnegative, std::move(coded.nonfinite)};
  const std::size_t kept = domain.nonfinite.size();
  EncodeResult r = encode_in_domain(view, options, domain);
  r.metric = metric_name(options.transfer);
  r.nonfinite = kept;
  return r;
}

}  // namespace pupwave

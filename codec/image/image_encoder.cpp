// encode_image with the bit-plane coder: every block is coded once at a fine quantizer step,
// then rate control picks each block's truncation point by rate-distortion slope (PCRD).
#include <algorithm>
#include <atomic>
#include <cmath>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_encoder.h"
#include "codec/error.h"
#include "codec/image/budget_trim.h"
#include "codec/image/encode_stats.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_encoder_ht.h"
#include "codec/image/image_encoder_lc.h"
#include "codec/image/image_encoder_pc.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_plan.h"
#include "codec/image/image_strip_encoder.h"
#include "codec/image/kept_block.h"
#include "codec/image/rate_guess.h"
#include "codec/image/transfer.h"
#include "codec/rate/byte_budget.h"
#include "codec/rate/pcrd.h"
#include "codec/rate/quantizer.h"
#include "codec/rate/rdoq.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

// Most codeword bytes a trial encode against a byte limit holds (code_every_pass): the
// lossless trial of a 32768^2 image at 1 bpp holds 128 MiB before it overflows. Above it, a
// trial that fits after all is coded twice.
constexpr std::size_t kMaxTrialBytes = std::size_t(64) << 20;
// Finest base step tried when a target needs more precision than the first guess.
constexpr int kMaxStepRefinements = 4;
// PSNR targets are met from above within this margin (dB) when possible.
constexpr double kPsnrTolerance = 0.05;
// Base-step families per octave (family_base).
constexpr int kFamilies = 8;
// Files below this size search every family: there one pass of a coarse-band block adds a few
// bytes and tenths of a dB, and the families' sizes for one target differ by more than the
// 0.5% a higher target may give less (chelsea.png: 3-6 byte drops under 1 KB, 0.64% at 3.6 KB).
constexpr std::size_t kSmallFile = 4096;
// Most samples whose transformed components the family search keeps (a float each: 256 MiB).
constexpr std::size_t kMaxKeptSamples = std::size_t(1) << 26;
// Decodes measured while searching the truncation for a PSNR target, and search steps in all.
constexpr int kMaxPsnrTrials = 14;
constexpr int kMaxPsnrSteps = 48;
// Truncations tried between two adjacent slope thresholds (refine_between).
constexpr int kMaxRefineTrials = 6;
// Base-step families tried for a byte budget, 1/kSizeFamilies octave apart: where the
// bit-planes of the bands fall moves the PSNR at one size by up to 0.2 dB (camera.png at 2
// bpp), and no family is best everywhere.
constexpr int kSizeFamilies = 3;
// RDOQ's estimate of the bytes an isolated coefficient costs in the last coded plane (a
// significance decision in a near-zero context, its sign, the contexts it wakes around
// it); fitted on the test photographs (0.5 and 2 give less).
constexpr double kIsolatedBytes = 1.0;
// Blocks offered leftover budget after the slope bisection.
constexpr std::size_t kMaxFillCandidates = 64;
// How much finer than the rate model's step to code, so PCRD has truncation points to choose
// from below the target. The model (fitted to the first component) is close to the coded size of
// that component alone; with colour, the chroma components it leaves out are margin enough,
// a grey image gets one bit-plane more. A guess that turns out too coarse is refined below.
double guess_margin(const ImagePlan& plan) { return plan.header.channels >= 3 ? 1.0 : 2.0; }
// Never finer than peak / 2^13 refined kMaxStepRefinements times (peak / 2^17):
// finer indices would overflow the block coder without improving the result.
constexpr double kFinestBaseStep = 1.0 / 131072.0;

// Returns the pages of freed memory to the system (glibc's malloc_trim; elsewhere nothing).
void return_freed_pages() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

// Hands the pages of many small freed blocks (codewords copied into a stream) back to the
// system every `step` bytes (kTrimBytes by default): the allocator keeps them otherwise, and
// the copy and its source would both stay resident (glibc's malloc_trim; elsewhere nothing).
class FreedMemory {
 public:
  explicit FreedMemory(std::size_t step = kTrimBytes) : step_(step) {}
  void add(std::size_t bytes) {
    if ((pending_ += bytes) < step_) return;
    pending_ = 0;
    return_freed_pages();
  }

 private:
  static constexpr std::size_t kTrimBytes = std::size_t(16) << 20;
  std::size_t step_;
  std::size_t pending_ = 0;
};

// All blocks coded with every pass (or those a byte budget can keep: BudgetTrim); the PCRD inputs.
struct CodedImage {
  std::vector<KeptBlock> blocks;
  std::vector<std::vector<HullPoint>> hulls;
  double initial_distortion = 0.0;  // index units^2, nothing coded
  std::size_t every_pass_size = 0;  // bytes of the stream with every pass of every block
};

// Whether component c is coded from a strip-wise transform (image_strip_encoder.h) rather
// than from the transformed component held in the plan.
bool streams(const ImagePlan& plan, std::size_t c, bool keep) {
  const bool held =
      (c < plan.coef.size() && !plan.coef[c].empty()) || (c < plan.icoef.size() && !plan.icoef[c].empty());
  return plan.strip_reach > 0 && !keep && !held;
}

using BlockCoder = std::function<void(std::size_t block, const std::vector<float>& magnitude,
                                      const std::vector<std::uint8_t>& negative)>;

// Quantizes every block and hands it to `code` (on the executor's threads), one component at
// a time so only one transformed component is held (or, by strips, only the rows the blocks
// being coded need), until `stop` returns true. With `keep`, the transformed components stay
// in the plan for the next call (release_coefficients frees them).
// With `wanted`, only the blocks it accepts are quantized and coded (the transform still runs).
void quantize_blocks(ImagePlan& plan, bool keep, const std::function<bool()>& stop, const BlockCoder& code,
                     const std::function<bool(std::size_t)>& wanted = {}) {
  const auto code_values = [&](std::size_t i, auto values) {
    if (stop() || (wanted && !wanted(i))) return;
    std::vector<float> magnitude;
    std::vector<std::uint8_t> negative;
    quantize_values(plan, i, values, magnitude, negative);
    code(i, magnitude, negative);
  };
  for (std::size_t c = 0; c < plan.header.channels && !stop(); ++c) {
    if (streams(plan, c, keep)) {
      if (plan.header.reversible)
        stream_component<std::int32_t>(
            plan, c, [&](std::size_t i, std::span<const std::int32_t> v) { code_values(i, v); }, stop);
      else
        stream_component<float>(
            plan, c, [&](std::size_t i, std::span<const float> v) { code_values(i, v); }, stop);
      continue;
    }
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (plan.blocks[i].component == c) ids.push_back(i);
    if (plan.coef.size() <= c || plan.coef[c].empty()) transform_component(plan, c);
    plan.executor->run(ids.size(), [&](std::size_t k) {
      if (stop() || (wanted && !wanted(ids[k]))) return;
      std::vector<float> magnitude;
      std::vector<std::uint8_t> negative;
      quantize_block(plan, ids[k], magnitude, negative);
      code(ids[k], magnitude, negative);
    });
    if (!keep) release_component(plan, c);
  }
  if (!keep) release_coefficients(plan);
}

// Codes every block with every pass and its rate-distortion hull (quantize_blocks). With a
// byte `budget` (a single family cut by one slope threshold), holds only the passes PCRD can
// choose for it (budget_trim.h).
CodedImage code_blocks(ImagePlan& plan, bool keep = false, std::optional<double> budget = std::nullopt) {
  CodedImage out;
  out.blocks.resize(plan.blocks.size());
  out.hulls.resize(plan.blocks.size());
  std::vector<BlockEntry> every(plan.blocks.size());
  std::optional<BudgetTrim> trim;
  if (budget) trim.emplace(out.blocks, out.hulls, *budget);
  quantize_blocks(
      plan, keep, [] { return false; },
      [&](std::size_t i, const std::vector<float>& magnitude, const std::vector<std::uint8_t>& negative) {
        const CodeBlock& b = plan.blocks[i];
        EncodedBlock coded = encode_block(magnitude, negative, b.size, b.orientation, plan.header.delta,
                                          context_tally(plan.stats));
        const int n = coded.pass_count();
        every[i] = {n > 0 ? coded.planes : 0, n, std::uint32_t(coded.size(n))};
        auto hull = rd_hull(coded);
        if (trim) return trim->add(i, std::move(coded), std::move(hull));
        out.hulls[i] = std::move(hull);
        out.hulls[i].shrink_to_fit();
        out.blocks[i] = KeptBlock(std::move(coded));
      });
  for (const auto& b : out.blocks) out.initial_distortion += b.initial_distortion;
  std::size_t data = 0;
  for (const auto& e : every) data += e.length;
  out.every_pass_size = container_size(plan.header, encode_index(every).size(), data);
  return out;
}

// The lossless-size estimate (lossless_clearly_over) codes one block in kSampleEvery, spread
// over every band by a hash of the block index; bands of fewer than kWholeBandBlocks blocks
// (the coarse levels, few bytes and least like the rest) are coded whole.
constexpr std::uint64_t kSampleEvery = 8;
constexpr std::size_t kWholeBandBlocks = 64;
// Only images of at least this many blocks are estimated: the sample then holds a few hundred
// finest-level blocks (a 4096^2 grey image: 4096 blocks, 5% of them coded whole, 12% of the
// rest sampled). Smaller images always run the exact trial, which costs them little.
constexpr std::size_t kMinEstimatedBlocks = 2048;
// The estimate must exceed the byte limit by this factor to skip the exact trial. On 4096^2
// mosaics and tilings of the test photographs (and one half flat, half noise) the estimate is
// within 1% of the lossless size (bench/results/image-speed-memory.md). The margin: with n of a
// band's N samples sampled at r_s bytes each and the rest at r_u, the estimate N r_s exceeds
// 1.5 (n r_s + (N - n) r_u) only if r_u < r_s (N - 1.5 n) / (1.5 (N - n)), 0.62 r_s at
// n = N/8: a lossless stream that fits is dropped only if the unsampled blocks code in under
// 0.62 of the sampled ones' bytes per sample. A pseudo-random sample of about a hundred
// blocks per finest band shows no such skew on natural images (the test has a half flat one).
// It is a statistical margin, not a proof: a flat image with 1/8 of its blocks noise and a
// budget of its lossless size is dropped if the sample catches 1.5x its share of noise blocks
// (3.7 standard deviations above the mean at a 4096^2 image's 384 finest-level samples, 2.6
// at 2048 blocks' 192), and an image built to hide its bytes from this hash could be; either
// still gets a lossy stream within its budget.
// Between 1 and this factor the exact trial runs as before.
constexpr double kEstimateMargin = 1.5;
// The sample codes about 1/kSampleEvery of the lossless stream (and transforms most of the
// image) wherever the limit is; the exact trial codes about `limit` bytes. Lossless streams of
// photographs hold about half the raw bits or more (3.9 of 8 on the grey mosaic, 8.8 of 24 on
// the RGB one), so below a limit of raw / kMinLimitFraction the exact trial is as cheap or
// cheaper (CPU s exact / sampled: grey mosaic at 0.25 bpp, raw / 32, 0.43 / 0.50; RGB mosaic
// at 2 bpp, raw / 12, 1.93 / 1.98; grey at 1 bpp, raw / 8, 0.98 / 0.90). Speed only, not
// the outcome.
constexpr double kMinLimitFraction = 10.0;

bool sampled_block(std::size_t i) {
  return (std::uint64_t(i) * 0x9E3779B97F4A7C15ull) >> 61 == 0;  // top 3 bits: 1 in kSampleEvery
}
static_assert(kSampleEvery == 8, "sampled_block keeps the top 3 bits of the hash");

// Whether the lossless every-pass stream of `plan` is clearly over `byte_limit` bytes: from
// the coded sizes of a spread sample of its blocks, each band's bytes are extrapolated by its
// samples (the estimate above). It saves the exact trial (code_every_pass against the limit)
// most of its work where the lossless stream is far over (a grey 4096^2 mosaic at 2 bpp
// codes about half its blocks before the exact trial gives up). Always false for images of
// few blocks. The sampled bytes alone over the limit are proof, and end the sample early.
bool lossless_clearly_over(ImagePlan& plan, std::size_t byte_limit) {
  if (plan.blocks.size() < kMinEstimatedBlocks) return false;
  const double raw_bytes = double(plan.samples) * std::log2(plan.peak + 1.0) / 8.0;
  if (double(byte_limit) < raw_bytes / kMinLimitFraction) return false;
  const std::size_t bands = plan.bands.size() * plan.header.channels;
  const auto band_of = [&](const CodeBlock& b) {
    return std::size_t(b.component) * plan.bands.size() + b.band;
  };
  std::vector<std::size_t> blocks_in(bands, 0), samples_in(bands, 0);
  for (const CodeBlock& b : plan.blocks) {
    ++blocks_in[band_of(b)];
    samples_in[band_of(b)] += b.count();
  }
  const auto wanted = [&](std::size_t i) {
    return blocks_in[band_of(plan.blocks[i])] < kWholeBandBlocks || sampled_block(i);
  };
  std::vector<std::atomic<std::size_t>> bytes_in(bands), sampled_in(bands);
  std::atomic<std::size_t> total{0};
  quantize_blocks(
      plan, false, [&] { return total.load(std::memory_order_relaxed) > byte_limit; },
      [&](std::size_t i, const std::vector<float>& magnitude, const std::vector<std::uint8_t>& negative) {
        const CodeBlock& b = plan.blocks[i];
        const std::size_t size = encode_block_whole(magnitude, negative, b.size, b.orientation,
                                                    plan.header.delta, context_tally(plan.stats))
                                     .codeword.size();
        bytes_in[band_of(b)] += size;
        sampled_in[band_of(b)] += b.count();
        total += size;
      },
      wanted);
  if (total > byte_limit) return true;
  double estimate = 0.0;
  for (std::size_t k = 0; k < bands; ++k)
    if (sampled_in[k] > 0) estimate += double(bytes_in[k]) * double(samples_in[k]) / double(sampled_in[k]);
  return estimate > kEstimateMargin * double(byte_limit);
}

// The stream with every pass of every block (step and lossless encodes), or nullopt once the
// codewords exceed `byte_limit` bytes. Only each block's whole codeword is kept, not its
// truncation points and hull (those take more memory than the codewords: 0.6 GB for a
// 32768^2 image). Against a limit (a trial, mostly one that overflows: the lossless stream
// against a lossy budget), codewords are kept only up to kMaxTrialBytes and then just counted,
// and a trial that fits after all is coded again.
std::optional<std::vector<std::uint8_t>> code_every_pass(
    ImagePlan& plan, std::size_t byte_limit = std::numeric_limits<std::size_t>::max()) {
  const bool trial = byte_limit != std::numeric_limits<std::size_t>::max();
  std::vector<BlockEntry> entries(plan.blocks.size());
  std::vector<std::vector<std::uint8_t>> words(plan.blocks.size());
  std::atomic<std::size_t> total{0};
  std::atomic<bool> over{false}, dropped{false};
  quantize_blocks(
      plan, false, [&] { return over.load(std::memory_order_relaxed); },
      [&](std::size_t i, const std::vector<float>& magnitude, const std::vector<std::uint8_t>& negative) {
        const CodeBlock& b = plan.blocks[i];
        WholeBlock coded = encode_block_whole(magnitude, negative, b.size, b.orientation, plan.header.delta,
                                              context_tally(plan.stats));
        const int n = coded.passes;
        const std::size_t size = coded.codeword.size();
        entries[i] = {n > 0 ? coded.planes : 0, n, std::uint32_t(size)};
        const std::size_t sum = total.fetch_add(size) + size;
        if (sum > byte_limit) over = true;
        if (trial && sum > kMaxTrialBytes) dropped = true;
        if (dropped) return;
        words[i] = std::move(coded.codeword);
        words[i].shrink_to_fit();  // the encoder's buffer has up to twice the capacity it needs
      });
  if (over) {
    words.clear();
    return_freed_pages();  // the many small codewords would stay resident through the lossy encode
    return std::nullopt;
  }
  if (dropped) {
    words.clear();
    return code_every_pass(plan);
  }
  std::vector<std::size_t> sizes(std::size_t(plan.header.levels) + 1, 0);
  for (std::size_t i = 0; i < words.size(); ++i)
    sizes[std::size_t(plan.blocks[i].resolution)] += words[i].size();
  FreedMemory freed;
  return write_container(plan.header, entries, sizes, [&](std::size_t r, std::vector<std::uint8_t>& out) {
    for (std::size_t i = 0; i < words.size(); ++i) {
      if (std::size_t(plan.blocks[i].resolution) != r) continue;
      out.insert(out.end(), words[i].begin(), words[i].end());
      freed.add(words[i].size());
      std::vector<std::uint8_t>().swap(words[i]);
    }
  });
}

// Magnitudes of component c for the rate model (rate_guess.h), gathered block by block from
// the strip-wise transform: the same counts as from the whole transformed component.
MagnitudeHistogram stream_histogram(const ImagePlan& plan, std::size_t c) {
  MagnitudeHistogram total;
  std::mutex lock;
  stream_component<float>(plan, c, [&](std::size_t i, std::span<const float> values) {
    auto h = std::make_unique<MagnitudeHistogram>();
    h->add(values, magnitude_scale(plan, c, plan.blocks[i].band));
    const std::lock_guard<std::mutex> hold(lock);
    total.merge(*h);
  });
  return total;
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
    for (int n = 0; n < passes[i]; ++n) removed += coded.blocks[i].distortion_drop(n);
  return coded.initial_distortion - removed;
}

// The stream of `coded` cut at `passes`. Each block's codeword goes straight into the stream
// (sized first, so it is never reallocated); when `coded` is not const, for the last build of
// an encode, each block's coded data is freed once copied (the coded blocks and the stream are
// then not both held whole).
template <class Coded>
std::vector<std::uint8_t> build_stream(const ImagePlan& plan, Coded& coded, const std::vector<int>& passes) {
  const auto entries = entries_for(coded, passes);
  std::vector<std::size_t> sizes(std::size_t(plan.header.levels) + 1, 0);
  for (std::size_t i = 0; i < passes.size(); ++i)
    sizes[std::size_t(plan.blocks[i].resolution)] += entries[i].length;
  // Every 1/16 of the stream, 1 MiB at least (at 16 MiB a 4 MiB stream and the blocks
  // it is copied from would both be resident at the end).
  FreedMemory freed(
      std::max(std::accumulate(sizes.begin(), sizes.end(), std::size_t(0)) / 16, std::size_t(1) << 20));
  return write_container(plan.header, entries, sizes, [&](std::size_t r, std::vector<std::uint8_t>& out) {
    for (std::size_t i = 0; i < passes.size(); ++i) {
      if (std::size_t(plan.blocks[i].resolution) != r) continue;
      coded.blocks[i].append_codeword(passes[i], out);
      if constexpr (!std::is_const_v<Coded>) {
        freed.add(coded.blocks[i].bytes_held());
        coded.blocks[i] = KeptBlock{};
      }
    }
  });
}

std::vector<std::uint8_t> build(const ImagePlan& plan, const CodedImage& coded,
                                const std::vector<int>& passes) {
  return build_stream(plan, coded, passes);
}

// The last build of an encode: frees the coded blocks as it goes.
std::vector<std::uint8_t> build_final(const ImagePlan& plan, CodedImage& coded,
                                      const std::vector<int>& passes) {
  return_freed_pages();  // the coding pass's freed buffers: the stream may take their place
  return build_stream(plan, coded, passes);
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

// A hull (rd_hull) with the distortion in output units (index units times `scale`, the base step
// squared), so blocks coded at different base steps compare.
std::vector<HullPoint> scale_hull(std::vector<HullPoint> hull, double scale) {
  for (HullPoint& p : hull) {
    p.removed *= scale;
    p.slope *= scale;
  }
  return hull;
}

// The blocks coded at one base step (hulls in index units).
struct Family {
  double base = 0.0;
  CodedImage coded;
};

// Index of the (component, band) a block belongs to: its step's place in the header.
std::size_t band_group(const ImagePlan& plan, std::size_t i) {
  return plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band;
}

// Per (component, band), the family whose blocks cut at slope lambda (output units per byte)
// cost least in distortion + lambda * bytes: the Lagrangian cost is a sum over bands, so
// choosing per band minimises it over every mix of families.
std::vector<std::size_t> choose_families(const ImagePlan& plan, const std::vector<Family>& families,
                                         double lambda) {
  const std::size_t groups = plan.header.channels * plan.bands.size();
  std::vector<double> cost(families.size() * groups, 0.0);
  for (std::size_t f = 0; f < families.size(); ++f) {
    const double scale = families[f].base * families[f].base;
    const CodedImage& coded = families[f].coded;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
      double removed = 0.0;
      std::size_t bytes = 0;
      for (const HullPoint& p : coded.hulls[i]) {
        if (p.slope * scale < lambda) break;
        removed = p.removed;
        bytes = p.bytes;
      }
      cost[f * groups + band_group(plan, i)] +=
          (coded.blocks[i].initial_distortion - removed) * scale + lambda * double(bytes);
    }
  }
  std::vector<std::size_t> choice(groups, 0);
  for (std::size_t g = 0; g < groups; ++g)
    for (std::size_t f = 1; f < families.size(); ++f)
      if (cost[f * groups + g] < cost[choice[g] * groups + g]) choice[g] = f;
  return choice;
}

// Bytes of the stream that takes every band from its chosen family, every block cut at lambda.
std::size_t mixed_size(const ImagePlan& plan, const std::vector<Family>& families,
                       const std::vector<std::size_t>& choice, double lambda) {
  std::vector<BlockEntry> entries(plan.blocks.size());
  std::size_t data = 0;
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    const Family& fam = families[choice[band_group(plan, i)]];
    const int passes = passes_at_slope(fam.coded.hulls[i], lambda / (fam.base * fam.base));
    const KeptBlock& b = fam.coded.blocks[i];
    entries[i] = {passes > 0 ? b.planes : 0, passes, std::uint32_t(b.size(passes))};
    data += entries[i].length;
  }
  return container_size(plan.header, encode_index(entries).size(), data);
}

// Smallest slope (output units per byte) whose per-band family choice and cuts fit the budget,
// by bisection on log lambda.
double mixed_threshold(const ImagePlan& plan, const std::vector<Family>& families, double budget) {
  const auto fits = [&](double lambda) {
    return double(mixed_size(plan, families, choose_families(plan, families, lambda), lambda)) <= budget;
  };
  double lo = 1e-30, hi = 1e30;
  if (fits(lo)) return lo;
  for (int iter = 0; iter < 200 && hi / lo > 1.0 + 1e-7; ++iter) {
    const double mid = std::sqrt(lo * hi);
    (fits(mid) ? hi : lo) = mid;
  }
  return hi;
}

// The blocks of the chosen family of every band, hulls in output units, with the plan's steps
// set to match; `scale` receives each block's base step squared.
CodedImage mix_families(ImagePlan& plan, std::vector<Family>& families,
                        const std::vector<std::size_t>& choice, std::vector<double>& scale) {
  std::vector<float> steps(choice.size());
  for (std::size_t f = 0; f < families.size(); ++f) {
    const auto family_steps = subband_steps(families[f].base, plan.norms, plan.weights, plan.visual);
    for (std::size_t g = 0; g < choice.size(); ++g)
      if (choice[g] == f) steps[g] = family_steps[g];
  }
  plan.header.steps = std::move(steps);
  CodedImage mixed;
  mixed.blocks.resize(plan.blocks.size());
  mixed.hulls.resize(plan.blocks.size());
  scale.resize(plan.blocks.size());
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    Family& fam = families[choice[band_group(plan, i)]];
    scale[i] = fam.base * fam.base;
    mixed.blocks[i] = std::move(fam.coded.blocks[i]);
    mixed.hulls[i] = scale_hull(std::move(fam.coded.hulls[i]), scale[i]);
  }
  return mixed;
}

// RDOQ (rdoq.h): recodes every block cut at `passes` with the coefficients that would become
// significant alone in its last coded plane, for less than lambda (output units per byte)
// times their rate, pulled under that plane. The transformed components must be kept in the
// plan and its steps those the blocks were coded at (`scale`: each block's base step
// squared). Returns whether any block changed (its hull is then recomputed).
bool pull_isolated_coefficients(const ImagePlan& plan, CodedImage& coded, const std::vector<double>& scale,
                                const std::vector<int>& passes, double lambda) {
  std::atomic<std::size_t> changed{0};
  plan.executor->run(passes.size(), [&](std::size_t i) {
    const int plane = last_cleanup_plane(coded.blocks[i].planes, passes[i]);
    if (plane < 0) return;
    std::vector<float> magnitude;
    std::vector<std::uint8_t> negative;
    quantize_block(plan, i, magnitude, negative);
    const CodeBlock& b = plan.blocks[i];
    if (pull_isolated(magnitude, b.size, plane, plan.header.delta, lambda * kIsolatedBytes / scale[i]) == 0)
      return;
    EncodedBlock recoded = encode_block(magnitude, negative, b.size, b.orientation, plan.header.delta,
                                        context_tally(plan.stats));
    coded.hulls[i] = scale_hull(rd_hull(recoded), scale[i]);
    coded.blocks[i] = KeptBlock(std::move(recoded));
    ++changed;
  });
  return changed > 0;
}

// Codes every block at base step `base`, refined by quarters while every pass still fits 95%
// of the budget (a guess too coarse leaves PCRD nothing to choose).
Family code_family(ImagePlan& plan, double base, double budget, bool keep) {
  for (int round = 0;; ++round, base /= 4.0) {
    set_base_step(plan, base);
    CodedImage coded = code_blocks(plan, keep, keep ? std::nullopt : std::optional<double>(budget));
    const bool fits_all = double(coded.every_pass_size) <= 0.95 * budget;
    if (fits_all && round < kMaxStepRefinements) continue;
    return Family{base, std::move(coded)};
  }
}

// Best quality within a byte budget. The first step comes from the rate model of component
// 0 (coded right after, so it is transformed once). At effort 2, where the transformed
// components fit in memory, the blocks are coded at kSizeFamilies base steps spread over an octave, every
// band takes the family that serves it best at the final slope (choose_families; the header holds a step per
// band), and isolated last-plane coefficients are requantized (RDOQ).
EncodeResult encode_for_size(const ImageView& image, ImagePlan& plan, double bpp, int effort) {
  const double budget = byte_budget(bpp, plan.pixels);
  double base = plan.peak / 512.0;
  const bool keep = effort >= 2 && !plan.header.reversible && plan.samples <= kMaxKeptSamples;
  if (!plan.header.reversible && streams(plan, 0, keep)) {
    // A first strip-wise pass over component 0 for the model's statistics (the input is
    // mapped: reading it again costs little), never the whole component in memory.
    base = std::max(guess_base_step(stream_histogram(plan, 0), budget, guess_margin(plan)),
                    kFinestBaseStep * plan.peak);
  } else if (!plan.header.reversible) {
    transform_component(plan, 0);
    base = std::max(guess_base_step(plan, 0, budget, guess_margin(plan)), kFinestBaseStep * plan.peak);
  }
  std::vector<Family> families;
  families.push_back(code_family(plan, base, budget, keep));
  for (int f = 1; keep && f < kSizeFamilies; ++f) {
    set_base_step(plan, families[0].base * std::exp2(-double(f) / kSizeFamilies));
    families.push_back(
        Family{families[0].base * std::exp2(-double(f) / kSizeFamilies), code_blocks(plan, true)});
  }
  // One family needs no choosing (and its hulls may be cut: BudgetTrim).
  const double lambda = families.size() > 1 ? mixed_threshold(plan, families, budget) : 0.0;
  base = families[0].base;  // the base step reported: family 0's (bands may use finer ones)
  std::vector<double> scale;
  CodedImage mixed = mix_families(plan, families, choose_families(plan, families, lambda), scale);
  families.clear();
  const auto fits = [&](const std::vector<int>& p) { return double(stream_size(plan, mixed, p)) <= budget; };
  auto passes = allocate_by_slope(mixed.hulls, true, fits);
  if (keep && pull_isolated_coefficients(plan, mixed, scale, passes, lambda))
    passes = allocate_by_slope(mixed.hulls, true, fits);
  release_coefficients(plan);
  fill_budget(plan, mixed, passes, budget);
  // The hulls are done with: freed now, the pages they share with the blocks go back to the
  // system as build_final frees the blocks (a 32768^2 image's hulls hold about 60 MiB).
  std::vector<std::vector<HullPoint>>().swap(mixed.hulls);
  auto bytes = build_final(plan, mixed, passes);
  mixed = CodedImage{};  // free the coded blocks before the PSNR check decodes the stream
  return make_encode_result(image, plan, std::move(bytes), base);
}

// One truncation of the coded blocks: every block cut at slope threshold lambda, decoded.
struct Trial {
  double lambda = 0.0;
  std::vector<std::uint8_t> bytes;
  double psnr = 0.0;  // measured on the decoded stream
};

Trial trial_at(const ImageView& image, const ImagePlan& plan, const CodedImage& coded, double lambda) {
  Trial t{lambda, build(plan, coded, passes_at_slope(coded.hulls, lambda)), 0.0};
  t.psnr = measure_psnr(image, t.bytes, *plan.executor);
  return t;
}

// Smallest positive hull slope: the threshold that keeps every pass.
double lowest_slope(const CodedImage& coded) {
  double low = std::numeric_limits<double>::infinity();
  for (const auto& h : coded.hulls)
    if (!h.empty() && h.back().slope > 0.0) low = std::min(low, h.back().slope);
  return std::isfinite(low) ? low : 1e-12;
}

// Next threshold to try between `ok` (reaches the target) and `fail` (misses it). Near the
// target the MSE is about proportional to lambda (high-rate theory), so log lambda is about
// linear in dB: interpolate, aiming a little above the target, kept inside the middle of the
// bracket so it always shrinks.
double next_lambda(const Trial& ok, const std::optional<Trial>& fail, double target) {
  const double aim = target + 0.4 * kPsnrTolerance;
  const double per_db = std::log(10.0) / 10.0;  // d(log lambda) / d(-dB)
  if (!fail) return ok.lambda * std::exp(per_db * std::min(ok.psnr - aim, 30.0));
  const double lo = std::log(ok.lambda), hi = std::log(fail->lambda);
  double x = 0.5 * (lo + hi);
  if (std::isfinite(ok.psnr) && ok.psnr > fail->psnr)
    x = lo + (hi - lo) * (ok.psnr - aim) / (ok.psnr - fail->psnr);
  else if (!std::isfinite(ok.psnr))
    x = hi - per_db * (aim - fail->psnr);
  return std::exp(std::clamp(x, lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo)));
}

// Adjacent slope thresholds can differ by a hull point spanning several passes of one block,
// a step of tenths of a dB at low rates. From the truncation that misses the target, raise
// one differing block to each pass count up to ok's, and keep the smallest that reaches it.
void refine_between(const ImageView& image, const ImagePlan& plan, const CodedImage& coded, double psnr,
                    Trial& ok, const Trial& fail) {
  const auto high = passes_at_slope(coded.hulls, ok.lambda);
  const auto low = passes_at_slope(coded.hulls, fail.lambda);
  std::vector<std::pair<std::size_t, std::vector<int>>> options;  // (stream size, passes)
  for (std::size_t i = 0; i < low.size(); ++i)
    for (int p = low[i] + 1; p <= high[i]; ++p) {
      auto passes = low;
      passes[i] = p;
      const std::size_t size = stream_size(plan, coded, passes);
      if (size < ok.bytes.size()) options.emplace_back(size, std::move(passes));
    }
  std::sort(options.begin(), options.end());
  int tried = 0;
  for (const auto& [size, passes] : options) {
    if (tried++ == kMaxRefineTrials) break;
    auto bytes = build(plan, coded, passes);
    const double got = measure_psnr(image, bytes, *plan.executor);
    if (got < psnr) continue;
    ok.bytes = std::move(bytes);
    ok.psnr = got;
    return;
  }
}

// Narrows a bracket [ok, fail) of truncations of `coded` down to the smallest that reaches the
// target: a search on the slope threshold, seeded by PCRD on the estimated distortion and
// steered by measuring the decoded image. Every truncation tried is remembered as reaching the
// target or not, so the answer always reaches it. Where the smallest overshoots the target by
// more than kPsnrWithin, the smallest one tried that does not is returned instead.
Trial narrow(const ImageView& image, const ImagePlan& plan, const CodedImage& coded, double psnr, double base,
             Trial ok, std::optional<Trial> fail) {
  std::optional<Trial> close;
  if (ok.psnr <= psnr + kPsnrWithin) close = ok;
  const double target_mse = plan.peak * plan.peak / std::pow(10.0, psnr / 10.0);
  const double allowed = target_mse * double(plan.samples) / (base * base);
  double lambda = slope_threshold(coded.hulls, false, [&](const std::vector<int>& p) {
    return remaining_distortion(coded, p) <= allowed;
  });
  int trials = 0;
  for (int k = 0; k < kMaxPsnrSteps && trials < kMaxPsnrTrials && ok.psnr > psnr + kPsnrTolerance; ++k) {
    if (k > 0 || !(lambda > ok.lambda) || (fail && !(lambda < fail->lambda)))
      lambda = trials % 2 == 1 && fail ? std::sqrt(ok.lambda * fail->lambda) : next_lambda(ok, fail, psnr);
    const auto passes = passes_at_slope(coded.hulls, lambda);
    // No block changes between the bracket's ends: ok is the last truncation that reaches the target.
    if (passes == passes_at_slope(coded.hulls, ok.lambda)) {
      ok.lambda = lambda;
      continue;
    }
    if (fail && passes == passes_at_slope(coded.hulls, fail->lambda)) {
      fail->lambda = lambda;
      continue;
    }
    Trial t = trial_at(image, plan, coded, lambda);
    ++trials;
    if (t.psnr >= psnr) {
      ok = std::move(t);
      if (ok.psnr <= psnr + kPsnrWithin) close = ok;
    } else {
      fail = std::move(t);
    }
  }
  if (fail && ok.psnr > psnr + kPsnrTolerance) refine_between(image, plan, coded, psnr, ok, *fail);
  if (ok.psnr > psnr + kPsnrWithin && close) return std::move(*close);
  return ok;
}

// Smallest truncation of `coded` whose decoded PSNR reaches the target (narrow); nullopt when
// even every pass misses the target (step too coarse).
std::optional<Trial> search_psnr(const ImageView& image, const ImagePlan& plan, const CodedImage& coded,
                                 double psnr, double base) {
  Trial ok = trial_at(image, plan, coded, lowest_slope(coded));
  if (!(ok.psnr >= psnr)) return std::nullopt;
  return narrow(image, plan, coded, psnr, base, std::move(ok), std::nullopt);
}

// Like search_psnr, for a truncation better than `best` only: starts from the largest
// truncation smaller than best, so a family that has none reaching the target costs one
// decode. Where best overshoots by more than kPsnrWithin, the smallest truncation at least as
// large as best is tried too (it may land closer).
std::optional<Trial> search_below(const ImageView& image, const ImagePlan& plan, const CodedImage& coded,
                                  double psnr, double base, const Trial& best) {
  const std::size_t limit = best.bytes.size();
  const auto size_of = [&](double lambda) {
    return stream_size(plan, coded, passes_at_slope(coded.hulls, lambda));
  };
  const double below = slope_threshold(
      coded.hulls, true, [&](const std::vector<int>& p) { return stream_size(plan, coded, p) < limit; });
  std::optional<Trial> q;
  if (size_of(below) < limit) {
    q = trial_at(image, plan, coded, below);
    if (q->psnr >= psnr) return narrow(image, plan, coded, psnr, base, std::move(*q), std::nullopt);
  }
  if (best.psnr <= psnr + kPsnrWithin) return std::nullopt;
  const double above = slope_threshold(
      coded.hulls, false, [&](const std::vector<int>& p) { return stream_size(plan, coded, p) >= limit; });
  if (size_of(above) < limit) return std::nullopt;
  Trial r = trial_at(image, plan, coded, above);
  if (!(r.psnr >= psnr)) return std::nullopt;
  return narrow(image, plan, coded, psnr, base, std::move(r), std::move(q));
}

// Whether trial `a` is a better answer than `b` for the target: within kPsnrWithin of the
// target first, then the fewer bytes.
bool better(const Trial& a, const std::optional<Trial>& b, double psnr) {
  if (!b) return true;
  const bool a_close = a.psnr <= psnr + kPsnrWithin, b_close = b->psnr <= psnr + kPsnrWithin;
  if (a_close != b_close) return a_close;
  return a.bytes.size() < b->bytes.size();
}

// The base step of family `shift` (0..kFamilies-1) no coarser than `at_most`: the largest
// peak * 2^-(k + shift / kFamilies) over integers k. Steps an octave apart quantize to the same
// indices less one bit-plane, so a family offers the same truncations whatever the target, and
// its smallest truncation reaching a target can only grow with the target.
double family_base(double peak, int shift, double at_most) {
  const double offset = double(shift) / double(kFamilies);
  const double k = std::ceil(std::log2(peak / at_most) - offset - 1e-9);
  return peak * std::exp2(-(k + offset));
}

// The smallest truncation of family `shift` found to reach the target (better than `best`
// only, if given), its base step refined by octaves (the same family) while even every pass
// misses the target; nullopt when the finest step still misses it. `round` is the refinement
// that worked, and where later families start.
std::optional<Trial> search_family(const ImageView& image, ImagePlan& plan, double psnr, int shift,
                                   const std::optional<Trial>& best, int& round, double& base) {
  // Later families reuse the transformed components (the transform does not depend on the
  // step: half the cost of a family) where they fit in memory.
  const bool keep = best && plan.samples <= kMaxKeptSamples;
  const double target_mse = plan.peak * plan.peak / std::pow(10.0, psnr / 10.0);
  const double finest = kFinestStep * plan.peak;
  // At most 0.42 (0.3 * sqrt 2) times the target RMS error: 0.3 on average over targets.
  const double first = family_base(plan.peak, shift, std::max(0.42 * std::sqrt(target_mse), finest));
  for (;; ++round) {
    base = std::max(first * std::pow(4.0, -round), finest);
    set_base_step(plan, base);
    const CodedImage coded = code_blocks(plan, keep);
    auto found = best ? search_below(image, plan, coded, psnr, base, *best)
                      : search_psnr(image, plan, coded, psnr, base);
    if (found || best || round >= kMaxStepRefinements || base <= finest) return found;
  }
}

// Smallest stream whose decoded PSNR reaches the target, from base-step families 1/8 octave
// apart (family_base). Family 0 usually lands close; small files (where one pass of a
// coarse-band block moves tenths of a dB, and the families' truncation points differ by more
// than the 0.5% the sizes may wobble) and targets family 0 overshoots by more than kPsnrWithin
// also look for a better file in every other family, so that the answer is the smallest close
// one and consistent from one target to the next.
EncodeResult encode_for_psnr(const ImageView& image, ImagePlan& plan, double psnr) {
  std::optional<Trial> best;
  double best_base = 0.0;
  int round = 0;
  for (int shift = 0; shift < kFamilies; ++shift) {
    double base = 0.0;
    auto found = search_family(image, plan, psnr, shift, best, round, base);
    if (found && better(*found, best, psnr)) {
      best = std::move(found);
      best_base = base;
    }
    if (!best) break;  // even family 0's finest step misses the target
    if (shift == 0 && best->psnr <= psnr + kPsnrWithin && best->bytes.size() >= kSmallFile) break;
  }
  if (!best)
    throw TargetRangeError("PSNR " + format_number(psnr) + " dB is beyond the precision of lossy coding");
  return make_encode_result(image, plan, std::move(best->bytes), best_base, best->psnr);
}

// What the stream records about the coded domain of a float image (transfer.h).
struct CodedDomain {
  Transfer transfer = Transfer::linear;
  int offset_log2 = kLogOffsetLog2;
  bool nonnegative = false;
  std::vector<NonFiniteSample> nonfinite;
};

// A coder that is not embedded codes at one step; each runs its own search over the step for a
// rate target (lc codes lossless only).
EncodeResult encode_not_embedded(const ImageView& image, ImagePlan& plan, const EncodeOptions& options) {
  switch (options.entropy) {
    case EntropyCoder::ht: return encode_ht(image, plan, options);
    case EntropyCoder::lc: return encode_lc(image, plan);
    case EntropyCoder::pc: return encode_pc(image, plan, options);
    case EntropyCoder::ebcot: break;
  }
  throw std::logic_error("the bit-plane coder's rate is set by truncation");
}

EncodeResult encode_with_levels(const ImageView& image, const EncodeOptions& options,
                                const CodedDomain& domain) {
  EncodeOptions planned = options;
  if (coder_traits(options.entropy).whole_bands) planned.block_size = kLcBlockSize;
  ImagePlan plan = plan_image(image, planned);
  plan.header.transfer = domain.transfer;
  plan.header.transfer_offset_log2 = domain.offset_log2;
  plan.header.nonnegative = domain.nonnegative;
  plan.header.nonfinite = domain.nonfinite;
  if (!coder_traits(options.entropy).embedded) return encode_not_embedded(image, plan, options);
  // The embedded bit-plane coder: every pass coded, then truncated to the target (PCRD).
  switch (options.mode) {
    case RateMode::lossless: {
      return make_encode_result(image, plan, *code_every_pass(plan), 1.0);
    }
    case RateMode::step: {
      set_base_step(plan, options.target);
      return make_encode_result(image, plan, *code_every_pass(plan), options.target);
    }
    case RateMode::bpp: return encode_for_size(image, plan, options.target, options.effort);
    case RateMode::psnr: return encode_for_psnr(image, plan, options.target);
  }
  throw std::invalid_argument("unknown rate mode");
}

EncodeResult encode_in_domain(const ImageView& image, const EncodeOptions& options,
                              const CodedDomain& domain) {
  if (options.levels >= 0) return encode_with_levels(image, options, domain);
  // The lc coder's default is no wavelet levels: its predictor on the samples themselves codes
  // the test photographs 2.5-5.5% smaller than on a 5-level cdf53 decomposition.
  if (options.entropy == EntropyCoder::lc) {
    EncodeOptions flat = options;
    flat.levels = 0;
    return encode_with_levels(image, flat, domain);
  }
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

// The lossless stream of an integer image (caller's levels and entropy coder), if it holds at
// most `byte_limit` bytes.
std::optional<EncodeResult> encode_exact(const ImageView& image, const EncodeOptions& options,
                                         std::size_t byte_limit = std::numeric_limits<std::size_t>::max()) {
  EncodeOptions exact = options;
  exact.mode = RateMode::lossless;
  exact.transform = "cdf53";
  exact.target = 0.0;
  exact.measure_psnr = false;
  // A lossy-only coder's lossless alternative is the bit-plane coder's, as the default's.
  if (!coder_traits(exact.entropy).lossless) exact.entropy = EntropyCoder::ebcot;
  ImagePlan plan = plan_image(image, exact);
  EncodeResult r;
  if (exact.entropy == EntropyCoder::ht) {
    r = encode_ht(image, plan, exact, byte_limit);
    if (r.bytes.empty()) return std::nullopt;
  } else {
    if (byte_limit != std::numeric_limits<std::size_t>::max() && lossless_clearly_over(plan, byte_limit))
      return std::nullopt;
    auto bytes = code_every_pass(plan, byte_limit);
    if (!bytes) return std::nullopt;
    r = make_encode_result(image, plan, std::move(*bytes), 1.0);
  }
  if (r.bytes.size() > byte_limit) return std::nullopt;
  r.psnr = std::numeric_limits<double>::infinity();
  r.switched_to_lossless = true;
  return r;
}

// Integer images have an exact stream of finite size and infinite PSNR, so no rate target
// should give a larger file: a budget it fits, a PSNR only exact decoding reaches, or a lossy
// stream at least as large all give the lossless stream instead.
EncodeResult encode_capped(const ImageView& image, const EncodeOptions& options) {
  if (options.mode == RateMode::bpp) {
    const double bytes = byte_budget(options.target, image.plane_size());
    const std::size_t budget = bytes < 1e18 ? std::size_t(bytes) : std::numeric_limits<std::size_t>::max();
    if (auto exact = encode_exact(image, options, budget)) return std::move(*exact);
    return encode_in_domain(image, options, CodedDomain{});
  }
  const double peak = psnr_peak(image);
  const double samples = double(image.plane_size() * image.channels);
  // A decoded image that is not exact has a sample off by at least 1: MSE >= 1 / samples. And
  // below an MSE of 1/256 (fewer than 1 sample in 256 off by one) a lossy stream has to code
  // nearly every bit the lossless one does and more (72 dB for 8 bits; on the test photographs
  // lossless already wins at 60-65 dB), so the long lossy search is skipped there.
  const double best_inexact = 10.0 * std::log10(peak * peak * std::min(samples, 256.0));
  if (options.mode == RateMode::psnr && options.target > best_inexact) return *encode_exact(image, options);
  std::optional<EncodeResult> lossy;
  try {
    lossy = encode_in_domain(image, options, CodedDomain{});
  } catch (const TargetRangeError&) {
    return *encode_exact(image, options);  // finer than lossy coding can go: exact is the answer
  }
  if (auto exact = encode_exact(image, options, lossy->bytes.size())) return std::move(*exact);
  return std::move(*lossy);
}

// A float image's PSNR target that lossy coding cannot reach (finer than the finest step, or
// indices beyond the coder's range): the stream at the finest step the coder takes, doubled
// until it fits, comes back with its measured PSNR, so encode_image reports the target as missed
// (the CLI warns) instead of failing without a file.
EncodeResult encode_finest(const ImageView& view, const EncodeOptions& options, const CodedDomain& domain) {
  EncodeOptions step = options;
  step.mode = RateMode::step;
  step.measure_psnr = true;  // what was reached is what the caller reports
  const double peak = psnr_peak(view);
  for (step.target = kFinestStep * peak;; step.target *= 2.0) {
    try {
      return encode_in_domain(view, step, domain);
    } catch (const IndexRangeError&) {
      if (step.target > peak) throw;
    }
  }
}

// encode_image before it judges the target.
EncodeResult encode_any(const ImageView& image, const EncodeOptions& options) {
  if (options.mode != RateMode::lossless && !(options.target > 0.0 && std::isfinite(options.target)))
    throw std::invalid_argument("rate target must be positive and finite");
  if (options.effort < 1 || options.effort > 2) throw std::invalid_argument("effort must be 1 or 2");
  const CoderTraits& coder = coder_traits(options.entropy);
  if (!coder.lossy && options.mode != RateMode::lossless)
    throw std::invalid_argument(std::string("the ") + coder.name + " coder codes lossless only (--lossless)");
  if (!coder.lossless && options.mode == RateMode::lossless)
    throw std::invalid_argument(std::string("the ") + coder.name +
                                " coder codes lossy only (--bpp, --psnr or --step)");
  if (is_integer(image.type)) {
    if (options.mode != RateMode::lossless) return encode_capped(image, options);
    return encode_in_domain(image, options, CodedDomain{});
  }
  // Float images are coded in the transfer domain, from a copy (non-finite samples taken out).
  check_view(image);
  if (image.channels > kMaxChannels || image.width > kMaxAxisExtent || image.height > kMaxAxisExtent ||
      image.plane_size() * image.channels > kMaxTotalSamples)
    throw EncodeError("image exceeds 65536 per axis, 64 channels or 2^31 samples");
  const int offset_log2 = options.mode == RateMode::bpp
                              ? adaptive_offset_log2(options.target / double(image.channels))
                              : kAdaptiveOffsetNoRate;
  CodedDomainImage coded = to_coded_domain(image, options.transfer, options.keep_nonfinite, offset_log2);
  ImageView view = view_of(coded.image);
  if (options.transfer != Transfer::linear) view.peak = 1.0;  // log-PSNR: peak 1 stop
  CodedDomain domain{options.transfer, coded.offset_log2, coded.nonnegative, std::move(coded.nonfinite)};
  const std::size_t kept = domain.nonfinite.size();
  EncodeResult r = [&] {
    if (options.mode != RateMode::psnr) return encode_in_domain(view, options, domain);
    try {
      return encode_in_domain(view, options, domain);
    } catch (const TargetRangeError&) {
    } catch (const IndexRangeError&) {
    }
    return encode_finest(view, options, domain);
  }();
  r.metric = metric_name(options.transfer);
  r.nonfinite = kept;
  return r;
}

}  // namespace

EncodeResult encode_image(const ImageView& image, const EncodeOptions& options) {
  EncodeResult r = encode_any(image, options);
  r.target_met = meets_target(r, options, image.plane_size());
  return r;
}

}  // namespace pupwave

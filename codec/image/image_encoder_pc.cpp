// encode_image with the pc back end. The components are transformed once and held; a coding
// pass quantizes and codes every block at one base step, one resolution at a time (the blocks
// of a resolution in parallel: their parents, the chosen indices one level coarser, are final),
// with greedy RDOQ against the models' own costs. Rate targets search the base step with whole
// passes: a secant on (log bytes or PSNR) against log step, kept inside the bracket found.
#include "codec/image/image_encoder_pc.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_groups.h"
#include "codec/error.h"
#include "codec/format/container.h"
#include "codec/image/image_components.h"
#include "codec/image/lc_parent.h"
#include "codec/image/pc_decoder.h"
#include "codec/rate/rate_guess.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

// Passes of a rate search before it only steps towards a fitting result; a byte budget is met
// within kSizeTolerance below it, a PSNR target within kPsnrTolerance dB above it.
constexpr int kMaxTrials = 10;
constexpr double kSizeTolerance = 0.005;
constexpr double kPsnrTolerance = 0.05;
// Until two points bracket the goal: bytes ~ step^-1.5, PSNR -20 log10(2) dB per octave.
constexpr double kSizeSlope = -1.5;
constexpr double kPsnrSlope = -20.0 / std::numbers::ln10;

// One coding pass: every block's entry and codeword and the chosen indices (Mallat planes).
struct Pass {
  double t = 0.0;  // log base step
  std::vector<float> steps;
  std::vector<BlockEntry> entries;
  std::vector<std::vector<std::uint8_t>> words;
  std::vector<std::vector<std::int32_t>> q;
  std::size_t bytes = 0;  // the whole file
  double score = 0.0;     // log bytes or PSNR, by the search
};

// Codes block i at the plan's steps with RDOQ, its parent read from (and its indices written
// to) the index planes q.
void code_block(const ImagePlan& plan, std::size_t i, std::vector<std::vector<std::int32_t>>& q, Pass& out) {
  const CodeBlock& b = plan.blocks[i];
  const Extent& dims = plan.header.dims;
  thread_local std::vector<float> u;
  u.resize(b.count());
  copy_block_out(plan.coef[b.component].data(), dims, b, u.data());
  const float inv = 1.0f / plan.header.steps[b.component * plan.bands.size() + b.band];
  for (float& x : u) x *= inv;
  std::vector<std::int32_t> v(b.count());
  const PcRdoq rdoq{u, kPcLambda, plan.header.delta};
  std::int32_t* plane = q[b.component].data();
  CoefCodeword w = pc_encode_block(v, b.size[0], b.size[1], lc_parent(plan.bands, b, plane, dims[0], nullptr),
                                   &rdoq, pc_luma(b, q, dims[0]));
  copy_block_in(v.data(), dims, b, plane);
  out.entries[i] = {w.bits, w.bits > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
  out.words[i] = std::move(w.bytes);
}

// Every block coded at base step exp(t), resolution by resolution. Throws IndexRangeError when
// an index leaves the coder's range.
Pass code_pass(ImagePlan& plan, double t) {
  set_base_step(plan, std::exp(t));
  Pass p;
  p.t = t;
  p.steps = plan.header.steps;
  p.entries.resize(plan.blocks.size());
  p.words.resize(plan.blocks.size());
  p.q.assign(plan.header.channels, std::vector<std::int32_t>(plan.header.dims[0] * plan.header.dims[1], 0));
  for (int g = 0; g < kPcGroupsPerResolution * (plan.header.levels + 1); ++g) {  // pc_group order
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (pc_group(plan.blocks[i], p.q.size()) == g) ids.push_back(i);
    std::atomic<bool> out_of_range{false};
    plan.executor->run(ids.size(), [&](std::size_t k) {
      try {
        code_block(plan, ids[k], p.q, p);
      } catch (const IndexRangeError&) {
        out_of_range = true;
      }
    });
    if (out_of_range) throw IndexRangeError("quantization index beyond the pc coder's range (step too fine)");
  }
  std::size_t data = 0;
  for (const auto& w : p.words) data += w.size();
  p.bytes = container_size(plan.header, encode_index(p.entries).size(), data);
  return p;
}

// PSNR of the image the pass decodes to: its indices dequantized as the decoder does
// (pc_dequantize_block), inverse transformed, compared as measure_psnr compares.
double pass_psnr(const ImageView& image, const ImagePlan& plan, const Pass& p) {
  const Extent& dims = plan.header.dims;
  const float delta = float(plan.header.delta);
  std::vector<std::vector<float>> planes(p.q.size(), std::vector<float>(dims[0] * dims[1], 0.0f));
  plan.executor->run(plan.blocks.size(), [&](std::size_t i) {
    const CodeBlock& b = plan.blocks[i];
    pc_dequantize_block(b, p.q[b.component].data(), planes[b.component].data(), dims[0],
                        p.steps[b.component * plan.bands.size() + b.band], delta);
  });
  for (auto& c : planes) inverse(*plan.transform, c.data(), dims, plan.header.levels, 0, *plan.executor);
  return components_psnr(image, planes, plan.header.colour, plan.header.nonnegative);
}

// The pass at log step t scored by `score` (falling as t grows), or nullopt when t is too fine
// for the coder's index range.
template <class Score>
std::optional<Pass> scored_pass(ImagePlan& plan, double t, const Score& score) {
  try {
    Pass p = code_pass(plan, t);
    p.score = score(p);
    return p;
  } catch (const IndexRangeError&) {
    return std::nullopt;
  }
}

// The next log step aiming the score at `aim`: the secant through the bracket's ends (kept in
// its inner 80%), else the secant through the last two passes (`last`, `before`; slope within
// 1/4 .. 4 times `slope`), else `slope` from the last pass.
double next_t(const std::optional<Pass>& fine, const std::optional<Pass>& coarse, const Pass& last,
              const std::optional<Pass>& before, double aim, double slope) {
  if (fine && coarse) {
    const double ds = coarse->score - fine->score, dt = coarse->t - fine->t;
    double t = ds < 0.0 ? fine->t + (aim - fine->score) * dt / ds : 0.5 * (fine->t + coarse->t);
    return std::clamp(t, fine->t + 0.1 * dt, coarse->t - 0.1 * dt);
  }
  if (before && before->t != last.t)
    slope = std::clamp((last.score - before->score) / (last.t - before->t), 4.0 * slope, 0.25 * slope);
  return last.t + std::clamp((aim - last.score) / slope, -4.0 * std::numbers::ln2, 4.0 * std::numbers::ln2);
}

// The pass closest to `goal` on the side where ok(score) holds: coarser passes score lower, and
// ok holds above the goal (PSNR) or below it (log bytes, `below`). nullopt when no pass between
// `finest` and `coarsest` is ok.
template <class Score>
std::optional<Pass> search(ImagePlan& plan, double t, double goal, double tolerance, bool below, double slope,
                           double finest, double coarsest, const Score& score) {
  const auto ok = [&](double s) { return below ? s <= goal : s >= goal; };
  const auto close = [&](double s) { return below ? s >= goal - tolerance : s <= goal + tolerance; };
  const double aim = below ? goal - 0.5 * tolerance : goal + 0.5 * tolerance;
  std::optional<Pass> fine, coarse, best;  // fine: smaller step, higher score
  std::optional<Pass> before;              // the pass before the last (its t and score)
  for (int n = 0;; ++n) {
    t = std::clamp(t, finest, coarsest);
    std::optional<Pass> p = scored_pass(plan, t, score);
    if (!p) {  // too fine for the index range: a PSNR this fine is out of reach; a budget moves coarser
      if (!below) return best;
      finest = t + std::numbers::ln2;
      if (finest > coarsest) return best;
      t = finest;
      continue;
    }
    const bool fits = ok(p->score);
    if (fits && (!best || std::abs(p->score - goal) < std::abs(best->score - goal))) best = *p;
    if (fits && close(p->score)) return best;
    // The pass on the side it lies of the goal (the bracket narrows).
    Pass last;
    last.t = p->t;
    last.score = p->score;
    if (p->score > goal)
      fine = std::move(p);
    else
      coarse = std::move(p);
    // A miss at the end of the step range: nothing can fit.
    const std::optional<Pass>& miss = below ? fine : coarse;
    if (!best && miss && (below ? miss->t >= coarsest : miss->t <= finest)) return best;
    if (n + 1 >= kMaxTrials && best) return best;
    const double next = next_t(fine, coarse, last, before, aim, slope);
    before = last;
    // Past the trial budget with nothing fitting yet: an octave towards fitting at least.
    if (n + 1 >= kMaxTrials)
      t = below ? std::max(next, t + std::numbers::ln2) : std::min(next, t - std::numbers::ln2);
    else
      t = next;
    if (fine && coarse && coarse->t - fine->t < 1e-6) return best;
  }
}

EncodeResult result_of(const ImageView& image, ImagePlan& plan, Pass& p, std::optional<double> psnr) {
  plan.header.steps = p.steps;
  if (!psnr && plan.measure_psnr) psnr = pass_psnr(image, plan, p);
  auto bytes = assemble(plan, p.entries, p.words);
  const double base = std::exp(p.t);
  release_coefficients(plan);
  return make_encode_result(image, plan, std::move(bytes), base,
                            psnr ? psnr : std::optional<double>(std::nan("")));
}

}  // namespace

EncodeResult encode_pc(const ImageView& image, ImagePlan& plan, const EncodeOptions& options) {
  if (plan.header.reversible || options.mode == RateMode::lossless)
    throw std::invalid_argument("the pc coder codes lossy streams only (--bpp, --psnr or --step)");
  plan.header.delta = std::round(kPcDelta * 65536.0) / 65536.0;  // as the header stores it
  transform_all_components(plan);
  const double finest = std::log(plan.peak * kFinestStep), coarsest = std::log(plan.peak * 4.0);
  if (options.mode == RateMode::step) {
    Pass p = code_pass(plan, std::log(options.target));
    return result_of(image, plan, p, std::nullopt);
  }
  if (options.mode == RateMode::bpp) {
    const double budget = std::floor(options.target * double(plan.pixels) / 8.0);
    const double guess = guess_base_step(plan, 0, budget / double(plan.header.channels), 1.0);
    auto best = search(plan, std::log(std::max(guess, plan.peak * kFinestStep)), std::log(budget),
                       -std::log1p(-kSizeTolerance), true, kSizeSlope, finest, coarsest,
                       [](const Pass& p) { return std::log(double(p.bytes)); });
    if (best) return result_of(image, plan, *best, std::nullopt);
    // Under the smallest stream (header and steps alone): that stream, as the other coders do.
    Pass smallest = code_pass(plan, coarsest);
    return result_of(image, plan, smallest, std::nullopt);
  }
  const double mse = plan.peak * plan.peak / std::pow(10.0, options.target / 10.0);
  const double t0 = std::log(std::sqrt(12.0 * mse));  // a uniform quantizer's error step^2 / 12
  auto best = search(plan, t0, options.target, kPsnrTolerance, false, kPsnrSlope, finest, coarsest,
                     [&](const Pass& p) { return pass_psnr(image, plan, p); });
  if (!best)
    throw TargetRangeError("PSNR " + format_number(options.target) +
                           " dB is beyond the precision of lossy coding");
  const double reached = best->score;
  return result_of(image, plan, *best, reached);
}

}  // namespace pupwave

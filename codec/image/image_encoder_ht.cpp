// encode_image with the ht back end: every block is one codeword at the plan's steps, so a
// byte budget or PSNR target is met by searching the base step: a secant on log(step) from the
// rate model's step, kept inside the bracket of the trials so far (bisection when the secant
// leaves it). Each trial codes every block (fast: no arithmetic coding).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <tuple>

#include "codec/entropy/ht_blocks.h"
#include "codec/image/image_encoder_ht.h"
#include "codec/rate/rate_guess.h"

namespace pupwave {
namespace {

// Trial encodes for a byte budget; a file within kSizeTolerance below the budget ends the search.
constexpr int kMaxSizeTrials = 12;
constexpr double kSizeTolerance = 0.01;
// The size search first runs on a sample of the blocks (a quarter of those of bands with
// kSampleWhole blocks or more) until it predicts the goal within kSampleClose (log units).
constexpr std::size_t kSampleEvery = 4;
constexpr std::size_t kSampleWhole = 16;
constexpr int kMaxSampleTrials = 6;
constexpr double kSampleClose = 0.003;
// Trial encodes (each decoded and measured) for a PSNR target, met within kPsnrTolerance dB above.
constexpr int kMaxPsnrTrials = 12;
constexpr double kPsnrTolerance = 0.05;
// Before those, the step is found on the PSNR the quantization error predicts (no decode):
// at most kMaxEstimateSteps passes, until within kEstimateClose dB.
constexpr int kMaxEstimateSteps = 8;
constexpr double kEstimateClose = 0.01;
// Where the secant has one point only: bytes ~ step^-1.5 and PSNR falls 20 log10(2) dB per
// doubling of the step (typical of the photographs at 0.25-2 bpp).
constexpr double kSizeSlope = -1.5;
constexpr double kPsnrSlope = -20.0 / std::numbers::ln10;
// Indices from this on are beyond the coder (2^kMaxBitPlanes): quantize clamps them here so
// ht_encode_block reports them.
constexpr float kIndexLimit = 1073741824.0f;

// Signed quantization indices of block i: floor(|v| / step) with v's sign, as quantize().
void block_indices(const ImagePlan& plan, std::size_t i, std::vector<std::int32_t>& q) {
  const CodeBlock& b = plan.blocks[i];
  q.resize(b.count());
  if (plan.header.reversible) {
    copy_block_out(plan.icoef[b.component].data(), plan.header.dims, b, q.data());
    return;
  }
  thread_local std::vector<float> values;
  values.resize(b.count());
  copy_block_out(plan.coef[b.component].data(), plan.header.dims, b, values.data());
  const float inv = 1.0f / plan.header.steps[b.component * plan.bands.size() + b.band];
  for (std::size_t k = 0; k < values.size(); ++k) {
    const float m = std::fabs(values[k]) * inv;
    const auto index = std::int32_t(m < kIndexLimit ? m : kIndexLimit);  // NaN too
    q[k] = values[k] < 0.0f ? -index : index;
  }
}

// Every block coded at the plan's steps.
struct Coded {
  std::vector<BlockEntry> entries;
  std::vector<std::vector<std::uint8_t>> words;
  std::size_t data_bytes = 0;
  bool over = false;  // stopped: the codewords exceeded the byte limit
};

// Codes the blocks `ids` into `out` (on the executor's threads).
void code_blocks(const ImagePlan& plan, const std::vector<std::size_t>& ids, Coded& out,
                 std::size_t byte_limit) {
  std::atomic<std::size_t> total{out.data_bytes};
  std::atomic<bool> over{false};
  plan.executor->run(ids.size(), [&](std::size_t k) {
    if (over.load(std::memory_order_relaxed)) return;
    const std::size_t i = ids[k];
    thread_local std::vector<std::int32_t> q;
    block_indices(plan, i, q);
    const CodeBlock& b = plan.blocks[i];
    HtCodeword w = ht_encode_block(q, b.size[0], b.size[1]);
    out.entries[i] = {w.planes, w.planes > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
    if (total.fetch_add(w.bytes.size()) + w.bytes.size() > byte_limit) over = true;
    out.words[i] = std::move(w.bytes);
  });
  out.data_bytes = total.load();
  out.over = over.load();
}

Coded code_all(ImagePlan& plan, double base) {
  if (!plan.header.reversible) set_base_step(plan, base);
  Coded out;
  out.entries.resize(plan.blocks.size());
  out.words.resize(plan.blocks.size());
  std::vector<std::size_t> ids(plan.blocks.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  code_blocks(plan, ids, out, std::numeric_limits<std::size_t>::max());
  return out;
}

std::size_t file_size(const ImagePlan& plan, const Coded& c) {
  return container_size(plan.header, encode_index(c.entries).size(), c.data_bytes);
}

// Lossless and --step encodes: one component transformed at a time (its blocks coded, then its
// buffer reused), stopping once the codewords exceed `byte_limit`.
std::optional<std::vector<std::uint8_t>> code_once(ImagePlan& plan, std::size_t byte_limit) {
  Coded out;
  out.entries.resize(plan.blocks.size());
  out.words.resize(plan.blocks.size());
  for (std::size_t c = 0; c < plan.header.channels; ++c) {
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (plan.blocks[i].component == c) ids.push_back(i);
    transform_component(plan, c);
    code_blocks(plan, ids, out, byte_limit);
    release_component(plan, c);
    if (out.over) break;
  }
  release_coefficients(plan);
  if (out.over) return std::nullopt;
  return assemble(plan, out.entries, out.words);
}

// One trial of a step search: the step (log), what it scored, and its coded blocks.
struct Trial {
  double log_step = 0.0;
  double score = 0.0;  // log(bytes) or PSNR
  Coded coded;
};

// The next log step of a search for `goal` (the score falls as the step grows): the secant
// through the two trials bracketing the goal, or from the one trial with `slope`, kept strictly
// inside the bracket (its middle where the secant leaves the inner half-open region).
double next_step(const std::optional<Trial>& low, const std::optional<Trial>& high, double goal,
                 double slope) {
  // low: a step whose score is above the goal (finer); high: one below (coarser).
  if (low && high) {
    const double span = high->log_step - low->log_step;
    const double s = (high->score - low->score) / span;
    double t = s < 0.0 ? low->log_step + (goal - low->score) / s : 0.5 * (low->log_step + high->log_step);
    if (!(t > low->log_step + 0.05 * span && t < high->log_step - 0.05 * span))
      t = 0.5 * (low->log_step + high->log_step);
    return t;
  }
  const Trial& one = low ? *low : *high;
  double t = one.log_step + (goal - one.score) / slope;
  // One side only: move at least 1/64 octave and at most 4 octaves away from it.
  const double move = std::clamp(t - one.log_step, -4.0 * std::numbers::ln2, 4.0 * std::numbers::ln2);
  const double least = std::numbers::ln2 / 64.0;
  return one.log_step + (low ? std::max(move, least) : std::min(move, -least));
}

// The base step the rate model gives for `budget` bytes over all components.
double model_step(const ImagePlan& plan, double budget) {
  MagnitudeHistogram total;
  std::mutex lock;
  plan.executor->run(plan.blocks.size(), [&](std::size_t i) {
    const CodeBlock& b = plan.blocks[i];
    thread_local std::vector<float> values;
    values.resize(b.count());
    copy_block_out(plan.coef[b.component].data(), plan.header.dims, b, values.data());
    auto h = std::make_unique<MagnitudeHistogram>();
    h->add(values, magnitude_scale(plan, b.component, b.band));
    const std::lock_guard<std::mutex> hold(lock);
    total.merge(*h);
  });
  return guess_base_step(total, budget, 1.0);
}

// Blocks standing for all in the step search: each (component, band) with few blocks whole,
// about one in kSampleEvery of the others, each weighted by how many it stands for.
struct Sample {
  std::vector<std::size_t> ids;
  std::vector<double> weights;
};

Sample sample_blocks(const ImagePlan& plan) {
  std::vector<std::vector<std::size_t>> groups(plan.header.channels * plan.bands.size());
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    groups[plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band].push_back(i);
  Sample s;
  for (const auto& g : groups) {
    // Hashed picks, not every kSampleEvery-th: a regular pick can alias with the picture
    // (the benchmark mosaic repeats photographs every 4 blocks of the first level).
    const auto picked = [&](std::size_t k) {
      return g.size() < kSampleWhole || ((std::uint32_t(k) * 2654435761u) >> 24) % kSampleEvery == 0;
    };
    std::size_t taken = 0;
    for (std::size_t k = 0; k < g.size(); ++k) taken += picked(k);
    for (std::size_t k = 0; k < g.size(); ++k)
      if (picked(k)) {
        s.ids.push_back(g[k]);
        s.weights.push_back(double(g.size()) / double(taken));
      }
  }
  return s;
}

// The file size the sample predicts at base step exp(t): weighted codeword bytes, and the
// index bytes of the sampled entries scaled to all blocks.
double sampled_size(ImagePlan& plan, const Sample& sample, double t) {
  set_base_step(plan, std::exp(t));
  Coded out;
  out.entries.resize(plan.blocks.size());
  out.words.resize(plan.blocks.size());
  code_blocks(plan, sample.ids, out, std::numeric_limits<std::size_t>::max());
  double data = 0.0;
  std::vector<BlockEntry> entries;
  for (std::size_t k = 0; k < sample.ids.size(); ++k) {
    data += sample.weights[k] * double(out.words[sample.ids[k]].size());
    entries.push_back(out.entries[sample.ids[k]]);
  }
  const double index =
      double(encode_index(entries).size()) * double(plan.blocks.size()) / double(entries.size());
  return double(container_size(plan.header, 0, 0)) + index + data;
}

// The log step at which the sample predicts `goal` bytes (a secant on log size over log step
// from `t`), and the local slope of log size over log step.
std::pair<double, double> sample_search(ImagePlan& plan, double goal, double t) {
  const Sample sample = sample_blocks(plan);
  double size = std::log(sampled_size(plan, sample, t)), slope = kSizeSlope;
  for (int n = 0; n < kMaxSampleTrials && std::abs(size - std::log(goal)) > kSampleClose; ++n) {
    const double move =
        std::clamp((std::log(goal) - size) / slope, -4.0 * std::numbers::ln2, 4.0 * std::numbers::ln2);
    const double next = std::log(sampled_size(plan, sample, t + move));
    if (next != size && std::abs(move) > 1e-9) slope = std::clamp((next - size) / move, -8.0, -0.25);
    t += move;
    size = next;
  }
  return {t, slope};
}

// Largest file within `budget` bytes (the smallest step that fits): the sample's step, then
// full trials from there (a secant with the sample's slope, inside the bracket found).
std::pair<std::vector<std::uint8_t>, double> search_size(ImagePlan& plan, double budget) {
  const double goal = budget * (1.0 - 0.5 * kSizeTolerance);
  const double coarsest = std::log(plan.peak * 4.0);
  const double model = std::clamp(model_step(plan, budget), plan.peak * kFinestStep, plan.peak * 4.0);
  auto [t, slope] = sample_search(plan, goal, std::log(model));
  t = std::min(t, coarsest);
  std::optional<Trial> low, high;  // low: over the budget; high: within it (the answer)
  for (int n = 0; n < kMaxSizeTrials || !high; ++n) {
    Trial trial{t, 0.0, code_all(plan, std::exp(t))};
    const double size = double(file_size(plan, trial.coded));
    trial.score = std::log(size);
    if (size <= budget) {
      high = std::move(trial);
      if (size >= budget * (1.0 - kSizeTolerance)) break;
    } else {
      low = std::move(trial);
    }
    // Nothing fits even with every index zero: the smallest file there is.
    if (!high && t >= coarsest) return {assemble(plan, low->coded.entries, low->coded.words), std::exp(t)};
    const double next = next_step(low, high, std::log(goal), slope);
    // Past the trial budget with nothing within it yet: an octave coarser at least.
    t = std::min(n + 1 >= kMaxSizeTrials && !high ? std::max(next, t + std::numbers::ln2) : next, coarsest);
  }
  return {assemble(plan, high->coded.entries, high->coded.words), std::exp(high->log_step)};
}

// The PSNR the quantization alone predicts at base step exp(t), without coding or decoding: a
// unit index error costs base^2 of output squared error in every band (quantizer.h).
double estimated_psnr(ImagePlan& plan, double t) {
  set_base_step(plan, std::exp(t));
  std::vector<double> sums(plan.blocks.size());
  const float delta = float(plan.header.delta);
  plan.executor->run(plan.blocks.size(), [&](std::size_t i) {
    const CodeBlock& b = plan.blocks[i];
    thread_local std::vector<float> values;
    values.resize(b.count());
    copy_block_out(plan.coef[b.component].data(), plan.header.dims, b, values.data());
    const float inv = 1.0f / plan.header.steps[b.component * plan.bands.size() + b.band];
    double sum = 0.0;
    for (const float v : values) {
      const float m = std::fabs(v) * inv, q = std::floor(m);
      const float e = m - (q == 0.0f ? 0.0f : q + delta);
      sum += double(e) * double(e);
    }
    sums[i] = sum;
  });
  double total = 0.0;
  for (const double s : sums) total += s;  // in block order: the same sum on any thread count
  const double mse = total * std::exp(2.0 * t) / double(plan.samples);
  return 10.0 * std::log10(plan.peak * plan.peak / std::max(mse, 1e-300));
}

// The log step at which the estimate meets `goal` (a secant from t): where the real trials start.
double estimate_search(ImagePlan& plan, double goal, double t, double finest) {
  double score = estimated_psnr(plan, t), slope = kPsnrSlope;
  for (int n = 0; n < kMaxEstimateSteps && std::abs(score - goal) > kEstimateClose; ++n) {
    const double move = std::clamp((goal - score) / slope, -4.0 * std::numbers::ln2, 4.0 * std::numbers::ln2);
    const double next_t = std::max(t + move, finest);
    if (next_t == t) break;
    const double next = estimated_psnr(plan, next_t);
    if (next != score) slope = std::clamp((next - score) / (next_t - t), -20.0, -2.0);
    t = next_t;
    score = next;
  }
  return t;
}

// The coarsest step found whose decoded PSNR reaches `psnr` (within kPsnrTolerance above it
// when the trials allow).
std::pair<std::vector<std::uint8_t>, double> search_psnr(const ImageView& image, ImagePlan& plan, double psnr,
                                                         double& reached) {
  const double finest = std::log(plan.peak * kFinestStep);
  // A uniform quantizer's error is step^2 / 12 in index units times base^2 (quantizer.h).
  const double mse = plan.peak * plan.peak / std::pow(10.0, psnr / 10.0);
  double t = std::max(std::log(std::sqrt(12.0 * mse)), finest);
  t = estimate_search(plan, psnr + 0.5 * kPsnrTolerance, t, finest);
  std::optional<Trial> low, high;  // low: reaches the target (the answer); high: misses it
  std::vector<std::uint8_t> best;
  for (int n = 0; n < kMaxPsnrTrials || !low; ++n) {
    Trial trial{t, 0.0, code_all(plan, std::exp(t))};
    auto bytes = assemble(plan, trial.coded.entries, trial.coded.words);
    trial.score = measure_psnr(image, bytes, *plan.executor);
    if (trial.score >= psnr) {
      best = std::move(bytes);
      low = std::move(trial);
      if (low->score <= psnr + kPsnrTolerance) break;
    } else {
      high = std::move(trial);
      if (t <= finest)
        throw TargetRangeError("PSNR " + format_number(psnr) + " dB is beyond the precision of lossy coding");
    }
    if (n + 1 >= kMaxPsnrTrials && low) break;
    const double next = next_step(low, high, psnr + 0.5 * kPsnrTolerance, kPsnrSlope);
    // Past the trial budget with no step reaching the target yet: an octave finer at least.
    t = std::max(n + 1 >= kMaxPsnrTrials ? std::min(next, t - std::numbers::ln2) : next, finest);
  }
  reached = low->score;
  return {std::move(best), std::exp(low->log_step)};
}

}  // namespace

EncodeResult encode_ht(const ImageView& image, ImagePlan& plan, const EncodeOptions& options,
                       std::size_t byte_limit) {
  if (options.mode == RateMode::lossless || options.mode == RateMode::step) {
    const double base = options.mode == RateMode::step ? options.target : 1.0;
    if (!plan.header.reversible) set_base_step(plan, base);
    auto bytes = code_once(plan, byte_limit);
    if (!bytes) return {};
    return make_encode_result(image, plan, std::move(*bytes), base);
  }
  transform_all_components(plan);  // the step search codes every block several times
  std::vector<std::uint8_t> bytes;
  double base = 1.0;
  if (options.mode == RateMode::bpp) {
    std::tie(bytes, base) = search_size(plan, std::floor(options.target * double(plan.pixels) / 8.0));
    release_coefficients(plan);
    return make_encode_result(image, plan, std::move(bytes), base);
  }
  double reached = 0.0;
  std::tie(bytes, base) = search_psnr(image, plan, options.target, reached);
  release_coefficients(plan);
  return make_encode_result(image, plan, std::move(bytes), base, reached);
}

}  // namespace pupwave

// encode_image with the ht back end: every block is one codeword at the plan's steps, so a
// byte budget or PSNR target is met by choosing steps. Integer images at a byte budget stream
// (search_size_streamed): a survey pass gives the rate model and a sample of blocks, the sample
// picks a step, and one strip-wise pass codes every block at that step and one a little
// coarser, each band taking either; only codewords are held. Other sources, and PSNR targets,
// hold the transformed components and search the base step with full trials: a secant on
// log(step), kept inside the bracket of the trials so far (bisection when it leaves it).
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <numeric>
#include <optional>
#include <span>
#include <thread>
#include <tuple>
#include <utility>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "codec/entropy/ht_blocks.h"
#include "codec/image/image_encoder_ht.h"
#include "codec/image/image_strip_encoder.h"
#include "codec/image/rate_guess.h"
#include "codec/rate/byte_budget.h"

namespace pupwave {
namespace {

// Trial encodes for a byte budget; a file within kSizeTolerance below the budget ends the search.
constexpr int kMaxSizeTrials = 12;
// The lossless attempt against a lossy budget (code_once) gives up once the first
// kHopelessAfter of the blocks project a stream kHopeless times over the budget.
constexpr double kHopelessAfter = 0.0625;
constexpr double kHopeless = 2.0;
constexpr double kSizeTolerance = 0.01;
// The size search first runs on a sample of the blocks (a quarter of those of bands with
// kSampleWhole blocks or more) until it predicts the goal within kSampleClose (log units).
constexpr std::size_t kSampleEvery = 4;
constexpr std::size_t kSampleWhole = 16;
// A streamed encode holds its sample's coefficients: one block in kStreamSampleEvery.
constexpr std::size_t kStreamSampleEvery = 8;
// Images of two kStripePeriod or more rows are surveyed by stripes (survey_stripes).
constexpr std::size_t kStripeRows = 256;
constexpr std::size_t kStripePeriod = 1024;
// Stripes, their edges extended, predict 3-6% more bytes than the whole image (both mosaics at
// 0.25-2 bpp; the pair's range absorbs the rest of the spread).
constexpr double kStripeBias = 0.955;
constexpr int kMaxSampleTrials = 6;
constexpr double kSampleClose = 0.003;
// Streamed size search (search_size_streamed): each pass codes every block at a fine step and
// one kPairRatio coarser (about 12% fewer bytes), the fine step aimed kPairAim over the budget
// (the sample's miss on the mosaics and photographs is -1% to +3%); at most kMaxPairPasses
// passes once one fits.
constexpr double kPairRatio = 1.0905;  // 2^(1/8)
constexpr double kPairAim = 1.015;
constexpr int kMaxPairPasses = 4;
// A sample of more bytes than this is freed while a pass runs and surveyed again where another
// pass follows (the grey 4096^2 mosaic's takes 8.7 MB, a third of its 2 bpp encode's
// heap); a smaller one is held (a survey again costs a quarter of a pass's transform or more).
constexpr std::size_t kHeldSampleBytes = std::size_t(1) << 20;
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

// Signed quantization indices of block i from its coefficients (x fastest): floor(|v| / step)
// with v's sign, as quantize(); reversible plans code the coefficients themselves.
void indices_of(const ImagePlan& plan, std::size_t i, std::span<const float> values,
                std::vector<std::int32_t>& q) {
  const CodeBlock& b = plan.blocks[i];
  q.resize(values.size());
  const float inv = 1.0f / plan.header.steps[b.component * plan.bands.size() + b.band];
  for (std::size_t k = 0; k < values.size(); ++k) {
    const float m = std::fabs(values[k]) * inv;
    const auto index = std::int32_t(m < kIndexLimit ? m : kIndexLimit);  // NaN too
    q[k] = values[k] < 0.0f ? -index : index;
  }
}

void indices_of(const ImagePlan&, std::size_t, std::span<const std::int32_t> values,
                std::vector<std::int32_t>& q) {
  q.assign(values.begin(), values.end());
}

// The same for block i of the transformed components held in the plan.
void block_indices(const ImagePlan& plan, std::size_t i, std::vector<std::int32_t>& q) {
  const CodeBlock& b = plan.blocks[i];
  if (plan.header.reversible) {
    q.resize(b.count());
    copy_block_out(plan.icoef[b.component].data(), plan.header.dims, b, q.data());
    return;
  }
  thread_local std::vector<float> values;
  values.resize(b.count());
  copy_block_out(plan.coef[b.component].data(), plan.header.dims, b, values.data());
  indices_of(plan, i, std::span<const float>(values), q);
}

// Every block coded at the plan's steps.
struct Coded {
  std::vector<BlockEntry> entries;
  std::vector<std::vector<std::uint8_t>> words;
  std::size_t data_bytes = 0;
  std::size_t blocks_coded = 0;  // by stream_blocks
  bool over = false;             // stopped: the codewords exceeded the byte limit
};

// Codes block i from its indices `q` into `out`; adds its bytes to `total` and sets `over` when
// that passes `byte_limit`.
void code_block(const ImagePlan& plan, std::size_t i, const std::vector<std::int32_t>& q, Coded& out,
                std::atomic<std::size_t>& total, std::atomic<bool>& over, std::size_t byte_limit) {
  const CodeBlock& b = plan.blocks[i];
  HtCodeword w = ht_encode_block(q, b.size[0], b.size[1]);
  out.entries[i] = {w.planes, w.planes > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
  if (total.fetch_add(w.bytes.size()) + w.bytes.size() > byte_limit) over = true;
  // The writer's buffer grows by doubling: held as it is, a pass's codewords would take 1.4 times
  // their bytes (the pair's codewords are the largest part of a 2 bpp encode).
  w.bytes.shrink_to_fit();
  out.words[i] = std::move(w.bytes);
}

// Codes the blocks `ids` into `out` (on the executor's threads).
void code_blocks(const ImagePlan& plan, const std::vector<std::size_t>& ids, Coded& out,
                 std::size_t byte_limit) {
  std::atomic<std::size_t> total{out.data_bytes};
  std::atomic<bool> over{false};
  plan.executor->run(ids.size(), [&](std::size_t k) {
    if (over.load(std::memory_order_relaxed)) return;
    thread_local std::vector<std::int32_t> q;
    block_indices(plan, ids[k], q);
    code_block(plan, ids[k], q, out, total, over, byte_limit);
  });
  out.data_bytes = total.load();
  out.over = over.load();
}

// Codes every block of component c from the strip-wise transform (image_strip_encoder.h), so
// the component is never whole in memory; stops between strips once over `byte_limit`, or
// (a trial against a limit) once the blocks coded so far, a kHopelessAfter share of the
// image's at least, project kHopeless times the limit for the whole image: blocks complete
// top down, finest first, so the projection errs low unless the image's top is its busiest.
template <class T>
void stream_blocks(const ImagePlan& plan, std::size_t c, Coded& out, std::size_t byte_limit) {
  std::atomic<std::size_t> total{out.data_bytes}, coded{out.blocks_coded};
  std::atomic<bool> over{false};
  const bool trial = byte_limit != std::numeric_limits<std::size_t>::max();
  const double all = double(plan.blocks.size());
  const auto hopeless = [&] {
    const double n = double(coded.load());
    return trial && n >= kHopelessAfter * all &&
           double(total.load()) * all > kHopeless * double(byte_limit) * n;
  };
  stream_component<T>(
      plan, c,
      [&](std::size_t i, std::span<const T> values) {
        if (over.load(std::memory_order_relaxed)) return;
        thread_local std::vector<std::int32_t> q;
        indices_of(plan, i, values, q);
        code_block(plan, i, q, out, total, over, byte_limit);
        ++coded;
      },
      [&] {
        if (hopeless()) over = true;
        return over.load(std::memory_order_relaxed);
      });
  out.data_bytes = total.load();
  out.blocks_coded = coded.load();
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

// Returns the pages of freed memory to the system (glibc's malloc_trim; elsewhere nothing):
// the allocator keeps the pages of many small freed codewords resident otherwise.
void return_freed_pages() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

// The stream of `c` (assemble's bytes), each codeword freed once copied into it and the
// freed pages returned every 1/16 of the stream (1 MiB at least), so the codewords and the
// stream are not both held whole (assemble holds them and a copy of the payloads).
std::vector<std::uint8_t> assemble_freeing(const ImagePlan& plan, Coded& c) {
  return_freed_pages();  // what the caller released before: the stream may take its place
  std::vector<std::size_t> sizes(std::size_t(plan.header.levels) + 1, 0);
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    sizes[std::size_t(plan.blocks[i].resolution)] += c.words[i].size();
  const std::size_t step =
      std::max(std::accumulate(sizes.begin(), sizes.end(), std::size_t(0)) / 16, std::size_t(1) << 20);
  std::size_t pending = 0;
  return write_container(plan.header, c.entries, sizes, [&](std::size_t r, std::vector<std::uint8_t>& out) {
    for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
      if (std::size_t(plan.blocks[i].resolution) != r) continue;
      out.insert(out.end(), c.words[i].begin(), c.words[i].end());
      pending += c.words[i].size();
      std::vector<std::uint8_t>().swap(c.words[i]);
      if (pending >= step) {
        pending = 0;
        return_freed_pages();
      }
    }
  });
}

// Lossless and --step encodes: by strips where the plan allows (strip_reach), else one
// component transformed at a time (its blocks coded, then its buffer reused), stopping once the
// codewords exceed `byte_limit` (a lossless attempt against a lossy budget mostly stops early).
std::optional<std::vector<std::uint8_t>> code_once(ImagePlan& plan, std::size_t byte_limit) {
  Coded out;
  out.entries.resize(plan.blocks.size());
  out.words.resize(plan.blocks.size());
  for (std::size_t c = 0; c < plan.header.channels && !out.over; ++c) {
    if (plan.strip_reach > 0) {
      if (plan.header.reversible)
        stream_blocks<std::int32_t>(plan, c, out, byte_limit);
      else
        stream_blocks<float>(plan, c, out, byte_limit);
      continue;
    }
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (plan.blocks[i].component == c) ids.push_back(i);
    transform_component(plan, c);
    code_blocks(plan, ids, out, byte_limit);
    release_component(plan, c);
  }
  release_coefficients(plan);
  if (out.over) return std::nullopt;
  return assemble_freeing(plan, out);
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

// Signed indices of `values` at step 1 / inv (as indices_of); returns the squared error in
// index units. Four samples at a time (GCC/Clang vector extensions: a scalar loop does not
// vectorize and costs 13% of an encode), summed in a fixed order: the same on any thread.
double quantize_error(std::span<const float> values, float inv, float delta, std::vector<std::int32_t>& q) {
  using F4 = float __attribute__((vector_size(16)));
  using I4 = std::int32_t __attribute__((vector_size(16)));
  const std::size_t n = values.size();
  q.resize(n);
  const float* v = values.data();
  std::int32_t* out = q.data();
  const F4 vinv = F4{} + inv, limit = F4{} + kIndexLimit, vdelta = F4{} + delta;
  F4 acc = {};
  std::size_t k = 0;
  for (; k + 4 <= n; k += 4) {
    F4 x;
    std::memcpy(&x, v + k, sizeof x);
    const F4 m = (x < 0.0f ? -x : x) * vinv;
    const I4 index = __builtin_convertvector(m < limit ? m : limit, I4);  // NaN: limit
    const I4 signed_index = x < 0.0f ? -index : index;
    std::memcpy(out + k, &signed_index, sizeof signed_index);
    const F4 e = m - (index == 0 ? F4{} : __builtin_convertvector(index, F4) + vdelta);
    acc += e * e;
  }
  double sum = double(acc[0]) + double(acc[1]) + double(acc[2]) + double(acc[3]);
  for (; k < n; ++k) {
    const float m = std::fabs(v[k]) * inv;
    const auto index = std::int32_t(m < kIndexLimit ? m : kIndexLimit);  // NaN too
    out[k] = v[k] < 0.0f ? -index : index;
    const float e = m - (index == 0 ? 0.0f : float(index) + delta);
    sum += double(e) * double(e);
  }
  return sum;
}

// Blocks standing for all in the step search: each (component, band) with few blocks whole,
// about one in kSampleEvery of the others, each weighted by how many it stands for. `values`:
// their coefficients where the components are not held in the plan (streamed encodes).
struct Sample {
  std::vector<std::size_t> ids;
  std::vector<double> weights;
  std::vector<std::vector<float>> values;
  // Surveyed by stripes (survey_stripes): blocks of other plans, each with its (component,
  // band) unit and extent; ids is then empty and weights are per unit.
  std::vector<std::size_t> units;
  std::vector<std::array<std::size_t, 2>> sizes;
};

// Bytes of the coefficients a sample holds (streamed encodes).
std::size_t sample_bytes(const Sample& s) {
  std::size_t n = 0;
  for (const auto& v : s.values) n += v.size() * sizeof(float);
  return n;
}

Sample sample_blocks(const ImagePlan& plan, std::size_t every = kSampleEvery) {
  std::vector<std::vector<std::size_t>> groups(plan.header.channels * plan.bands.size());
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    groups[plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band].push_back(i);
  Sample s;
  for (const auto& g : groups) {
    // Hashed picks, not every kSampleEvery-th: a regular pick can alias with the picture
    // (the benchmark mosaic repeats photographs every 4 blocks of the first level).
    const auto picked = [&](std::size_t k) {
      return g.size() < kSampleWhole || ((std::uint32_t(k) * 2654435761u) >> 24) % every == 0;
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
  const bool striped = !sample.units.empty();
  const std::size_t n = striped ? sample.units.size() : sample.ids.size();
  std::vector<BlockEntry> entries(n);
  const float delta = float(plan.header.delta);
  plan.executor->run(n, [&](std::size_t k) {
    thread_local std::vector<std::int32_t> q;
    std::array<std::size_t, 2> size{};
    if (striped) {
      quantize_error(sample.values[k], 1.0f / plan.header.steps[sample.units[k]], delta, q);
      size = sample.sizes[k];
    } else {
      const CodeBlock& b = plan.blocks[sample.ids[k]];
      if (sample.values.empty())
        block_indices(plan, sample.ids[k], q);
      else
        indices_of(plan, sample.ids[k], std::span<const float>(sample.values[k]), q);
      size = {b.size[0], b.size[1]};
    }
    const HtCodeword w = ht_encode_block(q, size[0], size[1]);
    entries[k] = {w.planes, w.planes > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
  });
  double data = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    data += sample.weights[striped ? sample.units[k] : k] * double(entries[k].length);
  const double index = double(encode_index(entries).size()) * double(plan.blocks.size()) / double(n);
  return double(container_size(plan.header, 0, 0)) + (index + data) * (striped ? kStripeBias : 1.0);
}

// The log step at which the sample predicts `goal` bytes (a secant on log size over log step
// from `t`, the slope of log size over log step starting at `slope`); returns it and the slope.
std::pair<double, double> sample_search(ImagePlan& plan, const Sample& sample, double goal, double t,
                                        double slope) {
  double size = std::log(sampled_size(plan, sample, t));
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

// Magnitude histograms of the rate model, one per executor thread (a block's merged into a
// shared one cost as much as the counting), added up at the end (counts: any order).
class ThreadHistograms {
 public:
  MagnitudeHistogram& mine() {
    const std::lock_guard<std::mutex> hold(lock_);
    for (auto& [id, h] : parts_)
      if (id == std::this_thread::get_id()) return *h;
    parts_.emplace_back(std::this_thread::get_id(), std::make_unique<MagnitudeHistogram>());
    return *parts_.back().second;
  }
  MagnitudeHistogram total() const {
    MagnitudeHistogram sum;
    for (const auto& part : parts_) sum.merge(*part.second);
    return sum;
  }

 private:
  std::mutex lock_;
  std::vector<std::pair<std::thread::id, std::unique_ptr<MagnitudeHistogram>>> parts_;
};

// Codes every block at base step exp(t): a full trial of the size search.
using FullTrial = std::function<Coded(double t)>;

// Largest file within `budget` bytes (the smallest step that fits) from the rate model's step
// `model`: the sample's step, then full trials from there. After a full trial the sample is
// searched again for the goal corrected by how far the sample missed that trial's size, kept
// inside the bracket of the full trials so far (bisection where it leaves it).
std::pair<std::vector<std::uint8_t>, double> search_size(ImagePlan& plan, const Sample& sample, double model,
                                                         double budget, const FullTrial& full) {
  const double goal = budget * (1.0 - 0.5 * kSizeTolerance);
  const double coarsest = std::log(plan.peak * 4.0);
  model = std::clamp(model, plan.peak * kFinestStep, plan.peak * 4.0);
  auto [t, slope] = sample_search(plan, sample, goal, std::log(model), kSizeSlope);
  t = std::min(t, coarsest);
  std::optional<Trial> low, high;  // low: over the budget; high: within it (the answer)
  for (int n = 0; n < kMaxSizeTrials || !high; ++n) {
    Trial trial{t, 0.0, full(t)};
    const double size = double(file_size(plan, trial.coded));
    trial.score = std::log(size);
    if (size <= budget) {
      high = std::move(trial);
      if (size >= budget * (1.0 - kSizeTolerance)) break;
    } else {
      low = std::move(trial);
    }
    // Nothing fits even with every index zero: the smallest file there is.
    if (!high && t >= coarsest) return {assemble_freeing(plan, low->coded), std::exp(t)};
    double next = next_step(low, high, std::log(goal), slope);
    if (n + 1 < kMaxSizeTrials) {
      // The sample's miss at t (log units) holds nearly unchanged for steps close by.
      const double miss = std::log(size) - std::log(sampled_size(plan, sample, t));
      const double aimed = sample_search(plan, sample, goal * std::exp(-miss), t, slope).first;
      const double lo = low ? low->log_step : -1e300, hi = high ? high->log_step : 1e300;
      if (aimed > lo && aimed < hi) next = aimed;
    }
    // Past the trial budget with nothing within it yet: an octave coarser at least.
    t = std::min(n + 1 >= kMaxSizeTrials && !high ? std::max(next, t + std::numbers::ln2) : next, coarsest);
  }
  low.reset();  // its codewords: the stream may take their place
  return {assemble_freeing(plan, high->coded), std::exp(high->log_step)};
}

// Pass 1 of a streamed size search: the rate model's step and the sampled blocks' coefficients
// from the strip-wise transform (no component is ever whole in memory).
std::pair<double, Sample> survey(const ImagePlan& plan, double budget) {
  Sample sample = sample_blocks(plan, kStreamSampleEvery);
  std::vector<std::size_t> slot(plan.blocks.size(), std::size_t(-1));
  for (std::size_t k = 0; k < sample.ids.size(); ++k) slot[sample.ids[k]] = k;
  sample.values.resize(sample.ids.size());
  ThreadHistograms histograms;
  for (std::size_t c = 0; c < plan.header.channels; ++c)
    stream_component<float>(plan, c, [&](std::size_t i, std::span<const float> values) {
      if (slot[i] != std::size_t(-1)) sample.values[slot[i]].assign(values.begin(), values.end());
      histograms.mine().add(values, magnitude_scale(plan, c, plan.blocks[i].band));
    });
  const MagnitudeHistogram total = histograms.total();
  return {guess_base_step(total, budget, 1.0), std::move(sample)};
}

// The same from a kStripeRows-row stripe of every kStripePeriod rows (at offsets that do not
// repeat with the period, so a periodic picture is not sampled at one phase), each transformed
// as an image of its own (its edges extended as the image's are), one block in two of each kept:
// a quarter of the survey's transform work. Nullopt where the image is too short for stripes.
std::optional<std::pair<double, Sample>> survey_stripes(const ImagePlan& plan, const EncodeOptions& options,
                                                        double budget) {
  const std::size_t height = plan.header.dims[1], stripes = height / kStripePeriod;
  if (stripes < 2 || plan.source.row_stride <= 0) return std::nullopt;
  EncodeOptions o = options;
  o.levels = plan.header.levels;
  const std::size_t units = plan.header.channels * plan.bands.size();
  Sample sample;
  std::vector<double> counted(units, 0.0), sampled(units, 0.0);
  for (const CodeBlock& b : plan.blocks)
    counted[b.component * plan.bands.size() + b.band] += double(b.count());
  ThreadHistograms histograms;
  double surveyed = 0.0;
  for (std::size_t k = 0; k < stripes; ++k) {
    const double phase = std::fmod(0.25 + 0.6180339887 * double(k), 1.0);
    const std::size_t y0 = k * kStripePeriod + std::size_t(phase * double(kStripePeriod - kStripeRows));
    ImageView v = plan.source;
    v.data = static_cast<const std::uint8_t*>(v.data) +
             std::ptrdiff_t(y0) * v.row_stride * std::ptrdiff_t(bytes_per_sample(v.storage));
    v.height = kStripeRows;
    v.drop_rows = nullptr;
    const ImagePlan sp = plan_image(v, o);
    if (sp.bands.size() != plan.bands.size() || sp.strip_reach == 0) return std::nullopt;
    // Bands of few blocks in the stripe are kept whole.
    std::vector<std::size_t> in_band(units, 0);
    for (const CodeBlock& b : sp.blocks) ++in_band[b.component * plan.bands.size() + b.band];
    std::vector<std::vector<float>> kept(sp.blocks.size());
    for (std::size_t c = 0; c < plan.header.channels; ++c)
      stream_component<float>(sp, c, [&](std::size_t i, std::span<const float> values) {
        const CodeBlock& b = sp.blocks[i];
        histograms.mine().add(values, magnitude_scale(plan, c, b.band));
        if (in_band[b.component * plan.bands.size() + b.band] < kSampleWhole ||
            ((std::uint32_t(i) * 2654435761u) >> 24) % 2 == 0)
          kept[i].assign(values.begin(), values.end());
      });
    if (plan.source.drop_rows)
      plan.source.drop_rows(plan.source.drop_context, plan.source, y0, y0 + kStripeRows);
    for (std::size_t i = 0; i < sp.blocks.size(); ++i) {
      if (kept[i].empty()) continue;
      const CodeBlock& b = sp.blocks[i];
      const std::size_t u = b.component * plan.bands.size() + b.band;
      sampled[u] += double(kept[i].size());
      sample.units.push_back(u);
      sample.sizes.push_back({b.size[0], b.size[1]});
      sample.values.push_back(std::move(kept[i]));
    }
    surveyed += double(sp.samples);
  }
  sample.weights.resize(units);
  for (std::size_t u = 0; u < units; ++u) {
    if (counted[u] > 0.0 && sampled[u] == 0.0) return std::nullopt;  // a band the stripes missed
    sample.weights[u] = sampled[u] > 0.0 ? counted[u] / sampled[u] : 0.0;
  }
  const double fraction = surveyed / double(plan.samples);
  return std::pair<double, Sample>{guess_base_step(histograms.total(), budget * fraction, 1.0),
                                   std::move(sample)};
}

// The rate model's step and the sample of a streamed size search: by stripes where the image
// allows, else from every block.
std::pair<double, Sample> survey_any(const ImagePlan& plan, const EncodeOptions& options, double budget) {
  auto surveyed = survey_stripes(plan, options, budget);
  return surveyed ? std::move(*surveyed) : survey(plan, budget);
}

// Every block of a streamed pass coded at two base steps, exp(t) (fine) and kPairRatio times
// that (coarse), with the output squared error of each; the stream takes, per (component,
// band), either (the header stores a step per band).
struct CodedPair {
  double t = 0.0;
  Coded fine, coarse;
  std::vector<double> fine_error, coarse_error;  // per block, output units squared
};

// One strip-wise pass over every component: each block quantized and coded at both steps as
// the strips complete it; only codewords are held.
CodedPair code_pair(ImagePlan& plan, double t) {
  CodedPair p;
  p.t = t;
  const std::vector<float> fine_steps = (set_base_step(plan, std::exp(t)), plan.header.steps);
  const std::vector<float> coarse_steps = (set_base_step(plan, std::exp(t) * kPairRatio), plan.header.steps);
  const double fine2 = std::exp(2.0 * t), coarse2 = fine2 * kPairRatio * kPairRatio;
  for (Coded* c : {&p.fine, &p.coarse}) {
    c->entries.resize(plan.blocks.size());
    c->words.resize(plan.blocks.size());
  }
  p.fine_error.resize(plan.blocks.size());
  p.coarse_error.resize(plan.blocks.size());
  std::atomic<std::size_t> fine_total{0}, coarse_total{0};
  std::atomic<bool> over{false};
  const float delta = float(plan.header.delta);
  const std::size_t none = std::numeric_limits<std::size_t>::max();
  for (std::size_t c = 0; c < plan.header.channels; ++c)
    stream_component<float>(plan, c, [&](std::size_t i, std::span<const float> values) {
      thread_local std::vector<std::int32_t> q;
      const std::size_t unit = plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band;
      p.fine_error[i] = fine2 * quantize_error(values, 1.0f / fine_steps[unit], delta, q);
      code_block(plan, i, q, p.fine, fine_total, over, none);
      p.coarse_error[i] = coarse2 * quantize_error(values, 1.0f / coarse_steps[unit], delta, q);
      code_block(plan, i, q, p.coarse, coarse_total, over, none);
    });
  p.fine.data_bytes = fine_total.load();
  p.coarse.data_bytes = coarse_total.load();
  return p;
}

// The largest file within `budget` the pair gives (nullopt when even every band at the coarse
// step exceeds it): from every band fine, the bands whose coarse step costs the least error
// per byte saved switch to it until the file fits, then any switched band whose fine codewords
// fit the room left switches back (the largest first). Sets the header's steps to the choice
// and p.fine to its blocks; returns the file's size.
std::optional<std::size_t> mix_pair(ImagePlan& plan, CodedPair& p, double budget) {
  const std::size_t units = plan.header.channels * plan.bands.size();
  std::vector<double> saved(units, 0.0), cost(units, 0.0);
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    const std::size_t u = plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band;
    saved[u] += double(p.fine.entries[i].length) - double(p.coarse.entries[i].length);
    cost[u] += p.coarse_error[i] - p.fine_error[i];
  }
  std::vector<char> coarse(units, 0);
  const auto size = [&] {
    std::vector<BlockEntry> entries(plan.blocks.size());
    std::size_t data = 0;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
      const std::size_t u = plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band;
      entries[i] = coarse[u] ? p.coarse.entries[i] : p.fine.entries[i];
      data += entries[i].length;
    }
    return double(container_size(plan.header, encode_index(entries).size(), data));
  };
  std::vector<std::size_t> order;
  for (std::size_t u = 0; u < units; ++u)
    if (saved[u] > 0.0) order.push_back(u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return cost[x] * saved[y] < cost[y] * saved[x]; });
  double total = size();
  std::size_t n = 0;
  for (; total > budget && n < order.size(); ++n) {
    coarse[order[n]] = 1;
    total = size();
  }
  if (total > budget) return std::nullopt;
  // Back to fine, the units saving most first, wherever the room left holds them.
  std::vector<std::size_t> switched(order.begin(), order.begin() + std::ptrdiff_t(n));
  std::stable_sort(switched.begin(), switched.end(),
                   [&](std::size_t x, std::size_t y) { return saved[x] > saved[y]; });
  for (const std::size_t u : switched) {
    if (total + saved[u] > budget * (1.0 + 1e-3)) continue;  // cannot fit (index bytes aside)
    coarse[u] = 0;
    if (const double back = size(); back <= budget)
      total = back;
    else
      coarse[u] = 1;
  }
  set_base_step(plan, std::exp(p.t));
  const std::vector<float> fine_steps = plan.header.steps;
  set_base_step(plan, std::exp(p.t) * kPairRatio);
  for (std::size_t u = 0; u < units; ++u)
    if (!coarse[u]) plan.header.steps[u] = fine_steps[u];
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    const std::size_t u = plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band;
    if (coarse[u]) {
      p.fine.entries[i] = p.coarse.entries[i];
      p.fine.words[i] = std::move(p.coarse.words[i]);
    }
  }
  p.fine.data_bytes = 0;
  for (const BlockEntry& e : p.fine.entries) p.fine.data_bytes += e.length;
  return file_size(plan, p.fine);
}

// A mix of a pair (mix_pair) kept until the search ends: its blocks and steps, not its stream
// (assembled once, from blocks freed as they are copied).
struct Mixed {
  Coded coded;
  std::vector<float> steps;
  std::size_t size = 0;
  double t = 0.0;
};

// A byte budget by strip-wise passes: the survey, then passes coding every block at a pair of
// steps the sample predicts to bracket the budget (mix_pair), the next aimed with the sample's
// miss on this one; the file is within the budget and, unless the passes run out, within
// kSizeTolerance under it.
std::pair<std::vector<std::uint8_t>, double> search_size_streamed(ImagePlan& plan,
                                                                  const EncodeOptions& options,
                                                                  double budget) {
  auto [model, sample] = survey_any(plan, options, budget);
  const double coarsest = std::log(plan.peak * 4.0);
  model = std::clamp(model, plan.peak * kFinestStep, plan.peak * 4.0);
  // The fine step aims a little over the budget: the coarse one then falls under it.
  auto [t, slope] = sample_search(plan, sample, budget * kPairAim, std::log(model), kSizeSlope);
  t = std::min(t, coarsest);
  std::optional<Mixed> best;  // within the budget
  for (int n = 0;; ++n) {
    // Its size at t is taken first: a large sample is not held while the pass runs, and is
    // surveyed again (the same blocks, the same values) only where another pass follows.
    const double predicted = sampled_size(plan, sample, t);
    const bool freed = sample_bytes(sample) > kHeldSampleBytes;
    if (freed) sample = Sample{};
    CodedPair p = code_pair(plan, t);
    const double fine = double(file_size(plan, p.fine));
    if (const auto size = mix_pair(plan, p, budget)) {
      const bool under = double(*size) < budget * (1.0 - kSizeTolerance);
      if (!best || *size > best->size) best = Mixed{std::move(p.fine), plan.header.steps, *size, t};
      if (!under || n + 1 >= kMaxPairPasses) break;
    }
    // Nothing fits even with every index zero: the coarse file is the smallest there is.
    if (!best && t >= coarsest) {
      p.fine = Coded{};
      sample = Sample{};
      return {assemble_freeing(plan, p.coarse), std::exp(t) * kPairRatio};
    }
    const double miss = std::log(fine) - std::log(predicted);
    p = CodedPair{};  // its codewords are kept in best where they fit: the survey may take their place
    if (freed) sample = survey_any(plan, options, budget).second;
    // Passes after the first aim the fine step just within the budget (the miss is known now),
    // so a pair whose mix fell short by a band's worth needs no mixing the next time.
    const double aim = budget * (1.0 - 0.5 * kSizeTolerance);
    const double next = sample_search(plan, sample, aim * std::exp(-miss), t, slope).first;
    // Past the pass budget with nothing within it yet: an octave coarser at least.
    t = std::min(n + 1 >= kMaxPairPasses && !best ? std::max(next, t + std::numbers::ln2) : next, coarsest);
  }
  sample = Sample{};  // the last pair is freed already: the stream takes their place
  plan.header.steps = best->steps;
  return {assemble_freeing(plan, best->coded), std::exp(best->t)};
}

// The same with every component transformed and held (for sources that cannot be streamed).
std::pair<std::vector<std::uint8_t>, double> search_size_held(ImagePlan& plan, double budget) {
  transform_all_components(plan);
  const Sample sample = sample_blocks(plan);
  auto result = search_size(plan, sample, model_step(plan, budget), budget,
                            [&](double t) { return code_all(plan, std::exp(t)); });
  release_coefficients(plan);
  return result;
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
  std::vector<std::uint8_t> bytes;
  double base = 1.0;
  if (options.mode == RateMode::bpp) {
    const double budget = byte_budget(options.target, plan.pixels);
    std::tie(bytes, base) = plan.strip_reach > 0 && !plan.header.reversible
                                ? search_size_streamed(plan, options, budget)
                                : search_size_held(plan, budget);
    return make_encode_result(image, plan, std::move(bytes), base);
  }
  transform_all_components(plan);  // the step search codes every block several times
  double reached = 0.0;
  std::tie(bytes, base) = search_psnr(image, plan, options.target, reached);
  release_coefficients(plan);
  return make_encode_result(image, plan, std::move(bytes), base, reached);
}

}  // namespace pupwave

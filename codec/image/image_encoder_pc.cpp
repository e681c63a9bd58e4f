// encode_image with the pc back end. The components are transformed once and held; a coding
// pass quantizes and codes every block at one base step, one resolution at a time (the blocks
// of a resolution in parallel: their parents, the chosen indices one level coarser, are final),
// with greedy RDOQ against the models' own costs, into one set of index planes. Rate targets
// search the base step with whole passes, each step where a rate model (codec/rate/
// pc_rate_model.h: per-band magnitude histograms) calibrated by the passes so far meets the
// target. A --bpp pass is steered as it goes: before each band of its two finest resolutions the
// bands left take the step that projects the file into the byte window (within kSteerReach), or
// the pass stops there when it cannot land (a calibration only); a pass that ends a little off is
// trimmed (a set of bands no other band reads coded again at a step of their own). About 1.5
// passes a search, where a plain secant takes 3-5.
#include "codec/image/image_encoder_pc.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_cfl.h"
#include "codec/entropy/pc_groups.h"
#include "codec/entropy/pc_priors.h"
#include "codec/error.h"
#include "codec/image/encode_stats.h"
#include "codec/image/image_components.h"
#include "codec/image/image_stream.h"
#include "codec/image/lc_parent.h"
#include "codec/image/pc_decoder.h"
#include "codec/image/pc_rate_model.h"
#include "codec/rate/byte_budget.h"
#include "codec/rate/quantizer.h"
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
// The model's residual (real minus model score) in dB before any pass: its mean on the test
// photographs. The residual's slope in log step is bounded by
// kMaxResidualSlope; a step inside a bracket keeps kBracketMargin of its width from its ends.
constexpr double kPsnrPrior = 0.0;
constexpr double kMaxResidualSlope = 0.5;
constexpr double kBracketMargin = 0.02;
// After the per-band fit the residual still grows as the step gets finer (the bands' ratios
// drift beyond what coded_bits_of_band's density shape carries): the slope in log bytes per log
// step that best predicts the next pass from one on the training photographs (it is -0.08
// with constant per-band scales).
constexpr double kBytesResidualSlope = -0.04;
// A bracket narrower than this in log step (a sixth of the byte window's width) ends the search.
constexpr double kNarrowestBracket = 5e-4;
// A trim (trim()) moves the steps of a set of bands by at most kTrimReach (log), in at most
// kTrimTries codings of those bands, when they hold kTrimShare of the bytes at least.
constexpr double kTrimReach = 0.125;
constexpr double kTrimShare = 0.03;
constexpr int kTrimTries = 3;
constexpr int kTrimSearches = 2;  // failed trims (each up to kTrimTries codings) before none
// A PSNR search whose base steps straddle a jump over the window (at low rates a band's RDOQ
// turning a block on or off moves the PSNR by tenths of a dB: 0.5 dB on a 256 x 256 crop of
// camera.png near 20 dB) moves the step of one band of a bracket's end by up to kBandReach
// (log): the kBandCandidates bands with the most bytes, in at most kBandPasses codings in all,
// shared by the ends (one end may sit at a jump of every band it tries).
constexpr double kBandReach = 0.25;
constexpr int kBandPasses = 16;
constexpr int kBandCandidates = 3;
// The coarsest base step a search tries, times the peak: coarse enough that the lowest PSNR
// targets (20 dB on the test photographs, where 4 x the peak still codes the coarse band at
// 21.7 dB) are met within the PSNR window.
constexpr double kCoarsestStep = 64.0;
// A band's model is scaled to its real bytes when it estimates at least this many.
constexpr double kFitBytes = 16.0;
// A --bpp pass is checked before each band of its last kAbandonGroups groups (the two finest
// resolutions' luma, Cb and Cr groups): the bytes of the bands coded, with the model of the rest
// scaled as they are, project its file. Before a quarter of the samples are coded, a pass whose
// projection, even steered, misses the byte window by more than kEarlyMargin (log) is abandoned
// (at most kAbandonPasses in a search).
constexpr int kAbandonGroups = 6;
constexpr double kEarlyMargin = 0.01;
constexpr int kAbandonPasses = 2;  // in a search; then every pass is coded whole
// At those checkpoints the bands left may be steered by up to this factor (log) in step: a pass
// that lands within the byte window saves a second one, while steps that move further from the
// others' cost rate-distortion (0.075 against 0.05 to 0.25 measured on the training, test and
// held-out photographs).
constexpr double kSteerReach = 0.075;

// One coding pass: every block's entry and codeword (its indices stay in the coder's planes
// until the next pass).
struct Pass {
  double t = 0.0;  // log base step
  std::vector<float> steps;
  std::vector<BlockEntry> entries;
  std::vector<std::vector<std::uint8_t>> words;
  std::vector<PcCfl> cfl;   // per block: its chroma-from-luma weights (none for most)
  std::size_t bytes = 0;    // the whole file (an abandoned pass: the projection's)
  double score = 0.0;       // log bytes or PSNR, by the search
  std::vector<bool> coded;  // per band (as shift): coded (all of them unless abandoned)
  bool abandoned = false;   // stopped before its finest groups: no stream, only a calibration
  // Per band (component x bands + band, as the steps): its log step's offset from t, non-zero
  // where the pass was steered (Coder::checkpoint moved the finest groups' steps).
  std::vector<double> shift;
  double band_t(std::size_t k) const { return t + shift[k]; }
  // The log steps a plain pass would need to be finer (lo) or coarser (hi) than this one in
  // every band: t for an unsteered pass, the bracket ends a steered one stands for.
  double finest_t() const { return t + std::min(0.0, *std::min_element(shift.begin(), shift.end())); }
  double coarsest_t() const { return t + std::max(0.0, *std::max_element(shift.begin(), shift.end())); }
  bool steered() const { return finest_t() != coarsest_t(); }
};

// The passes' shared state: one set of index planes (Mallat layout per component), which hold
// the last pass coded, and the reconstruction planes of the PSNR measurement, reused by every
// pass that measures.
struct Coder {
  const ImageView& image;
  ImagePlan& plan;
  std::vector<std::vector<std::int32_t>> q;
  double held = std::nan("");  // t of the pass q holds
  std::vector<std::vector<float>> recon;
  // Per block, the chroma-from-luma choice of the first pass that weighed it (0: not yet, 1:
  // without, 2: with the prediction, by pc_cfl_pays' estimate): later passes keep it.
  std::vector<std::int8_t> choice;
  // Asked before each of the last groups of a pass (the finest resolutions, most of the samples):
  // it may move the steps of the groups left (plan.header.steps, the pass's steps and shift) to
  // steer the pass into the byte window, or return true to abandon the pass there (its
  // projection set in the pass), which a search then takes as a calibration only. None for
  // --step and --psnr.
  std::function<bool(Pass&)> checkpoint;
  // The search's cost so far (EncodeStats' pc figures; trims also decide when a search stops
  // trying them): whole passes, trims, and the samples of abandoned passes in passes.
  int passes = 0;
  int trims = 0;
  double abandoned_share = 0.0;
};

// The Cb block of Cr block i (same band, same place).
std::size_t cb_block(const ImagePlan& plan, std::size_t i) {
  const CodeBlock& b = plan.blocks[i];
  for (std::size_t j = 0; j < plan.blocks.size(); ++j) {
    const CodeBlock& o = plan.blocks[j];
    if (o.component == 1 && o.band == b.band && o.offset == b.offset) return j;
  }
  throw std::logic_error("pc encoder: a Cr block without its Cb block");
}

// Chroma detail block i's prediction (pc_cfl.h) into `pred` (the block's samples, x fastest): the
// least-squares weights on the decoded luma (and Cb, for Cr) of the planes q at the pass's steps.
PcCfl predict_block(const ImagePlan& plan, std::size_t i, const std::vector<std::vector<std::int32_t>>& q,
                    const Pass& out, std::vector<float>& pred) {
  const CodeBlock& b = plan.blocks[i];
  const Extent& dims = plan.header.dims;
  const std::size_t per = plan.bands.size();
  const float delta = float(plan.header.delta);
  const float luma_step = out.steps[b.band], cb_step = out.steps[per + b.band];
  const PcCfl cb = b.component == 2 ? out.cfl[cb_block(plan, i)] : PcCfl{};
  thread_local std::vector<float> l, m;
  l.resize(b.count());
  m.assign(b.count(), 0.0f);
  PcCflSums sums;
  for (std::size_t y = 0; y < b.size[1]; ++y) {
    const std::size_t at = b.offset[0] + dims[0] * (b.offset[1] + y);
    const float* row = plan.coef[b.component].data() + at;
    for (std::size_t x = 0; x < b.size[0]; ++x) {
      const std::size_t k = y * b.size[0] + x;
      l[k] = pc_dequantize(q[0][at + x], luma_step, delta);
      if (b.component == 2)
        m[k] = pc_dequantize(q[1][at + x], cb_step, delta) + pc_cfl_predict(cb, l[k], 0.0f);
      sums.add(l[k], m[k], row[x]);
    }
  }
  const PcCfl k = pc_cfl_fit(sums, pc_cfl_count(b));
  pred.resize(b.count());
  for (std::size_t j = 0; j < pred.size(); ++j) pred[j] = pc_cfl_predict(k, l[j], m[j]);
  return k;
}

// Codes block i at the plan's steps with RDOQ, its parent read from (and its indices written
// to) the index planes q. A chroma detail block is coded once: with its prediction when `choice`
// (Coder::choice) says so, or, in the first pass that weighs it, when pc_cfl_pays estimates its
// residual cheaper (then `choice` keeps that for later passes); a block that codes nothing has no
// prediction (the decoder sees no weights), so a residual that codes nothing is coded again plain.
void code_block(const ImagePlan& plan, std::size_t i, std::vector<std::vector<std::int32_t>>& q, Pass& out,
                std::int8_t& choice) {
  const CodeBlock& b = plan.blocks[i];
  const Extent& dims = plan.header.dims;
  thread_local std::vector<float> u, ur, pred;
  thread_local std::vector<std::int32_t> v;  // RDOQ overwrites every index
  u.resize(b.count());
  v.resize(b.count());
  const float inv = 1.0f / plan.header.steps[b.component * plan.bands.size() + b.band];
  for (std::size_t y = 0; y < b.size[1]; ++y) {  // copy_block_out and the scaling in one go
    const float* row = plan.coef[b.component].data() + b.offset[0] + dims[0] * (b.offset[1] + y);
    float* to = u.data() + y * b.size[0];
    for (std::size_t x = 0; x < b.size[0]; ++x) to[x] = row[x] * inv;
  }
  std::int32_t* plane = q[b.component].data();
  const LcParent parent = lc_parent(plan.bands, b, plane, dims[0], nullptr);
  const PcLuma luma = pc_luma(b, q, dims[0]);
  const bool cfl = pc_cfl_applies(b, plan.header.channels);
  const PcModels* start = &pc_block_priors(plan.bands, b, plan.header.channels);
  PcCfl none;
  none.count = cfl ? pc_cfl_count(b) : 0;
  PcCfl chosen = none;
  CoefCodeword w;
  const PcCfl k = cfl && choice != 1 ? predict_block(plan, i, q, out, pred) : none;
  if (cfl && !pc_cfl_none(k)) {
    ur.resize(b.count());
    for (std::size_t y = 0; y < b.size[1]; ++y) {
      const float* row = plan.coef[b.component].data() + b.offset[0] + dims[0] * (b.offset[1] + y);
      for (std::size_t x = 0; x < b.size[0]; ++x)
        ur[y * b.size[0] + x] = (row[x] - pred[y * b.size[0] + x]) * inv;
    }
    const bool deciding = choice == 0;
    if (deciding) choice = pc_cfl_pays(u, ur, plan.header.delta, kPcLambda) ? 2 : 1;
    if (choice == 2) {
      const PcRdoq residual{ur, kPcLambda, plan.header.delta};
      w = pc_encode_block(v, b.size[0], b.size[1], parent, &residual, luma, &k, start);
      if (w.bits > 0)
        chosen = k;
      else if (deciding)  // as when both were coded: a residual that codes nothing loses for good
        choice = 1;
    }
  }
  if (pc_cfl_none(chosen)) {  // plain: no prediction, or a residual that coded nothing
    const PcRdoq rdoq{u, kPcLambda, plan.header.delta};
    w = pc_encode_block(v, b.size[0], b.size[1], parent, &rdoq, luma, cfl ? &none : nullptr, start);
    chosen = none;
  }
  copy_block_in(v.data(), dims, b, plane);
  out.cfl[i] = w.bits > 0 ? chosen : PcCfl{};
  out.entries[i] = {w.bits, w.bits > 0 ? 1 : 0, std::uint32_t(w.bytes.size())};
  out.words[i] = std::move(w.bytes);
}

// Runs `f` on the blocks `ids` (all when empty) group by group in pc_group's order (the blocks of
// one group in parallel), so every block's parent band and luma / Cb parents are final before it.
template <class F>
void by_resolution(const ImagePlan& plan, const F& f, const std::vector<std::size_t>& only = {}) {
  for (int g = 0; g < kPcGroupsPerResolution * (plan.header.levels + 1); ++g) {
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (pc_group(plan.blocks[i], plan.header.channels) == g &&
          (only.empty() || std::find(only.begin(), only.end(), i) != only.end()))
        ids.push_back(i);
    plan.executor->run(ids.size(), [&](std::size_t k) { f(ids[k]); });
  }
}

// Every block coded at base step exp(t) into the coder's planes (the blocks tile them, so
// nothing is cleared between passes). Throws IndexRangeError when an index leaves the coder's
// range.
Pass code_pass(Coder& coder, double t) {
  ImagePlan& plan = coder.plan;
  ++coder.passes;
  set_base_step(plan, std::exp(t));
  Pass p;
  p.t = t;
  p.steps = plan.header.steps;
  p.shift.assign(p.steps.size(), 0.0);
  p.entries.resize(plan.blocks.size());
  p.words.resize(plan.blocks.size());
  p.cfl.resize(plan.blocks.size());
  coder.choice.resize(plan.blocks.size(), 0);
  if (coder.q.empty())
    coder.q.assign(plan.header.channels,
                   std::vector<std::int32_t>(plan.header.dims[0] * plan.header.dims[1]));
  coder.held = std::nan("");
  p.coded.assign(p.steps.size(), false);
  std::atomic<bool> out_of_range{false};
  const int groups = kPcGroupsPerResolution * (plan.header.levels + 1);
  const std::size_t per = plan.bands.size();
  std::size_t coded = 0;  // samples
  for (int g = 0; g < groups; ++g) {
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (pc_group(plan.blocks[i], plan.header.channels) == g) ids.push_back(i);
    if (ids.empty()) continue;
    // The finest groups go band by band (a group's bands are independent), each after a
    // checkpoint, so that a steer sees the real bytes of as much of the pass as it can.
    const bool checked = coder.checkpoint && g >= groups - kAbandonGroups;
    const auto band_of = [&](std::size_t i) { return plan.blocks[i].component * per + plan.blocks[i].band; };
    std::vector<std::vector<std::size_t>> parts;
    if (!checked)
      parts = {ids};
    else
      for (std::size_t i : ids) {  // a group's blocks come band by band (plan order)
        if (parts.empty() || band_of(parts.back().front()) != band_of(i)) parts.emplace_back();
        parts.back().push_back(i);
      }
    for (const std::vector<std::size_t>& part : parts) {
      if (checked && coder.checkpoint(p)) {
        p.abandoned = true;
        --coder.passes;
        coder.abandoned_share += double(coded) / double(plan.samples);
        return p;
      }
      plan.executor->run(part.size(), [&](std::size_t k) {
        if (out_of_range) return;
        try {
          code_block(plan, part[k], coder.q, p, coder.choice[part[k]]);
        } catch (const IndexRangeError&) {
          out_of_range = true;
        }
      });
      if (out_of_range)
        throw IndexRangeError("quantization index beyond the pc coder's range (step too fine)");
      for (std::size_t i : part) {
        coded += plan.blocks[i].count();
        p.coded[band_of(i)] = true;
      }
    }
  }
  coder.held = t;
  std::size_t data = 0;
  for (const auto& w : p.words) data += w.size();
  p.bytes = container_size(plan.header, encode_index(p.entries).size(), data);
  return p;
}

// The coder's planes made to hold pass p again, by decoding its codewords as the decoder does
// (cheaper than coding it again; the indices are the same).
void hold(Coder& coder, const Pass& p) {
  if (coder.held == p.t) return;
  const ImagePlan& plan = coder.plan;
  const Extent& dims = plan.header.dims;
  by_resolution(plan, [&](std::size_t i) {
    const CodeBlock& b = plan.blocks[i];
    std::int32_t* plane = coder.q[b.component].data();
    std::int32_t* at = plane + b.offset[0] + dims[0] * b.offset[1];
    if (p.entries[i].passes == 0) {
      for (std::size_t y = 0; y < b.size[1]; ++y) std::fill_n(at + y * dims[0], b.size[0], 0);
      return;
    }
    PcCfl cfl;  // read past (p.cfl has the block's weights)
    cfl.count = pc_cfl_applies(b, plan.header.channels) ? pc_cfl_count(b) : 0;
    pc_decode_block(p.words[i], p.entries[i].planes, b.size[0], b.size[1],
                    lc_parent(plan.bands, b, plane, dims[0], nullptr), at, dims[0],
                    pc_luma(b, coder.q, dims[0]), cfl.count ? &cfl : nullptr,
                    &pc_block_priors(plan.bands, b, plan.header.channels));
  });
  coder.held = p.t;
}

// PSNR of the image the pass the planes hold decodes to: its indices dequantized as the
// decoder does (pc_dequantize_block), inverse transformed, compared as measure_psnr compares.
double pass_psnr(Coder& coder, const Pass& p) {
  const ImagePlan& plan = coder.plan;
  const Extent& dims = plan.header.dims;
  const float delta = float(plan.header.delta);
  coder.recon.resize(coder.q.size());
  for (auto& c : coder.recon) c.resize(dims[0] * dims[1]);  // every sample is written below
  for (int g = 0; g < kPcGroupsPerResolution; ++g) {  // luma before Cb before Cr: their predictions read it
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < plan.blocks.size(); ++i)
      if (pc_group(plan.blocks[i], plan.header.channels) % kPcGroupsPerResolution == g) ids.push_back(i);
    plan.executor->run(ids.size(), [&](std::size_t k) {
      const CodeBlock& b = plan.blocks[ids[k]];
      pc_dequantize_block(b, coder.q[b.component].data(), coder.recon[b.component].data(), dims[0],
                          p.steps[b.component * plan.bands.size() + b.band], delta);
      if (!pc_cfl_none(p.cfl[ids[k]]))
        pc_add_prediction(b, p.cfl[ids[k]], coder.recon[0].data(), coder.recon[1].data(),
                          coder.recon[b.component].data(), dims[0]);
    });
  }
  for (auto& c : coder.recon) inverse(*plan.transform, c.data(), dims, plan.header.levels, 0, *plan.executor);
  return components_psnr(coder.image, coder.recon, plan.header.colour, plan.header.nonnegative);
}

// The pass at log step t scored by `score` (falling as t grows), or nullopt when t is too fine
// for the coder's index range.
template <class Score>
std::optional<Pass> scored_pass(Coder& coder, double t, const Score& score) {
  try {
    Pass p = code_pass(coder, t);
    p.score = score(p);
    return p;
  } catch (const IndexRangeError&) {
    return std::nullopt;
  }
}

// The secant's next log step aiming the score at `aim`, for when the model cannot say: through
// the bracket's ends (kept in its inner 80%), else through the last two passes (`last`,
// `before`; slope within 1/4 .. 4 times `slope`), else `slope` from the last pass.
double secant_t(const std::optional<Pass>& fine, const std::optional<Pass>& coarse, const Pass& last,
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

// The residual of the model against the passes (real minus model score), linear in log step
// through the last two passes (its slope bounded: the model carries the score's shape), the
// last one's with the slope `prior_slope`, or `prior` before any pass.
template <class Model>
struct Calibration {
  const Model& model;
  double prior = 0.0;
  double prior_slope = 0.0;
  std::vector<std::pair<double, double>> seen;  // (t, score) of the passes
  double residual(double t) const {
    if (seen.empty()) return prior;
    const auto& [tb, sb] = seen.back();
    const double rb = sb - model(tb);
    if (seen.size() == 1) return rb + prior_slope * (t - tb);
    const auto& [ta, sa] = seen[seen.size() - 2];
    if (std::abs(tb - ta) < 1e-9) return rb;
    const double ra = sa - model(ta);
    return rb + std::clamp((rb - ra) / (tb - ta), -kMaxResidualSlope, kMaxResidualSlope) * (t - tb);
  }
};

// The log step in [lo, hi] where model(t) + residual(t) = aim (both fall as t grows), by
// false position with the Illinois halving (the model is smooth: a few evaluations, each a
// sum over every band's bins); an end of the interval when the aim lies beyond it.
template <class Model>
double solve_model(const Calibration<Model>& cal, double aim, double lo, double hi) {
  const double r = cal.residual(0.0), slope = cal.residual(1.0) - r;  // residual(t) = r + slope t
  const auto f = [&](double t) { return cal.model(t) + r + slope * t - aim; };
  double flo = f(lo), fhi = f(hi);
  if (flo <= 0.0) return lo;
  if (fhi >= 0.0) return hi;
  int side = 0;
  for (int i = 0; i < 100 && hi - lo > 1e-5; ++i) {
    double t = (lo * fhi - hi * flo) / (fhi - flo);
    if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
    const double ft = f(t);
    if (std::abs(ft) < 1e-7) return t;  // log bytes or dB: far inside any window
    if (ft > 0.0) {
      lo = t, flo = ft;
      if (side > 0) fhi *= 0.5;
      side = 1;
    } else {
      hi = t, fhi = ft;
      if (side < 0) flo *= 0.5;
      side = -1;
    }
  }
  return 0.5 * (lo + hi);
}

// The bands a trim codes again: of the sets that no band outside reads, a detail band with the finer
// bands of its orientation (its children) and the same bands of the components that take them as
// their luma / Cb parent (pc_luma: Cb and Cr of luma's, Cr of Cb's), the one with the most bytes
// in pass p among those of at most a third of the samples.
std::vector<std::size_t> trim_bands(const ImagePlan& plan, const Pass& p) {
  const std::size_t per = plan.bands.size(), channels = plan.header.channels;
  std::vector<double> bytes(channels * per, 0.0);
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    bytes[plan.blocks[i].component * per + plan.blocks[i].band] += double(p.words[i].size());
  std::vector<std::size_t> best;
  double most = -1.0;
  for (std::size_t c0 = 0; c0 < channels; ++c0) {
    const std::size_t c1 = pc_has_luma(c0 + 1, channels) ? 3 : c0 + 1;  // the components reading c0's
    for (unsigned o = 1; o < (1u << 2); ++o)
      for (int level = 1; level <= plan.header.levels; ++level) {
        std::vector<std::size_t> set;
        std::size_t samples = 0;
        double sum = 0.0;
        for (std::size_t c = c0; c < c1; ++c)
          for (std::size_t b = 0; b < per; ++b)
            if (plan.bands[b].orientation == o && plan.bands[b].level <= level) {
              set.push_back(c * per + b);
              samples += plan.bands[b].count();
              sum += bytes[c * per + b];
            }
        if (set.empty() || 3 * samples > plan.samples) break;  // deeper sets only grow
        if (sum > most) most = sum, best = std::move(set);
      }
  }
  return best;
}

// Pass p, which missed the byte window by a little, brought into it by coding again only the
// blocks of a set of bands (trim_bands: no band outside reads them, so nothing else changes)
// at a step of their own, k x their step in p: a 1D search of log k, its first guess from the
// bands' share of the bytes. At most a third of a pass each; the steps stay within kTrimReach (log) of
// the others', so the allocation barely moves. nullopt when it does not land.
std::optional<Pass> trim(Coder& coder, Pass p, double goal, double tolerance) {
  ImagePlan& plan = coder.plan;
  const std::vector<std::size_t> bands = trim_bands(plan, p);
  std::vector<std::size_t> blocks;
  double share = 0.0;
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    if (std::find(bands.begin(), bands.end(),
                  plan.blocks[i].component * plan.bands.size() + plan.blocks[i].band) != bands.end()) {
      blocks.push_back(i);
      share += double(p.words[i].size());
    }
  share /= double(p.bytes);
  const double aim = goal - 0.5 * tolerance;
  // The bands' bytes ~ 1 / step near these rates (measured 0.75-1.25): the log step factor
  // that moves the file to the aim.
  if (share < kTrimShare || std::abs(aim - p.score) > kTrimReach * share) return std::nullopt;
  const std::vector<float> base = p.steps;
  double k0 = 0.0, s0 = p.score, k = (p.score - aim) / share;
  for (int n = 0; n < kTrimTries; ++n) {
    k = std::clamp(k, -kTrimReach, kTrimReach);
    plan.header.steps = base;
    for (std::size_t b : bands) plan.header.steps[b] = float(base[b] * std::exp(k));
    p.steps = plan.header.steps;
    coder.held = std::nan("");  // the planes hold no whole pass now
    std::atomic<bool> out_of_range{false};
    by_resolution(
        plan,
        [&](std::size_t i) {
          try {
            code_block(plan, i, coder.q, p, coder.choice[i]);
          } catch (const IndexRangeError&) {
            out_of_range = true;
          }
        },
        blocks);
    ++coder.trims;
    if (out_of_range) return std::nullopt;
    std::size_t data = 0;
    for (const auto& w : p.words) data += w.size();
    p.bytes = container_size(plan.header, encode_index(p.entries).size(), data);
    p.score = std::log(double(p.bytes));
    if (p.score <= goal && p.score >= goal - tolerance) {
      coder.held = p.t;  // the pass returned: hold() need not decode it
      return p;
    }
    // The secant through the last two tries (the untrimmed pass first), else the first guess's slope.
    const double next = std::abs(p.score - s0) > 1e-9 ? k + (aim - p.score) * (k - k0) / (p.score - s0)
                                                      : k + (p.score - aim) / share;
    k0 = k;
    s0 = p.score;
    k = next;
  }
  return std::nullopt;
}

// Pass p coded again with the step of band `band` (component x bands + band) at exp(k) times p's,
// scored by `score`; every block is coded again, since finer bands read the indices of their
// parents. nullopt when an index leaves the coder's range.
template <class Score>
std::optional<Pass> with_band_step(Coder& coder, const Pass& p, std::size_t band, double k,
                                   const Score& score) {
  ImagePlan& plan = coder.plan;
  Pass r = p;
  plan.header.steps = p.steps;
  plan.header.steps[band] = float(p.steps[band] * std::exp(k));
  r.steps = plan.header.steps;
  coder.held = std::nan("");  // the planes hold no plain pass now
  std::atomic<bool> out_of_range{false};
  by_resolution(plan, [&](std::size_t i) {
    try {
      code_block(plan, i, coder.q, r, coder.choice[i]);
    } catch (const IndexRangeError&) {
      out_of_range = true;
    }
  });
  ++coder.trims;
  if (out_of_range) return std::nullopt;
  std::size_t data = 0;
  for (const auto& w : r.words) data += w.size();
  r.bytes = container_size(plan.header, encode_index(r.entries).size(), data);
  r.score = score(r);
  return r;
}

// The bands of pass p with the most bytes, most first (kBandCandidates of them): bands that code
// many indices, whose PSNR moves in small steps with their step.
std::vector<std::size_t> busiest_bands(const ImagePlan& plan, const Pass& p) {
  const std::size_t per = plan.bands.size();
  std::vector<std::size_t> bytes(p.steps.size(), 0), order(p.steps.size());
  for (std::size_t i = 0; i < plan.blocks.size(); ++i)
    bytes[plan.blocks[i].component * per + plan.blocks[i].band] += p.words[i].size();
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return bytes[a] > bytes[b]; });
  order.resize(std::min<std::size_t>(order.size(), kBandCandidates));
  while (!order.empty() && bytes[order.back()] == 0) order.pop_back();
  return order;
}

// The PSNR window [goal, goal + kPsnrWithin] reached where plain passes jump over it: one band of
// a bracket's end (`fine` above the window, `coarse` below the goal) at a step of its own, its
// log factor k bisected between 0 and kBandReach towards the window (coarser from `fine`,
// finer from `coarse`); the nearer end first, each end its share of kBandPasses codings. nullopt
// when no band lands.
template <class Score>
std::optional<Pass> land_psnr(Coder& coder, const std::optional<Pass>& fine,
                              const std::optional<Pass>& coarse, double goal, const Score& score) {
  const auto in = [&](double s) { return s >= goal && s <= goal + kPsnrWithin; };
  std::vector<const Pass*> ends;
  for (const Pass* e : {fine ? &*fine : nullptr, coarse ? &*coarse : nullptr})
    if (e && !e->abandoned) ends.push_back(e);
  // The nearer end first: the smaller move in PSNR.
  const auto distance = [&](const Pass* e) {
    return e->score > goal ? e->score - goal - kPsnrWithin : goal - e->score;
  };
  std::sort(ends.begin(), ends.end(),
            [&](const Pass* a, const Pass* b) { return distance(a) < distance(b); });
  for (const Pass* e : ends) {
    int passes = kBandPasses / int(ends.size());
    const double dir = e->score > goal ? 1.0 : -1.0;  // coarser lowers the PSNR
    for (std::size_t band : busiest_bands(coder.plan, *e)) {
      double near = 0.0, far = kBandReach;  // |k|: near stays on e's side of the window
      for (int n = 0; n < 4 && passes > 0; ++n, --passes) {
        const double k = n == 0 ? far : 0.5 * (near + far);
        std::optional<Pass> r = with_band_step(coder, *e, band, dir * k, score);
        if (!r) {
          far = k;
          continue;
        }
        if (in(r->score)) return r;
        if ((r->score > goal) == (e->score > goal)) {
          if (n == 0) break;  // even the farthest move stays on e's side: the next band
          near = k;
        } else {
          far = k;
        }
      }
    }
  }
  return std::nullopt;
}

// The pass closest to `goal` on the side where ok(score) holds: coarser passes score lower, and
// ok holds above the goal (PSNR) or below it (log bytes, `below`). nullopt when no pass between
// `finest` and `coarsest` is ok. Each next step is where the model, calibrated by the passes so
// far, meets the aim (inside the bracket once there is one); the secant when it cannot.
template <class Score, class Model, class Refit>
std::optional<Pass> search(Coder& coder, double goal, double tolerance, bool below, double slope,
                           double finest, double coarsest, const Score& score, const Model& model,
                           double prior, double prior_slope, const Refit& refit) {
  const auto ok = [&](double s) { return below ? s <= goal : s >= goal; };
  const auto close = [&](double s) { return below ? s >= goal - tolerance : s <= goal + tolerance; };
  const double aim = below ? goal - 0.5 * tolerance : goal + 0.5 * tolerance;
  Calibration<Model> cal{model, prior, prior_slope, {}};
  std::optional<Pass> fine, coarse, best;  // fine: smaller step, higher score
  std::optional<Pass> before;              // the pass before the last (its t and score)
  double t = solve_model(cal, aim, finest, coarsest);
  double bracket = INFINITY;  // the bracket's width before the last pass
  int trims_left = kTrimSearches;
  // A PSNR search that ends outside the window (plain passes jump over it) lands with one band's
  // step moved (land_psnr) where it can.
  const auto done = [&]() -> std::optional<Pass> {
    if (below || (best && best->score <= goal + kPsnrWithin)) return best;
    if (std::optional<Pass> landed = land_psnr(coder, fine, coarse, goal, score)) return landed;
    return best;
  };
  for (int n = 0;; ++n) {
    t = std::clamp(t, finest, coarsest);
    std::optional<Pass> p = scored_pass(coder, t, score);
    if (!p) {  // too fine for the index range: a PSNR this fine is out of reach; a budget moves coarser
      if (!below) return done();
      finest = t + std::numbers::ln2;
      if (finest > coarsest) return best;
      t = std::max(finest, solve_model(cal, aim, finest, coarsest));
      continue;
    }
    refit(*p);  // the model itself calibrated by the pass, where it can be
    // A steered pass has no one step: refit has fitted the model to it (its residual is none).
    cal.seen.emplace_back(p->t, p->steered() ? model(p->t) : p->score);
    const bool fits = !p->abandoned && ok(p->score);
    if (fits && (!best || std::abs(p->score - goal) < std::abs(best->score - goal))) best = *p;
    if (fits && close(p->score)) return best;
    if (below && trims_left > 0 &&
        !p->abandoned) {  // a budget missed by a little: a trim of a few bands may land it
      const int coded = coder.trims;
      if (std::optional<Pass> trimmed = trim(coder, *p, goal, tolerance)) return trimmed;
      if (coder.trims > coded) --trims_left;  // tried and missed: bytes this jumpy (small images) stop trims
    }
    // The pass on the side it lies of the goal (the bracket narrows).
    Pass last;
    last.t = p->t;
    last.score = p->score;
    if (p->abandoned)  // a projection, not bytes: a calibration, never a bracket's end
      ;
    else if (p->score > goal)  // a steered pass: a plain one finer in every band is too
      fine = std::move(p), fine->t = fine->finest_t();
    else
      coarse = std::move(p), coarse->t = coarse->coarsest_t();
    // A miss at the end of the step range: nothing can fit.
    const std::optional<Pass>& miss = below ? fine : coarse;
    if (!best && miss && (below ? miss->t >= coarsest : miss->t <= finest)) return best;
    if (n + 1 >= kMaxTrials && best) return done();
    const double lo = fine ? fine->t : finest, hi = coarse ? coarse->t : coarsest;
    double next = solve_model(cal, aim, lo, hi);
    if (fine && coarse) {  // strictly inside the bracket: its ends are coded
      const double dt = hi - lo;
      next = std::clamp(next, lo + kBracketMargin * dt, hi - kBracketMargin * dt);
      // A bracket the model's last step did not halve (bytes that jump, a model that steps on
      // small images): bisect, so it shrinks whatever the model says.
      if (dt > 0.5 * bracket) next = 0.5 * (lo + hi);
      bracket = dt;
    } else if (next == last.t || next <= lo || next >= hi) {
      next = secant_t(fine, coarse, last, before, aim, slope);
    }
    before = last;
    // Past the trial budget with nothing fitting yet: an octave towards fitting at least.
    if (n + 1 >= kMaxTrials)
      t = below ? std::max(next, t + std::numbers::ln2) : std::min(next, t - std::numbers::ln2);
    else
      t = next;
    // A bracket this narrow that still misses the window straddles a jump in the bytes (an
    // RDOQ choice flipping a block's coding): no pass inside it lands.
    if (fine && coarse && coarse->t - fine->t < kNarrowestBracket) return done();
  }
}

EncodeResult result_of(Coder& coder, Pass& p, std::optional<double> psnr) {
  ImagePlan& plan = coder.plan;
  plan.header.steps = p.steps;
  if (!psnr && plan.measure_psnr) {
    hold(coder, p);
    psnr = pass_psnr(coder, p);
  }
  std::vector<std::vector<std::int32_t>>().swap(coder.q);
  std::vector<std::vector<float>>().swap(coder.recon);
  release_coefficients(plan);
  auto bytes = assemble(plan, p.entries, p.words);
  const double base = std::exp(p.t);
  return make_encode_result(coder.image, plan, std::move(bytes), base,
                            psnr ? psnr : std::optional<double>(std::nan("")));
}

// Adds the coder's counts to the caller's stats however the encode ends (a PSNR target beyond
// reach throws after its passes, and the caller may then code lossless).
class StatsReport {
 public:
  StatsReport(const Coder& coder, EncodeStats* stats) : coder_(coder), stats_(stats) {}
  ~StatsReport() {
    if (stats_ == nullptr) return;
    stats_->pc_passes += coder_.passes;
    stats_->pc_trims += coder_.trims;
    stats_->pc_abandoned_share += coder_.abandoned_share;
  }
  StatsReport(const StatsReport&) = delete;
  StatsReport& operator=(const StatsReport&) = delete;

 private:
  const Coder& coder_;
  EncodeStats* stats_;
};

}  // namespace

EncodeResult encode_pc(const ImageView& image, ImagePlan& plan, const EncodeOptions& options) {
  if (plan.header.reversible || options.mode == RateMode::lossless)
    throw std::invalid_argument("the pc coder codes lossy streams only (--bpp, --psnr or --step)");
  plan.header.delta = std::round(kPcDelta * 65536.0) / 65536.0;  // as the header stores it
  transform_all_components(plan);
  Coder coder{image, plan, {}, std::nan(""), {}, {}, {}};
  const StatsReport report(coder, plan.stats);
  const double finest = std::log(plan.peak * kFinestStep), coarsest = std::log(plan.peak * kCoarsestStep);
  if (options.mode == RateMode::step) {
    Pass p = code_pass(coder, std::log(options.target));
    return result_of(coder, p, std::nullopt);
  }
  const PcRateModel model(plan, plan.header.delta);
  if (options.mode == RateMode::bpp) {
    const double budget = byte_budget(options.target, plan.pixels);
    const double goal = std::log(budget), tolerance = -std::log1p(-kSizeTolerance);
    // The model of the bytes: the container's (header, steps, index; about, until a pass says),
    // each band's estimate times its scale, or a band's real bytes (`fixed`) where the model
    // gives almost nothing. The estimates carry the coder's ratio to the model by the band's
    // density (PcRateModel::coded_bits_of_band), which also calibrates the first pass.
    double container = double(container_size(plan.header, 4 * plan.blocks.size(), 0));
    std::vector<double> scale(model.band_count(), 1.0), fixed(model.band_count(), 0.0);
    const auto estimate = [&](std::size_t k, double t) {
      return model.coded_bits_of_band(k, std::exp(t)) / 8.0;
    };
    // Band k's bytes at log step t: its estimate times its scale s, or its real bytes f where the
    // model gives almost nothing.
    const auto band_bytes = [&](std::size_t k, double t, const std::vector<double>& s,
                                const std::vector<double>& f) {
      return s[k] > 0.0 ? s[k] * estimate(k, t) : f[k];
    };
    const auto bytes = [&](double t, const std::vector<double>& s, const std::vector<double>& f, double c) {
      double total = c;
      for (std::size_t k = 0; k < s.size(); ++k) total += band_bytes(k, t, s, f);
      return total;
    };
    const auto log_bytes = [&](double t) { return std::log(bytes(t, scale, fixed, container)); };
    // Each band the pass coded (its first `groups` pc groups) scaled to its bytes in it (the bands'
    // ratios differ, and their mix moves with the step); the bands it did not code (an abandoned
    // pass's finest) take their component's ratio of real to modelled bytes in its finest coded
    // level, which tracks theirs.
    const auto fit = [&](const Pass& p, std::vector<double>& s, std::vector<double>& f) {
      const std::size_t per = plan.bands.size();
      std::vector<double> real(s.size(), 0.0);
      for (std::size_t i = 0; i < plan.blocks.size(); ++i)
        real[plan.blocks[i].component * per + plan.blocks[i].band] += double(p.words[i].size());
      const std::vector<bool>& coded = p.coded;
      std::vector<int> level(plan.header.channels, 1 << 20);  // per component: its finest coded level
      for (std::size_t k = 0; k < s.size(); ++k)
        if (coded[k] && plan.bands[k % per].orientation != 0 && s[k] > 0.0)
          level[k / per] = std::min(level[k / per], plan.bands[k % per].level);
      std::vector<double> got(plan.header.channels, 0.0), modelled(plan.header.channels, 0.0);
      for (std::size_t k = 0; k < s.size(); ++k) {
        if (!coded[k] || plan.bands[k % per].level != level[k / per] || plan.bands[k % per].orientation == 0)
          continue;
        got[k / per] += real[k];
        modelled[k / per] += s[k] * estimate(k, p.band_t(k));
      }
      for (std::size_t k = 0; k < s.size(); ++k) {
        if (coded[k]) {
          const double e = estimate(k, p.band_t(k));
          s[k] = e >= kFitBytes ? real[k] / e : 0.0;
          f[k] = s[k] == 0.0 ? real[k] : 0.0;
        } else if (modelled[k / per] >= kFitBytes) {
          s[k] *= got[k / per] / modelled[k / per];
        }
      }
    };
    const auto refit = [&](const Pass& p) {
      if (!p.abandoned) {
        std::size_t data = 0;
        for (const auto& w : p.words) data += w.size();
        container = double(p.bytes - data);
      }
      fit(p, scale, fixed);
    };
    // The container of pass p with the blocks of the bands it has not coded at their bands'
    // estimates s, f (the index's size moves with the blocks' lengths).
    const auto container_of = [&](const Pass& p, const std::vector<double>& s, const std::vector<double>& f) {
      const std::size_t per = plan.bands.size();
      std::vector<BlockEntry> entries = p.entries;
      int planes = 0;
      for (std::size_t i = 0; i < plan.blocks.size(); ++i)
        if (p.coded[plan.blocks[i].component * per + plan.blocks[i].band])
          planes = std::max(planes, entries[i].planes);
      for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
        const CodeBlock& b = plan.blocks[i];
        const std::size_t k = b.component * per + b.band;
        if (p.coded[k]) continue;
        const double share = double(b.count()) / double(plan.bands[b.band].count());
        const double length = share * band_bytes(k, p.t, s, f);
        entries[i] = {length >= 1.0 ? planes : 0, length >= 1.0 ? 1 : 0, std::uint32_t(std::lround(length))};
      }
      return double(container_size(plan.header, encode_index(entries).size(), 0));
    };
    // Pass p's projected log bytes with the bands it has not coded at log step p.t + k: the
    // bands coded with their real bytes, the rest by the model fitted to them (fit), the
    // container with the rest at p.t (its index barely moves with k).
    const auto projection = [&](const Pass& p, std::vector<double>& s, std::vector<double>& f, double& c) {
      s = scale, f = fixed;
      fit(p, s, f);
      c = container_of(p, s, f);
      double coded = c;
      for (std::size_t i = 0; i < plan.blocks.size(); ++i) coded += double(p.words[i].size());
      return [&, coded](double k) {
        double total = coded;
        for (std::size_t b = 0; b < s.size(); ++b)
          if (!p.coded[b]) total += band_bytes(b, p.t + k, s, f);
        return std::log(total);
      };
    };
    // Pass p, before each band of its finest groups, steered into the byte window: the bands left
    // take the log step p.t + k (|k| <= kSteerReach) that projects the file to the aim, so a pass
    // lands without a second whole pass when the model's first step was a little off. Abandoned
    // instead, before a quarter of the samples, when even that projection misses the window by
    // more than kEarlyMargin (its projected bytes at k = 0 then stand for its own, and the model
    // of the rest is fitted by refit as here).
    const double aim = goal - 0.5 * tolerance;
    int abandons_left = kAbandonPasses;
    coder.checkpoint = [&](Pass& p) {
      std::vector<double> s, f;
      double c = 0.0;
      const auto projected = projection(p, s, f, c);
      const double at0 = projected(0.0);
      double k = 0.0;
      if (at0 > goal || at0 < goal - tolerance) {    // inside the window: the steps stay
        double lo = -kSteerReach, hi = kSteerReach;  // projected falls as k grows
        for (int i = 0; i < 40 && hi - lo > 1e-4; ++i) {
          const double mid = 0.5 * (lo + hi);
          (projected(mid) > aim ? lo : hi) = mid;
        }
        k = 0.5 * (lo + hi);
        // Bands that barely move the bytes (nearly empty ones) are not worth moving off the steps.
        if (std::abs(projected(k) - at0) < 0.25 * std::abs(at0 - aim)) k = 0.0;
      }
      const double score = projected(k);
      std::size_t n = 0;
      for (const CodeBlock& b : plan.blocks)
        if (p.coded[b.component * plan.bands.size() + b.band]) n += b.count();
      // Before a quarter of the samples are coded an abandon costs little; later a pass is
      // finished, since a trim brings a miss of a few percent in for a third of a pass at most.
      if (abandons_left > 0 && 4 * n < plan.samples &&
          (score > goal + kEarlyMargin || score < goal - tolerance - kEarlyMargin)) {
        --abandons_left;
        container = c;
        p.bytes = std::size_t(std::exp(at0));
        return true;
      }
      if (k == 0.0) return false;
      const std::vector<float> steered =
          subband_steps(std::exp(p.t + k), plan.norms, plan.weights, plan.visual);
      for (std::size_t b = 0; b < s.size(); ++b)
        if (!p.coded[b]) {
          p.shift[b] = k;
          p.steps[b] = plan.header.steps[b] = steered[b];
        }
      return false;
    };
    auto best = search(
        coder, goal, tolerance, true, kSizeSlope, finest, coarsest,
        [](const Pass& p) { return std::log(double(p.bytes)); }, log_bytes, 0.0, kBytesResidualSlope, refit);
    if (best) return result_of(coder, *best, std::nullopt);
    // Under the smallest stream (header and steps alone): that stream, as the other coders do.
    coder.checkpoint = nullptr;  // the stream itself
    Pass smallest = code_pass(coder, coarsest);
    return result_of(coder, smallest, std::nullopt);
  }
  const double samples = double(plan.samples), peak2 = plan.peak * plan.peak;
  const auto model_psnr = [&](double t) {
    const double error = model.squared_error(std::exp(t));
    return error > 0.0 ? 10.0 * std::log10(peak2 * samples / error) : 400.0;
  };
  auto best = search(
      coder, options.target, kPsnrTolerance, false, kPsnrSlope, finest, coarsest,
      [&](const Pass& p) { return pass_psnr(coder, p); }, model_psnr, kPsnrPrior, 0.0, [](const Pass&) {});
  if (!best)
    throw TargetRangeError("PSNR " + format_number(options.target) +
                           " dB is beyond the precision of lossy coding");
  const double reached = best->score;
  return result_of(coder, *best, reached);
}

}  // namespace pupwave

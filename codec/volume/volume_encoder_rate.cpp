// Rate-controlled volume coding (--bpv, --psnr): every brick is coded once at a fine base step
// (the same for all bricks, so index-unit distortions are comparable), then one PCRD slope
// threshold picks the truncation point of every code-block of every brick.
#include <cmath>
#include <vector>

#include "codec/entropy/block_encoder.h"
#include "codec/rate/byte_budget.h"
#include "codec/rate/pcrd.h"
#include "codec/volume/volume_encoder_plan.h"
#include "codec/volume/volume_outliers.h"

namespace pupwave {
namespace {

constexpr int kMaxStepRefinements = 3;
constexpr int kMaxRounds = 5;
// A PSNR beyond what the coder's index range allows at the step it implies (float volumes:
// targets past the samples' own precision) codes at a step this many times coarser, up to
// kMaxStepCoarsenings times, and the result says what it reached (a missed target, warned).
constexpr double kStepCoarsening = 4.0;
constexpr int kMaxStepCoarsenings = 16;
// Bytes per block entry assumed while choosing passes (the index is range coded).
constexpr double kIndexBytesPerBlock = 1.5;

struct Coded {
  std::vector<BrickCode> codes;
  std::vector<std::vector<HullPoint>> hulls;               // flat over (brick, block)
  std::vector<std::pair<std::size_t, std::size_t>> where;  // flat index -> (brick, block)
  double initial = 0.0;                                    // index units^2 with nothing coded
};

Coded code_all(const VolumePlan& plan, double base) {
  Coded c;
  c.codes.resize(plan.jobs.size());
  SlabRelease release(plan.jobs);  // measure_all reads the input again (from the page cache)
  plan.executor->run(plan.jobs.size(), [&](std::size_t i) {
    std::vector<double> samples;
    std::vector<std::uint8_t> active;
    brick_samples(plan.jobs[i], samples, active);
    c.codes[i].base_step = base;
    c.codes[i].coded = code_brick(plan.coding, samples, plan.jobs[i].box.size, base);
    release.done(i);
  });
  for (std::size_t i = 0; i < c.codes.size(); ++i)
    for (std::size_t k = 0; k < c.codes[i].coded.coded.size(); ++k) {
      c.hulls.push_back(rd_hull(c.codes[i].coded.coded[k]));
      c.where.emplace_back(i, k);
      c.initial += c.codes[i].coded.coded[k].initial_distortion;
    }
  return c;
}

// code_all at `base`, or at the finest coarser step whose indices fit the coder (base updated).
Coded code_all_in_range(const VolumePlan& plan, double& base) {
  for (int k = 0;; ++k, base *= kStepCoarsening) {
    try {
      return code_all(plan, base);
    } catch (const IndexRangeError&) {
      if (k == kMaxStepCoarsenings) throw;
    }
  }
}

void set_passes(Coded& c, const std::vector<int>& passes) {
  for (auto& code : c.codes) code.passes.assign(code.coded.coded.size(), 0);
  for (std::size_t f = 0; f < passes.size(); ++f)
    c.codes[c.where[f].first].passes[c.where[f].second] = passes[f];
}

double estimated_bytes(const Coded& c, const std::vector<int>& passes) {
  double n = 0.0;
  for (std::size_t f = 0; f < passes.size(); ++f)
    n += double(c.codes[c.where[f].first].coded.coded[c.where[f].second].size(passes[f])) +
         kIndexBytesPerBlock;
  return n;
}

double remaining(const Coded& c, const std::vector<int>& passes) {
  double removed = 0.0;
  for (std::size_t f = 0; f < passes.size(); ++f) {
    const EncodedBlock& b = c.codes[c.where[f].first].coded.coded[c.where[f].second];
    for (int n = 0; n < passes[f]; ++n) removed += b.distortion_drop[std::size_t(n)];
  }
  return c.initial - removed;
}

// Measures every brick's reconstruction (max error, squared error) for the chosen passes.
double measure_all(const std::vector<VolumeGrid>& grids, const VolumePlan& plan, Coded& c) {
  SlabRelease release(plan.jobs);
  plan.executor->run(c.codes.size(), [&](std::size_t i) {
    measure_brick(grids[plan.jobs[i].grid], plan.jobs[i], reconstruct_brick(plan, plan.jobs[i], c.codes[i]),
                  c.codes[i]);
    release.done(i);
  });
  double sse = 0.0;
  for (const auto& code : c.codes) sse += code.sse;
  return sse;
}

std::vector<BrickCode> for_size(const std::vector<VolumeGrid>& grids, VolumePlan& plan, double bpv) {
  const double budget = byte_budget(bpv, plan.voxels);
  double base = plan.range > 0.0 ? plan.range / 1024.0 : 1.0;
  for (int round = 0;; ++round, base /= 4.0) {
    Coded c = code_all(plan, base);
    set_passes(c, std::vector<int>(c.hulls.size(), 0));
    const double overhead = double(assemble_volumes(plan, c.codes).size());
    std::vector<int> all;
    for (const auto& h : c.hulls) all.push_back(h.empty() ? 0 : h.back().passes);
    const bool fits_all = overhead + estimated_bytes(c, all) <= 0.95 * budget;
    if (fits_all && round < kMaxStepRefinements) continue;
    double allowed = budget - overhead;
    for (int k = 0; k < kMaxRounds; ++k) {
      const auto passes = allocate_by_slope(
          c.hulls, true, [&](const std::vector<int>& p) { return estimated_bytes(c, p) <= allowed; });
      set_passes(c, passes);
      const double size = double(assemble_volumes(plan, c.codes).size());
      if (size <= budget) break;
      allowed -= size - budget;  // the index estimate was short; ask for that much less
    }
    measure_all(grids, plan, c);
    return std::move(c.codes);
  }
}

std::vector<BrickCode> for_psnr(const std::vector<VolumeGrid>& grids, VolumePlan& plan, double psnr) {
  const double peak = plan.range > 0.0 ? plan.range : 1.0;
  const double target_mse = peak * peak / std::pow(10.0, psnr / 10.0);
  double base = 0.3 * std::sqrt(target_mse);
  const double voxels = double(std::max<std::size_t>(plan.voxels, 1));  // active voxels of all grids
  Coded c = code_all_in_range(plan, base);
  double allowed = target_mse * voxels / (base * base);
  std::vector<int> best;
  for (int k = 0; k < kMaxRounds; ++k) {
    const auto passes = allocate_by_slope(
        c.hulls, false, [&](const std::vector<int>& p) { return remaining(c, p) <= allowed; });
    set_passes(c, passes);
    const double mse = measure_all(grids, plan, c) / voxels;
    if (mse <= target_mse) {
      best = passes;
      if (mse >= 0.9 * target_mse) break;
    }
    allowed *= mse > 0.0 ? target_mse / mse : 2.0;  // correct the estimate by the measurement
  }
  if (best.empty())
    for (const auto& h : c.hulls) best.push_back(h.empty() ? 0 : h.back().passes);
  set_passes(c, best);
  measure_all(grids, plan, c);
  return std::move(c.codes);
}

}  // namespace

std::vector<BrickCode> code_for_rate(const std::vector<VolumeGrid>& grids, VolumePlan& plan,
                                     const VolumeEncodeOptions& options) {
  if (options.mode == VolumeRateMode::bpv) return for_size(grids, plan, options.target);
  return for_psnr(grids, plan, options.target);
}

}  // namespace pupwave

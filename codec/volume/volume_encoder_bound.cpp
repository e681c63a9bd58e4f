// Max-error coding of one brick: one forward transform, the base step chosen from a model of
// the coded size (cheap statistics of the quantization indices) plus an estimate of the size of
// corrections the step needs (from their count), then one block coding at that step.
#include <cmath>

#include "codec/volume/volume_encoder_plan.h"
#include "codec/volume/volume_outliers.h"

namespace pupwave {
namespace {

// Base steps the search may pick, as multiples of the bound (ratio ~1.12 apart): a coarser
// step gives fewer coefficient bits but more outliers.
constexpr double kBoundStepFactors[] = {1.0, 1.12, 1.25, 1.4, 1.57, 1.76, 1.97,
                                        2.2, 2.47, 2.77, 3.1, 3.5,  3.9};
constexpr std::size_t kFactorCount = std::size(kBoundStepFactors);
constexpr std::size_t kFirstFactor = 3;  // 1.4: the best factor of most bricks is 1.25..1.76
// Coded bytes of a brick's blocks ~ a K + b L + c H (relative least squares over the bricks of
// wmag91 and a 128^3 turbulence field at bounds 1e-2..1e-4 of range and 7 step factors each,
// refitted for the coefficient coder: 2.1% rms error): K significant
// coefficients (sign and significance), L = sum of log2(index) over them (refinement bits),
// H = sum over blocks of n h(K_block / n) (where in the block they are).
constexpr double kBytesPerSignificant = 0.315;
constexpr double kBytesPerLog2Index = 0.133;
constexpr double kBytesPerMapBit = 0.075;

// Range-coded outlier list of n corrections among `voxels` ~ n (log2(voxels / n) + c) bits: the
// entropy of the positions (log2(1 / p) + log2 e per outlier at density p) plus sign, |k| and
// the coder's overhead; estimated, as coding the list for every candidate step cost ~8% of encode.
double outlier_bytes(std::size_t n, std::size_t voxels) {
  constexpr double c = 2.65;  // fitted: 2.5 and 2.85 gave files up to 0.16% larger
  if (n == 0) return 0.0;
  return double(n) * (std::log2(double(voxels) / double(n)) + c) / 8.0;
}

// One candidate step: its modelled size, the exact corrections and the error they leave. Its
// reconstruction is not kept (one buffer serves every candidate: a second one cost each thread
// 1 MiB for a pass that measuring the error with the outliers makes unnecessary).
struct Candidate {
  double bytes = 0.0;
  std::vector<Outlier> outliers;
  StoredError error;
};

// Buffers reused from brick to brick by each thread: fresh multi-megabyte vectors per
// candidate cost more in page faults than the evaluation itself.
struct Scratch {
  std::vector<float> coef;         // the brick's transform
  std::vector<float> requantized;  // a candidate's reconstruction as the decoder holds it
  Candidate best, trial;
  // Drops buffers larger than a 64^3 brick needs, so a pool thread keeps ~2 MB (the transform,
  // one float reconstruction and the outlier lists), not the hundreds a 256^3 brick takes.
  void trim() {
    constexpr std::size_t kKeptVoxels = std::size_t(1) << 18;
    if (coef.capacity() > kKeptVoxels || requantized.capacity() > kKeptVoxels) *this = Scratch{};
  }
};

template <class S>
struct BrickInput {
  const BrickCoding& coding;
  std::span<const float> coef;
  const Extent& size;
  std::span<const S> samples;
  std::span<const std::uint8_t> active;
  double bound;
  VoxelType type;
};

template <class S>
void evaluate(const BrickInput<S>& in, double base, std::vector<float>& requantized, Candidate& c) {
  IndexStats stats;
  requantize_brick(in.coding, in.coef, in.size, base, requantized, &stats);
  store_and_find_outliers(in.samples, requantized, {}, in.active, in.bound, in.type, c.outliers, &c.error);
  c.bytes = kBytesPerSignificant * stats.significant + kBytesPerLog2Index * stats.log2_sum +
            kBytesPerMapBit * stats.map_bits + outlier_bytes(c.outliers.size(), in.samples.size());
}

}  // namespace

template <class S>
BrickCode code_within_bound(const VolumePlan& plan, const VolumeGrid& grid, const BrickJob& job,
                            std::span<const S> samples, std::span<const std::uint8_t> active) {
  const double bound = plan.header.max_error;
  thread_local Scratch scratch;
  std::vector<float>& coef = scratch.coef;
  analyze_brick(plan.coding, samples, job.box.size, coef);
  const BrickInput<S> in{plan.coding, coef, job.box.size, samples, active, bound, grid.volume.type};
  Candidate& best = scratch.best;
  // Descent over the factors from the usual best: the modelled total is unimodal in practice.
  std::size_t at = kFirstFactor;
  evaluate(in, kBoundStepFactors[at] * bound, scratch.requantized, best);
  for (const std::ptrdiff_t direction : {1, -1}) {
    bool moved = false;
    for (std::size_t next = at + direction; next < kFactorCount; next += direction) {
      evaluate(in, kBoundStepFactors[next] * bound, scratch.requantized, scratch.trial);
      if (scratch.trial.bytes >= best.bytes) break;
      std::swap(best, scratch.trial);
      at = next;
      moved = true;
    }
    if (moved) break;  // the total fell going up; it rises going down
  }
  BrickCode code;
  code.base_step = kBoundStepFactors[at] * bound;
  code.coded = code_coefficients(plan.coding, coef, job.box.size, code.base_step);
  for (const auto& b : code.coded.coded) code.passes.push_back(b.pass_count());
  code.outliers = encode_outliers(best.outliers);
  code.outlier_count = best.outliers.size();
  code.max_error = best.error.max;
  code.sse = best.error.sse;
  scratch.trim();
  return code;
}

template BrickCode code_within_bound(const VolumePlan&, const VolumeGrid&, const BrickJob&,
                                     std::span<const std::uint8_t>, std::span<const std::uint8_t>);
template BrickCode code_within_bound(const VolumePlan&, const VolumeGrid&, const BrickJob&,
                                     std::span<const std::uint16_t>, std::span<const std::uint8_t>);
template BrickCode code_within_bound(const VolumePlan&, const VolumeGrid&, const BrickJob&,
                                     std::span<const float>, std::span<const std::uint8_t>);
template BrickCode code_within_bound(const VolumePlan&, const VolumeGrid&, const BrickJob&,
                                     std::span<const double>, std::span<const std::uint8_t>);

}  // namespace pupwave

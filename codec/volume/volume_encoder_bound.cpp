// Max-error coding of one brick: one forward transform, the brick coded at the base step that
// gives the fewest bytes once the voxels outside the bound are corrected explicitly.
#include <cmath>

#include "codec/volume/volume_encoder_plan.h"
#include "codec/volume/volume_outliers.h"

namespace pupwave {
namespace {

// Base steps tried per brick, as multiples of the bound: a coarser step gives fewer
// coefficient bits but more outliers; the smallest total wins.
constexpr double kBoundStepFactors[] = {1.25, 1.9, 2.8};

std::size_t code_bytes(const BrickCode& c) {
  std::size_t n = c.outliers.size();
  for (std::size_t i = 0; i < c.passes.size(); ++i) n += c.coded.coded[i].size(c.passes[i]);
  return n;
}

// Largest and squared error over the voxels that count.
void measure(std::span<const double> samples, std::span<const std::uint8_t> active,
             std::span<const double> stored, BrickCode& code) {
  code.max_error = 0.0;
  code.sse = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (!active.empty() && active[i] == 0) continue;
    const double e = std::abs(samples[i] - stored[i]);
    code.max_error = std::max(code.max_error, e);
    code.sse += e * e;
  }
}

BrickCode code_at(const BrickCoding& coding, std::span<const float> coef, const Extent& size,
                  std::span<const double> samples, std::span<const std::uint8_t> active, double bound,
                  VoxelType type, double base) {
  BrickCode code;
  code.base_step = base;
  code.coded = code_coefficients(coding, coef, size, base);
  for (const auto& b : code.coded.coded) code.passes.push_back(b.pass_count());
  std::vector<double> recon = requantized_brick(coding, coef, size, base);
  for (double& v : recon) v = to_stored(v, type);
  const auto outliers = find_outliers(samples, recon, active, bound, type);
  code.outliers = encode_outliers(outliers);
  code.outlier_count = outliers.size();
  measure(samples, active, recon, code);
  return code;
}

}  // namespace

BrickCode code_within_bound(const VolumePlan& plan, const VolumeGrid& grid, const BrickJob& job,
                            std::span<const double> samples, std::span<const std::uint8_t> active) {
  const double bound = plan.header.max_error;
  const std::vector<float> coef = analyze_brick(plan.coding, samples, job.box.size);
  BrickCode best;
  for (double f : kBoundStepFactors) {
    BrickCode c =
        code_at(plan.coding, coef, job.box.size, samples, active, bound, grid.volume.type, f * bound);
    if (best.passes.empty() || code_bytes(c) < code_bytes(best)) best = std::move(c);
  }
  return best;
}

}  // namespace pupwave

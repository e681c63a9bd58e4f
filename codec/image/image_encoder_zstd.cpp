// encode_image with the zstd back end: rate control can only move the quantizer base step,
// so bpp and PSNR targets are met by bisection on it.
#include <cmath>
#include <tuple>

#include "codec/entropy/zstd_blocks.h"
#include "codec/image/image_plan.h"
#include "codec/rate/byte_budget.h"

namespace pupwave {
namespace {

constexpr int kStepBisections = 30;

std::vector<std::uint8_t> code_with_zstd(ImagePlan& plan, double base) {
  if (!plan.header.reversible) set_base_step(plan, base);
  std::vector<std::vector<std::uint8_t>> words(plan.blocks.size());
  plan.executor->run(plan.blocks.size(), [&](std::size_t i) {
    std::vector<float> magnitude;
    std::vector<std::uint8_t> negative;
    quantize_block(plan, i, magnitude, negative);
    words[i] = zstd_encode_block(magnitude, negative);
  });
  std::vector<BlockEntry> entries(words.size());
  for (std::size_t i = 0; i < words.size(); ++i) {
    const bool coded = !words[i].empty();
    entries[i] = {coded ? 1 : 0, coded ? 1 : 0, std::uint32_t(words[i].size())};
  }
  return assemble(plan, entries, words);
}

// Bisection on log(base step) for the finest (bpp) or coarsest (PSNR) step accepted.
template <class Accept>
std::pair<std::vector<std::uint8_t>, double> bisect_step(ImagePlan& plan, bool accept_coarse,
                                                         Accept&& accept) {
  double fine = plan.peak * 1e-5, coarse = plan.peak * 4.0;
  // Fallback when nothing is accepted: the smallest file (bpp) or the best quality (PSNR).
  double best_step = accept_coarse ? coarse : fine;
  std::vector<std::uint8_t> best = code_with_zstd(plan, best_step);
  for (int i = 0; i < kStepBisections; ++i) {
    const double mid = std::sqrt(fine * coarse);
    auto bytes = code_with_zstd(plan, mid);
    const bool ok = accept(bytes);
    if (ok) {
      best = std::move(bytes);
      best_step = mid;
    }
    // For a size budget coarser steps are accepted; for a PSNR target finer ones.
    if (ok == accept_coarse)
      coarse = mid;
    else
      fine = mid;
  }
  return {best, best_step};
}

}  // namespace

EncodeResult encode_zstd(const ImageView& image, ImagePlan& plan, const EncodeOptions& options) {
  std::vector<std::uint8_t> bytes;
  double base = 1.0;
  transform_all_components(plan);  // the step search revisits every block many times
  if (options.mode == RateMode::lossless) {
    bytes = code_with_zstd(plan, 1.0);
  } else if (options.mode == RateMode::step) {
    base = options.target;
    bytes = code_with_zstd(plan, base);
  } else if (options.mode == RateMode::bpp) {
    const double budget = byte_budget(options.target, plan.pixels);
    std::tie(bytes, base) = bisect_step(
        plan, true, [&](const std::vector<std::uint8_t>& b) { return double(b.size()) <= budget; });
  } else {
    std::tie(bytes, base) = bisect_step(plan, false, [&](const std::vector<std::uint8_t>& b) {
      return measure_psnr(image, b, *plan.executor) >= options.target;
    });
  }
  release_coefficients(plan);
  // A PSNR target reports the PSNR it reached, as the bit-plane path does.
  if (options.mode == RateMode::psnr) {
    const double reached = measure_psnr(image, bytes, *plan.executor);
    return make_encode_result(image, plan, std::move(bytes), base, reached);
  }
  return make_encode_result(image, plan, std::move(bytes), base);
}

}  // namespace pupwave

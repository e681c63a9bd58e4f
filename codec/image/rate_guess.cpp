#include "codec/image/rate_guess.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

namespace pupwave {
namespace {

// Histogram of log2 magnitudes in 1/8 octave bins: the top 12 bits of a positive float
// (sign, exponent, 3 mantissa bits) are its bin, so no log is computed per coefficient.
constexpr int kBinShift = 20;
constexpr std::size_t kBins = std::size_t(1) << (32 - kBinShift);
// Bits per significant index beyond its magnitude bits: sign, significance and the zeros
// coded around it. Fitted on the photograph mosaic: the model is 0.9-1.15x the coded size of
// the first component at every pass, from 0.1 to 4 bpp.
constexpr double kOverheadBits = 4.0;

using Histogram = MagnitudeHistogram::Counts;
static_assert(std::tuple_size_v<Histogram> == kBins);

// log2 of the centre of bin k.
double bin_log2(std::size_t k) {
  const int exponent = int(k >> 3) - 127;
  return double(exponent) + std::log2(1.0 + (double(k & 7u) + 0.5) / 8.0);
}

Histogram histogram(const ImagePlan& plan, std::size_t c) {
  MagnitudeHistogram h;
  const float* plane = plan.coef[c].data();
  const Extent& dims = plan.header.dims;
  for (std::size_t b = 0; b < plan.bands.size(); ++b) {
    const Subband& band = plan.bands[b];
    const float scale = magnitude_scale(plan, c, b);
    for (std::size_t z = 0; z < band.size[2]; ++z)
      for (std::size_t y = 0; y < band.size[1]; ++y) {
        const float* row =
            plane + band.offset[0] + dims[0] * ((band.offset[1] + y) + dims[1] * (band.offset[2] + z));
        h.add(std::span<const float>(row, band.size[0]), scale);
      }
  }
  return h.counts;
}

double model_bits(const Histogram& h, double log2_base) {
  double bits = 0.0;
  for (std::size_t k = 0; k < kBins; ++k) {
    if (h[k] == 0) continue;
    const double magnitude_bits = bin_log2(k) - log2_base;
    if (magnitude_bits >= 0.0) bits += double(h[k]) * (magnitude_bits + kOverheadBits);
  }
  return bits;
}

double step_for_bits(const Histogram& h, double budget_bytes, double margin) {
  const double budget_bits = 8.0 * budget_bytes;
  // Bits fall as the step grows; bisect log2(step) over the float range in 1/64 octave.
  double lo = -150.0, hi = 130.0;
  while (hi - lo > 1.0 / 64.0) {
    const double mid = 0.5 * (lo + hi);
    (model_bits(h, mid) > budget_bits ? lo : hi) = mid;
  }
  return std::exp2(hi) / margin;
}

}  // namespace

float magnitude_scale(const ImagePlan& plan, std::size_t c, std::size_t band) {
  // Output units: index units times the base step, the same scale in every band.
  const double visual = plan.visual.empty() ? 1.0 : plan.visual[c * plan.norms.size() + band];
  return float(plan.norms[band] * std::sqrt(plan.weights[c]) * visual);
}

void MagnitudeHistogram::add(std::span<const float> values, float scale) {
  for (const float x : values) {
    const float v = std::fabs(x) * scale;
    ++counts[std::bit_cast<std::uint32_t>(v) >> kBinShift];
  }
}

void MagnitudeHistogram::merge(const MagnitudeHistogram& other) {
  for (std::size_t k = 0; k < kBins; ++k) counts[k] += other.counts[k];
}

double guess_base_step(const ImagePlan& plan, std::size_t c, double budget_bytes, double margin) {
  return step_for_bits(histogram(plan, c), budget_bytes, margin);
}

double guess_base_step(const MagnitudeHistogram& h, double budget_bytes, double margin) {
  return step_for_bits(h.counts, budget_bytes, margin);
}

}  // namespace pupwave

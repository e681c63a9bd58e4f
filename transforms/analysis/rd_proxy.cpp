#include "transforms/analysis/rd_proxy.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "transforms/norms.h"
#include "transforms/separable.h"

namespace pupwave::merit {

namespace {

std::size_t index_of(const Extent& dims, const Subband& b, std::size_t x, std::size_t y) {
  return (b.offset[0] + x) + dims[0] * (b.offset[1] + y);
}

// Quantizes band b of `coef` into `recon` (dead zone, reconstruction at (|q| + delta) step)
// and returns the zeroth-order entropy of its indices in bits.
double quantize_band(const std::vector<double>& coef, const Extent& dims, const Subband& b, double step,
                     double delta, std::vector<double>& recon) {
  std::unordered_map<long long, std::size_t> histogram;
  for (std::size_t y = 0; y < b.size[1]; ++y)
    for (std::size_t x = 0; x < b.size[0]; ++x) {
      const std::size_t i = index_of(dims, b, x, y);
      const double m = std::floor(std::abs(coef[i]) / step);
      const long long q = static_cast<long long>(std::min(m, 1e15)) * (coef[i] < 0 ? -1 : 1);
      ++histogram[q];
      recon[i] = q == 0 ? 0.0 : std::copysign((m + delta) * step, coef[i]);
    }
  const double n = static_cast<double>(b.count());
  double bits = 0;
  for (const auto& [q, count] : histogram) bits -= static_cast<double>(count) * std::log2(count / n);
  return bits;
}

double psnr_8bit(const std::vector<double>& recon, const std::vector<float>& plane) {
  double se = 0;
  for (std::size_t i = 0; i < plane.size(); ++i) {
    const double e = std::round(std::clamp(recon[i], 0.0, 255.0)) - plane[i];
    se += e * e;
  }
  const double mse = std::max(se / static_cast<double>(plane.size()), 1e-12);
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

}  // namespace

std::vector<double> default_proxy_steps() { return {0.5, 1, 2, 4, 8, 16, 32}; }

std::vector<RdProxyPoint> rd_proxy_curve(const Transform1D& t, const std::vector<float>& plane, const Extent& dims,
                                         int levels, const std::vector<double>& base_steps, double delta) {
  if (dims[2] != 1 || dims[0] * dims[1] == 0 || plane.size() != dims[0] * dims[1])
    throw std::invalid_argument("rd proxy: the plane does not match its 2-D dimensions");
  const std::vector<Subband> bands = subbands(dims, levels);
  const std::vector<double> norms = synthesis_norms(t, dims, levels);
  std::vector<double> coef(plane.begin(), plane.end());
  forward(t, coef.data(), dims, levels);
  std::vector<RdProxyPoint> curve;
  for (double base : base_steps) {
    if (!(base > 0)) throw std::invalid_argument("rd proxy: steps must be positive");
    std::vector<double> recon(coef.size());
    double bits = 0;
    for (std::size_t b = 0; b < bands.size(); ++b)
      bits += quantize_band(coef, dims, bands[b], base / norms[b], delta, recon);
    inverse(t, recon.data(), dims, levels);
    curve.push_back({bits / static_cast<double>(plane.size()), psnr_8bit(recon, plane)});
  }
  return curve;
}

}  // namespace pupwave::merit

#include "codec/image/pc_rate_model.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iterator>

#include "codec/entropy/pc_cfl.h"
#include "codec/image/rate_guess.h"

namespace pupwave {
namespace {

// Bins of 1/32 octave: bits 18 and up of a positive float (exponent and 5 mantissa bits) are
// its bin, no log per coefficient. 56 octaves from 2^-40 of the PSNR peak hold every magnitude
// a step from kFinestStep up can quantize (larger ones clamp into the top bin).
constexpr int kBinShift = 18;
constexpr int kBinsPerOctave = 32;
constexpr int kOctaves = 56;
constexpr int kBins = kOctaves * kBinsPerOctave;
// RDOQ's thresholds in index units beyond the nearest reconstruction point's (index k from
// k - 0.5 + delta): greedy RDOQ at lambda 0.1 zeroes a 1 up to about |u| 0.75 (the bits of a 1
// against a 0) and rounds larger indices down a little. The search calibrates the rest away.
constexpr double kZeroBias = 0.2;
constexpr double kRoundBias = 0.07;
// Indices from this one up are counted in octaves, each spread evenly over its width.
constexpr int kFirstOctave = 8;
// Bins wider than two indices hold a uniform error of a twelfth of a squared step.
constexpr double kUniformFrom = 2.0 * kBinsPerOctave;

// Real bytes of the pc coder over the model's (bits_of_band) in a detail band, by the model's
// log2 bits per sample of the band from -4 to 3 (linear between, flat beyond), luma and chroma,
// and in the coarse band: bytes summed over the last pass of every --bpp search (0.125-2 bpp) on
// the training photographs (tools/train/README.md).
constexpr double kLumaShare[] = {0.42, 0.44, 0.48, 0.58, 0.69, 0.78, 0.86, 0.94};
constexpr double kChromaShare[] = {0.41, 0.38, 0.54, 0.67, 0.87, 0.90, 0.93, 0.97};
constexpr double kCoarseShare = 0.95;
constexpr int kShareFrom = -4;

double cube(double x) { return x * x * x; }

// Lower edge of bin k (k >= 1) relative to 2^low.
double bin_edge(int k) {
  return std::ldexp(1.0 + double(k % kBinsPerOctave) / kBinsPerOctave, k / kBinsPerOctave);
}

}  // namespace

PcRateModel::PcRateModel(const ImagePlan& plan, double delta) : delta_(delta) {
  low_exponent_ = std::ilogb(plan.peak > 0.0 ? plan.peak : 1.0) - 40;
  const std::uint32_t first = std::uint32_t(low_exponent_ + 127) << 5;  // bin of 2^low
  const Extent& dims = plan.header.dims;
  for (std::size_t c = 0; c < plan.coef.size(); ++c)
    for (std::size_t b = 0; b < plan.bands.size(); ++b) {
      const Subband& band = plan.bands[b];
      const float scale = magnitude_scale(plan, c, b);
      std::vector<std::uint32_t> counts(kBins, 0u);
      // Cb and Cr detail bands: the residual of their chroma-from-luma prediction (pc_cfl.h),
      // fitted here on the unquantized luma and Cb (the passes fit it on the decoded ones).
      const bool predicted = pc_cfl_applies(c, band.orientation, plan.coef.size());
      const auto at = [&](std::size_t y) { return band.offset[0] + dims[0] * (band.offset[1] + y); };
      PcCfl k;
      if (predicted) {
        PcCflSums sums;
        for (std::size_t y = 0; y < band.size[1]; ++y)
          for (std::size_t x = 0; x < band.size[0]; ++x)
            sums.add(plan.coef[0][at(y) + x], c == 2 ? plan.coef[1][at(y) + x] : 0.0f,
                     plan.coef[c][at(y) + x]);
        k = pc_cfl_fit(sums, c == 2 ? 2 : 1);
      }
      for (std::size_t y = 0; y < band.size[1]; ++y) {
        const float* row = plan.coef[c].data() + at(y);
        for (std::size_t x = 0; x < band.size[0]; ++x) {
          const float v = predicted ? row[x] - pc_cfl_predict(k, plan.coef[0][at(y) + x],
                                                              c == 2 ? plan.coef[1][at(y) + x] : 0.0f)
                                    : row[x];
          const std::uint32_t bin = std::bit_cast<std::uint32_t>(std::fabs(v) * scale) >> kBinShift;
          ++counts[std::min<std::uint32_t>(bin > first ? bin - first : 0u, kBins - 1)];
        }
      }
      Band out;
      out.count = band.size[0] * band.size[1];
      out.coarse = band.orientation == 0;
      out.chroma = c > 0 && plan.header.colour != ColourTransform::none;
      if (!plan.visual.empty())
        out.error_scale =
            1.0 / (plan.visual[c * plan.bands.size() + b] * plan.visual[c * plan.bands.size() + b]);
      out.below.assign(kBins + 1, 0u);
      for (int bin = 0; bin < kBins; ++bin) out.below[bin + 1] = out.below[bin] + counts[bin];
      bands_.push_back(std::move(out));
    }
}

double PcRateModel::count_below(const Band& band, double magnitude) const {
  const double rel = std::ldexp(magnitude, -low_exponent_);
  if (!(rel > 1.0)) return 0.0;
  const int e = std::ilogb(rel);
  if (e >= kOctaves) return double(band.count);
  const double m = (std::ldexp(rel, -e) - 1.0) * kBinsPerOctave;  // 0 .. 32 inside the octave
  const int k = e * kBinsPerOctave + std::min(int(m), kBinsPerOctave - 1);
  const double f = m - std::floor(m);
  return double(band.below[k]) + f * double(band.below[k + 1] - band.below[k]);
}

double PcRateModel::band_bits(const Band& band, double step) const {
  const double n = double(band.count);
  // Indices at least k: the magnitudes over the threshold below index k.
  const auto at_least = [&](double k) {
    const double threshold = k <= 1.0 ? 0.5 + delta_ + kZeroBias : k - 0.5 + delta_ + kRoundBias;
    return n - count_below(band, threshold * step);
  };
  const auto info = [&](double m) { return m > 0.5 ? m * std::log2(n / m) : 0.0; };
  double bits = 0.0, above = n;
  for (int k = 0; k < kFirstOctave; ++k) {
    const double next = at_least(k + 1);
    bits += info(above - next);
    if (k == 0) bits += next;  // a sign per nonzero index
    above = next;
  }
  for (double lo = kFirstOctave; above > 0.5 && lo < 0x1p40; lo *= 2.0) {
    const double next = at_least(2.0 * lo);
    bits += info(above - next) + (above - next) * std::log2(lo);
    above = next;
  }
  return bits;
}

double PcRateModel::coded_bits_of_band(std::size_t k, double base_step) const {
  const Band& band = bands_[k];
  const double bits = band_bits(band, base_step);
  if (band.coarse) return kCoarseShare * bits;
  const double* share = band.chroma ? kChromaShare : kLumaShare;
  constexpr int last = int(std::size(kLumaShare)) - 1;
  const double x = bits > 0.0 ? std::log2(bits / double(band.count)) - kShareFrom : 0.0;
  if (x <= 0.0) return share[0] * bits;
  if (x >= last) return share[last] * bits;
  const int i = int(x);
  return (share[i] + (x - i) * (share[i + 1] - share[i])) * bits;
}

double PcRateModel::band_error(const Band& band, double step) const {
  const double t1 = 0.5 + delta_ + kZeroBias, shift = delta_ + kRoundBias - 0.5;
  // The cell (index) of x and its upper edge, in index units.
  const auto cell = [&](double x) { return x < t1 ? 0.0 : std::max(1.0, std::floor(x - shift)); };
  const auto upper = [&](double k) { return k == 0.0 ? t1 : k + 1.0 + shift; };
  const double unit = std::ldexp(1.0, low_exponent_) / step;  // 2^low in index units
  // Bins under 2^-8 of a step add under 2^-16 of a squared step each: left out.
  const int from = std::clamp(int(std::floor(std::log2(1.0 / 256.0 / unit) * kBinsPerOctave)), 1, kBins);
  const int to = std::clamp(int(std::floor(std::log2(kUniformFrom / unit) * kBinsPerOctave)), from, kBins);
  double error = double(band.count - band.below[to]) / 12.0;
  for (int k = from; k < to; ++k) {
    const double n = double(band.below[k + 1] - band.below[k]);
    if (n == 0.0) continue;
    const double a = bin_edge(k) * unit, b = bin_edge(k + 1) * unit;
    // Mean squared error of magnitudes uniform on [a, b): the cells it meets, integrated.
    double sum = 0.0;
    for (double x = a, q = cell(a); x < b; q += 1.0) {
      const double r = q == 0.0 ? 0.0 : q + delta_, end = std::min(b, upper(q));
      if (end > x) sum += (cube(end - r) - cube(x - r)) / 3.0;
      x = std::max(x, end);
    }
    error += n * sum / (b - a);
  }
  return error * step * step;
}

double PcRateModel::bits(double base_step, const std::vector<double>* scale) const {
  double total = 0.0;
  for (std::size_t k = 0; k < bands_.size(); ++k) {
    if (scale && (*scale)[k] == 0.0) continue;
    total += band_bits(bands_[k], base_step) * (scale ? (*scale)[k] : 1.0);
  }
  return total;
}

double PcRateModel::squared_error(double base_step) const {
  double total = 0.0;
  for (const Band& b : bands_) total += b.error_scale * band_error(b, base_step);
  return total;
}

}  // namespace pupwave

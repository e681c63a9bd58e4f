#include "codec/image/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pupwave {

double psnr_from_mse(double mse, double peak) {
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(peak * peak / mse);
}

double psnr_peak(const ImageView& reference) {
  if (reference.peak > 0.0) return reference.peak;
  if (is_integer(reference.type)) return nominal_max(reference.type);
  if (reference.plane_size() * reference.channels == 0) return 1.0;
  // The range of the finite samples: NaN and infinity (kept by --keep-nonfinite) have none.
  std::vector<float> row(reference.width);
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (std::size_t c = 0; c < reference.channels; ++c)
    for (std::size_t y = 0; y < reference.height; ++y) {
      reference.read_row(c, y, row.data());
      for (float v : row)
        if (std::isfinite(v)) {
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
    }
  const double range = double(hi) - double(lo);
  return range > 0.0 && std::isfinite(range) ? range : 1.0;
}

namespace {

// Accumulates the error of one sequence of differences.
struct ErrorSum {
  double sum_sq = 0.0;
  double max_abs = 0.0;
  std::size_t count = 0;
  void add(double diff) {
    sum_sq += diff * diff;
    max_abs = std::max(max_abs, std::abs(diff));
    ++count;
  }
  ChannelError finish(double peak) const {
    ChannelError e;
    e.mse = count ? sum_sq / double(count) : 0.0;
    e.psnr = psnr_from_mse(e.mse, peak);
    e.max_abs = max_abs;
    return e;
  }
};

// The error of one sample. Where either side is NaN or infinite, the same non-finite value
// back is exact (--keep-nonfinite codes it so) and anything else an infinite error, so the
// finite samples still get a PSNR.
double sample_error(double reference, double test) {
  if (std::isfinite(reference) && std::isfinite(test)) return reference - test;
  const bool same = (std::isnan(reference) && std::isnan(test)) || reference == test;
  return same ? 0.0 : std::numeric_limits<double>::infinity();
}

double luma_at(const Image& img, std::size_t i) {
  return 0.299 * img.plane(0)[i] + 0.587 * img.plane(1)[i] + 0.114 * img.plane(2)[i];
}

}  // namespace

ImageError compare_images(const Image& reference, const Image& test) {
  if (reference.width != test.width || reference.height != test.height || reference.channels != test.channels)
    throw std::invalid_argument("images differ in shape: " + std::to_string(reference.width) + "x" +
                                std::to_string(reference.height) + "x" + std::to_string(reference.channels) +
                                " vs " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                "x" + std::to_string(test.channels));
  if (reference.type != test.type)
    throw std::invalid_argument("images differ in sample type: " + to_string(reference.type) + " vs " +
                                to_string(test.type));
  ImageError result;
  result.peak = psnr_peak(reference);
  ErrorSum all;
  for (std::size_t c = 0; c < reference.channels; ++c) {
    ErrorSum channel;
    const float* a = reference.plane(c);
    const float* b = test.plane(c);
    for (std::size_t i = 0; i < reference.plane_size(); ++i) {
      const double d = sample_error(a[i], b[i]);
      channel.add(d);
      all.add(d);
    }
    result.channels.push_back(channel.finish(result.peak));
  }
  result.overall = all.finish(result.peak);
  result.has_luma = reference.channels == 3 || reference.channels == 4;
  if (result.has_luma) {
    ErrorSum luma;
    for (std::size_t i = 0; i < reference.plane_size(); ++i)
      luma.add(sample_error(luma_at(reference, i), luma_at(test, i)));
    result.luma = luma.finish(result.peak);
  }
  return result;
}

}  // namespace pupwave

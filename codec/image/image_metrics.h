#pragma once
// Distortion measures between two images of the same shape: MSE, PSNR, max abs error.

#include <limits>
#include <vector>

#include "codec/image/image.h"
#include "codec/image/image_view.h"

namespace pupwave {

struct ChannelError {
  double mse = 0.0;
  double psnr = std::numeric_limits<double>::infinity();  // dB; infinite when identical
  double max_abs = 0.0;
};

struct ImageError {
  double peak = 0.0;                   // the peak signal value the PSNRs use
  std::vector<ChannelError> channels;  // one per channel
  ChannelError overall;                // MSE over all samples of all channels
  bool has_luma = false;               // true for RGB and RGBA
  ChannelError luma;                   // Rec. 601 luma Y = 0.299 R + 0.587 G + 0.114 B
};

// PSNR in dB of a mean squared error against a peak value (infinity for mse == 0).
double psnr_from_mse(double mse, double peak);

// Peak value for PSNR: 2^bits - 1 for integer samples; for float samples the value range
// (max - min) of the reference, or 1.0 when the reference is constant.
double psnr_peak(const ImageView& reference);
inline double psnr_peak(const Image& reference) { return psnr_peak(view_of(reference)); }

// Compares `test` against `reference`; both must have equal width, height, channel count and
// sample type (std::invalid_argument otherwise).
ImageError compare_images(const Image& reference, const Image& test);

}  // namespace pupwave

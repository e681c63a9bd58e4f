// The coder choice shared by the CLI and the library, so both give the same bytes.
#include <cmath>
#include <limits>

#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_plan.h"

namespace pupwave {

bool pc_is_default_for(const ImageView& image) { return image.plane_size() <= kPcDefaultPixels; }

EncodeResult encode_image_default_coder(const ImageView& image, EncodeOptions options) {
  if (options.mode == RateMode::lossless) {
    options.entropy = EntropyCoder::lc;
    return encode_image(image, options);
  }
  if (options.effort != 1)  // the bit-plane coder's search: pc has one, and codes smaller
    throw std::invalid_argument("effort 2 applies to the bit-plane coder (ebcot): choose it explicitly");
  options.entropy = pc_is_default_for(image) ? EntropyCoder::pc : EntropyCoder::ebcot;
  EncodeResult first = encode_image(image, options);
  // encode_image keeps a rate target's file within the bit-plane coder's lossless stream; the
  // lossless default (lc) is smaller still (by 7-8% on photographs, by a third or more on smooth
  // images), so a target that gave the former gives lc's stream when it is the smaller, as does
  // a lossy file that may be near lc's. The check costs about a lossless encode, so only files
  // of more than a quarter of the raw size or decoded within one sample unit RMS (MSE <= 1: the
  // step is about 1 and lossy coding spends about the bits of an exact stream) pay it.
  const double raw_bytes =
      double(image.plane_size() * image.channels) * (std::log2(nominal_max(image.type) + 1.0) / 8.0);
  const auto within_a_unit = [&] {
    const double peak = psnr_peak(image);  // after is_integer: a float image's would scan it
    return std::isfinite(first.psnr) && peak * peak <= std::pow(10.0, first.psnr / 10.0);
  };
  const bool near_lossless =
      is_integer(image.type) && (double(first.bytes.size()) > raw_bytes / 4.0 || within_a_unit());
  if (!first.switched_to_lossless && !near_lossless) return first;
  EncodeOptions exact = options;
  exact.mode = RateMode::lossless;
  exact.transform = "cdf53";
  exact.entropy = EntropyCoder::lc;
  exact.measure_psnr = false;
  EncodeResult lc = encode_image(image, exact);
  lc.psnr = std::numeric_limits<double>::infinity();
  lc.switched_to_lossless = true;
  if (!(lc.bytes.size() < first.bytes.size())) return first;
  lc.target_met = meets_target(lc, options, image.plane_size());  // judged by the caller's target
  return lc;
}

}  // namespace pupwave

// The coder choice shared by the CLI and the library, so both give the same bytes.
#include <limits>

#include "codec/image/image_codec.h"

namespace pupwave {

EncodeResult encode_image_default_coder(const ImageView& image, EncodeOptions options) {
  if (options.mode == RateMode::lossless) {
    options.entropy = EntropyCoder::lc;
    return encode_image(image, options);
  }
  options.entropy = EntropyCoder::ebcot;
  EncodeResult first = encode_image(image, options);
  // A rate target that gave the bit-plane coder's lossless stream gives the lossless default
  // (lc, smaller) instead, so no rate target exceeds the lossless file.
  if (!first.switched_to_lossless) return first;
  EncodeOptions exact = options;
  exact.mode = RateMode::lossless;
  exact.transform = "cdf53";
  exact.entropy = EntropyCoder::lc;
  exact.measure_psnr = false;
  EncodeResult lc = encode_image(image, exact);
  lc.psnr = std::numeric_limits<double>::infinity();
  lc.switched_to_lossless = true;
  return lc.bytes.size() < first.bytes.size() ? lc : first;
}

}  // namespace pupwave

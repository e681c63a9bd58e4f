// fuzz_image: an image stream decoded at full resolution. Invariants: the image has the
// header's dimensions; decoding twice gives the same pixels; an integer image re-encodes
// losslessly to a stream that decodes to the same pixels (a float one to a decodable stream).
#include <cstring>
#include <stdexcept>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "fuzz_check.h"

using namespace pupwave;

namespace {

// Same shape and values (-0 equals +0: a decoder rounds small negatives of an integer image
// to -0, which every writer stores as 0; fuzz finding 1, docs/fuzzing.md).
bool same_values(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels && a.type == b.type &&
         a.samples == b.samples;
}

// Bit-identical: a decode is deterministic.
bool same_pixels(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels && a.type == b.type &&
         std::memcmp(a.samples.data(), b.samples.data(), a.samples.size() * sizeof(float)) == 0;
}

void check_reencodes(const Image& image) {
  EncodeOptions o;
  o.executor = &serial_executor();
  o.measure_psnr = false;
  if (is_integer(image.type)) {
    o.mode = RateMode::lossless;
    o.transform = "cdf53";
  } else {
    o.mode = RateMode::step;
    o.target = 1.0;
  }
  std::vector<std::uint8_t> stream;
  try {
    stream = encode_image(image, o).bytes;
  } catch (const EncodeError&) {
    // Only a float image can be refused (non-finite samples decoded from a hostile stream).
    FUZZ_CHECK(!is_integer(image.type));
    return;
  }
  const Image back = decode_image(stream, 0, serial_executor(), fuzz::kFuzzLimits);
  FUZZ_CHECK(back.width == image.width && back.height == image.height && back.channels == image.channels);
  if (is_integer(image.type)) FUZZ_CHECK(same_values(back, image));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = fuzz::as_span(data, size);
  Image image;
  try {
    image = decode_image(bytes, 0, serial_executor(), fuzz::kFuzzLimits);
  } catch (const DecodeError&) {
    return 0;
  }
  const StreamHeader h = parse_container(bytes, 0, fuzz::kFuzzLimits).header;
  FUZZ_CHECK(image.width == h.dims[0] && image.height == h.dims[1] && image.channels == h.channels);
  FUZZ_CHECK(image.type == h.type);
  FUZZ_CHECK(same_pixels(image, decode_image(bytes, 0, serial_executor(), fuzz::kFuzzLimits)));
  check_reencodes(image);
  return 0;
}

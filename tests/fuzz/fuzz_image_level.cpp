// fuzz_image_level: an image stream decoded at a reduced level taken from the first byte.
// Invariants: the image has the level's extent of the header's dimensions; decoding twice
// gives the same pixels.
#include <cstring>
#include <stdexcept>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "fuzz_check.h"
#include "transforms/separable.h"

using namespace pupwave;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int level = data[0] % 9;
  const auto bytes = fuzz::as_span(data + 1, size - 1);
  Image image;
  try {
    image = decode_image(bytes, level, serial_executor(), fuzz::kFuzzLimits);
  } catch (const DecodeError&) {
    return 0;
  } catch (const std::invalid_argument&) {  // level above the stream's levels: documented
    return 0;
  }
  const StreamHeader h = parse_container(bytes, level, fuzz::kFuzzLimits).header;
  const Extent e = level_extent(h.dims, level);
  FUZZ_CHECK(image.width == e[0] && image.height == e[1] && image.channels == h.channels);
  const Image again = decode_image(bytes, level, serial_executor(), fuzz::kFuzzLimits);
  FUZZ_CHECK(std::memcmp(image.samples.data(), again.samples.data(), image.samples.size() * sizeof(float)) ==
             0);
  return 0;
}

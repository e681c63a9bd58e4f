#pragma once
// The test photographs and their crops, shared by the tests of tests/cli_codec (every coder, the
// strip encoder and decoder, rate targets).

#include <cstddef>
#include <string>

#include "codec/image/image.h"
#include "codec/image/image_codec.h"
#include "tools/image_io.h"

namespace pupwave::test {

inline Image photo(const std::string& name) {
  return cli::read_image(std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name);
}

// The top-left w x h pixels (odd sizes exercise the ends of every level's lines).
inline Image crop(const Image& in, std::size_t w, std::size_t h) {
  Image out(w, h, in.channels, in.type);
  for (std::size_t c = 0; c < in.channels; ++c)
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) out.at(c, x, y) = in.at(c, x, y);
  return out;
}

// Options of a pc (entropy coder 4) encode at a rate target.
inline EncodeOptions pc_options(RateMode mode, double target) {
  EncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.entropy = EntropyCoder::pc;
  return o;
}

}  // namespace pupwave::test

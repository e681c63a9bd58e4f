#include "codec/format/decode_limits.h"

#include "codec/error.h"

namespace pupwave {

void check_decode_limit(std::size_t count, const DecodeLimits& limits, const char* what) {
  if (count > limits.max_pixels)
    throw DecodeError(std::string(what) + " of " + std::to_string(count) + " exceeds the decode limit of " +
                      std::to_string(limits.max_pixels) + " (raise it with --max-pixels)");
}

}  // namespace pupwave

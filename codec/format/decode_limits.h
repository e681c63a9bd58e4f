#pragma once
// The decode limit (docs/bitstream.md, Decoder bounds): a stream may describe an image or
// volume far larger than its bytes (empty code-blocks cost almost nothing), so a decoder
// refuses one whose output exceeds a cap before allocating it, as libpng and libjxl cap
// dimensions. The CLI raises it with --max-pixels.

#include <cstddef>
#include <string>

namespace pupwave {

// 2^28 pixels (a 16384 x 16384 image) or voxels (a 512 x 512 x 1024 volume).
inline constexpr std::size_t kDefaultMaxDecodePixels = std::size_t(1) << 28;

struct DecodeLimits {
  // Images: pixels (width x height) of the decoded level. Volumes: voxels of all grids at
  // full resolution (the sparse topology is restored at full resolution).
  std::size_t max_pixels = kDefaultMaxDecodePixels;
};

// Throws DecodeError naming `what`, the count and the limit when count exceeds the limit.
void check_decode_limit(std::size_t count, const DecodeLimits& limits, const char* what);

}  // namespace pupwave

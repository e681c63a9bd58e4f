#pragma once
// Decoder of coef_encoder.h: the signed quantization indices of one block from its codeword.

#include <cstdint>
#include <span>

#include "transforms/subband.h"

namespace pupwave {

// Decodes the signed indices of a block of `size` (x fastest) into `out` (size[0]*size[1]*size[2]
// values). `bits` is the block's index bit width (1..kCoefMaxBits; every decoded index is kept
// below 2^bits). Any bytes decode to something in bounded time: corrupt input gives wrong values,
// never out-of-bounds access. Throws DecodeError for `bits` or `out` out of range.
void decode_coefficients(std::span<const std::uint8_t> codeword, int bits, const Extent& size,
                         std::span<std::int32_t> out);

}  // namespace pupwave

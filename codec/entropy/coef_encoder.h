#pragma once
// Non-embedded coefficient coder of one code-block (coef_contexts.h): every quantization index
// in full, in one pass, for streams that never truncate a block (max-error volume bricks). About
// three binary decisions per coefficient instead of one per coefficient and bit-plane.

#include <cstdint>
#include <span>
#include <vector>

#include "transforms/subband.h"

namespace pupwave {

struct CoefCodeword {
  int bits = 0;                     // bit width of the largest index (0: all zero, no bytes)
  std::vector<std::uint8_t> bytes;  // the block's codeword
};

// Codes `index[i]` (< 2^kCoefMaxBits) with sign `negative[i]` (ignored for index 0), in block
// order over `size` (x fastest). Throws IndexRangeError for an index out of range.
CoefCodeword encode_coefficients(std::span<const std::uint32_t> index, std::span<const std::uint8_t> negative,
                                 const Extent& size);

}  // namespace pupwave

#pragma once
// The parent-context coefficient coder: the candidate for a lossy non-embedded entropy coder
// (entropy coder 4 in the design of bench/results/rd_issue20.md; NOT yet part of the stream
// format, nothing calls it but its tests). One pass over a detail block's quantization indices
// with the volume coefficient coder's binarisation and models (coef_contexts.h: Rice class from
// the causal neighbour magnitudes, unary high part with models, modelled top low bits, raw rest,
// sign by neighbour signs), the index of the parent (the next coarser band of the same
// orientation, already decoded) added to the activity sum and the sign context (ECECOW-style).
// Measured with bench/nonembedded_rd (coefp): with greedy RDOQ, -3.3% BD-rate against the
// default bit-plane coder on the four test photographs and -5.3% on nine held-out ones.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/entropy/coef_encoder.h"
#include "codec/entropy/lc_blocks.h"

namespace pupwave {

// Greedy rate-distortion optimised quantization inside the encoder: each index starts at the
// reconstruction point nearest its coefficient and takes the one of {nearest, nearest - 1, 0}
// with the least squared error (index units) + lambda x the bits the models would spend on it.
struct PcRdoq {
  std::span<const float> coefficients;  // the block's coefficients in index units (x / step)
  double lambda = 0.1;                  // squared index-unit error per bit (measured best: 0.1)
  double delta = 0.05;                  // the decoder's reconstruction offset (measured best: 0.05)
};

// Codes the indices `q` (`width` x `height`, x fastest) of a block whose parent is `parent`
// (LcParent's origin, stride, extent and the block's offset in its band; null origin: none).
// With `rdoq`, q is first re-chosen (and rewritten) as PcRdoq says. Throws IndexRangeError for an
// index of 2^kCoefMaxBits or more.
CoefCodeword pc_encode_block(std::vector<std::int32_t>& q, std::size_t width, std::size_t height,
                             const LcParent& parent, const PcRdoq* rdoq = nullptr);

// Decodes a codeword of `bits` (the largest index's bit length, 1 .. kCoefMaxBits) into `width` x
// `height` indices at `out` (row y at out + y * stride). Throws DecodeError unless the largest
// decoded index has bit length `bits`.
void pc_decode_block(std::span<const std::uint8_t> codeword, int bits, std::size_t width, std::size_t height,
                     const LcParent& parent, std::int32_t* out, std::size_t stride);

}  // namespace pupwave

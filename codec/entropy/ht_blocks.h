#pragma once
// The high-throughput block coder (`--entropy ht`, entropy coder 2 in docs/bitstream.md): one
// pass over a code-block's quantization indices in raster order with no arithmetic coding.
// A coefficient whose four causal neighbours (W, NW, N, NE) are all zero starts a run of zeros
// along its row, coded with an adaptive run length (the run mode of LOCO-I / JPEG-LS); every
// other coefficient's magnitude is a Golomb-Rice code whose parameter adapts per context, the
// context being the bit length of its neighbours' weighted magnitudes. Bits are packed 64 at a
// time (ht_bits.h). One codeword per block, no truncation points: rate control moves the
// quantizer step only.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pupwave {

struct HtCodeword {
  int planes = 0;  // bit length of the largest magnitude (0: all zero, no bytes)
  std::vector<std::uint8_t> bytes;
};

// Codes `width` x `height` signed indices (x fastest). Throws IndexRangeError for a magnitude
// of 2^kMaxBitPlanes or more.
HtCodeword ht_encode_block(std::span<const std::int32_t> indices, std::size_t width, std::size_t height);

// Decodes a codeword into `width` x `height` signed indices at `out`. Throws DecodeError unless
// the codeword holds exactly that many indices (no byte more or fewer) whose largest magnitude
// has bit length `planes`.
void ht_decode_block(std::span<const std::uint8_t> codeword, std::size_t width, std::size_t height,
                     int planes, std::int32_t* out);

}  // namespace pupwave

#pragma once
// Bit-plane decoder of one code-block: the inverse of block_encoder.h, kept separate so the
// decoder stays small. Decoding needs only the block's own codeword.

#include <cstdint>
#include <span>
#include <vector>

#include "transforms/subband.h"

namespace pupwave {

// What the decoder knows of each coefficient after the coded passes.
struct DecodedBlock {
  std::vector<std::int32_t> known;      // signed magnitude bits decoded so far (lower bits 0)
  std::vector<std::uint8_t> low_plane;  // bit-plane of the last bit decoded; 255: insignificant
};

// Decodes the first `passes` coding passes of a block with `planes` bit-planes from
// `codeword`, in block order over `size`. Any bytes decode to something: corrupt input
// gives wrong values, never out-of-bounds access. Throws DecodeError if planes or passes
// are out of range.
DecodedBlock decode_block(std::span<const std::uint8_t> codeword, int planes, int passes, const Extent& size,
                          unsigned orientation);

// Reconstructed coefficient in index units: 0 when insignificant, otherwise the known bits
// plus delta of the unknown interval (or exactly the known bits when `exact` and every
// plane was decoded, for lossless coding).
inline float reconstruct(const DecodedBlock& block, std::size_t i, double delta, bool exact) {
  // Selects rather than branches: whether a coefficient is significant is a coin toss.
  const int plane = block.low_plane[i];
  const bool significant = plane != 255;
  const std::int32_t v = block.known[i];
  const double mag = double(v < 0 ? -std::int64_t(v) : v);
  const double offset = (exact && plane == 0) ? 0.0 : delta * double(1u << (significant ? plane : 0));
  const float r = float(v < 0 ? -(mag + offset) : mag + offset);
  return significant ? r : 0.0f;
}

}  // namespace pupwave

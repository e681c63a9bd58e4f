#pragma once
// Entropy coding of the quantised integers of a .pwm file (docs/bitstream.md, Mesh): each
// signed integer is a zero flag (context: magnitude class of the previous integer of the same
// axis), then a sign (equiprobable), then |v| - 1 in Exp-Golomb form whose unary prefix bits
// have adaptive contexts and whose suffix bits are equiprobable. One stream per chunk.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/entropy/bit_model.h"

namespace pupwave::mesh {

// Largest magnitude a quantised value may have (the encoder refuses larger ones).
inline constexpr std::int64_t kMaxQuantised = std::int64_t(1) << 40;

// Codes triples of integers (x, y, z of one point) into one range-coded byte stream.
std::vector<std::uint8_t> encode_triples(std::span<const std::int64_t> values);

// Decodes `count` integers (a multiple of 3); any byte string decodes to some values.
std::vector<std::int64_t> decode_triples(std::span<const std::uint8_t> bytes, std::size_t count);

}  // namespace pupwave::mesh

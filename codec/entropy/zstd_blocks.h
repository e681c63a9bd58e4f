#pragma once
// The zstd back end (`--entropy zstd`), for comparison with the bit-plane coder: a block's
// quantization indices as zigzag varints, compressed by zstd. One "pass" per block, no
// truncation points, so rate control can only change the quantizer step.

#include <cstdint>
#include <span>
#include <vector>

namespace pupwave {

// Compresses the indices floor(magnitude) with their signs. Returns an empty vector when all
// indices are zero.
std::vector<std::uint8_t> zstd_encode_block(std::span<const float> magnitude,
                                            std::span<const std::uint8_t> negative);

// Decodes `count` signed indices; throws DecodeError unless the codeword holds exactly that.
std::vector<std::int32_t> zstd_decode_block(std::span<const std::uint8_t> codeword, std::size_t count);

}  // namespace pupwave

#pragma once
// The code-block index: for every block its bit-plane count, coded pass count and codeword
// length, compressed with the adaptive range coder (most entries are small and alike).

#include <cstdint>
#include <span>
#include <vector>

namespace pupwave {

struct BlockEntry {
  int planes = 0;            // magnitude bit-planes of the block (0..kMaxBitPlanes)
  int passes = 0;            // coding passes included (0..passes_for_planes(planes))
  std::uint32_t length = 0;  // codeword bytes in the data chunk
};

std::vector<std::uint8_t> encode_index(std::span<const BlockEntry> entries);

// Decodes `count` entries; throws DecodeError for an entry out of range (planes above
// kMaxBitPlanes, passes above what the planes allow, a length with passes == 0).
std::vector<BlockEntry> decode_index(std::span<const std::uint8_t> bytes, std::size_t count);

}  // namespace pupwave

#pragma once
// CRC-32 (IEEE 802.3 polynomial, reflected, as in zlib/PNG) guarding every container chunk.

#include <cstdint>
#include <span>

namespace pupwave {

// CRC-32 of `bytes`, continuing from a previous value `crc` (0 to start).
std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

}  // namespace pupwave

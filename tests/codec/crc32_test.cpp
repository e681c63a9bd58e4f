// The slicing-by-8 CRC-32 must equal the textbook bit-at-a-time CRC-32 (zlib/PNG) on every
// length and alignment, and continue across split buffers: every stream's chunk CRCs depend on it.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <span>
#include <string_view>
#include <vector>

#include "codec/format/crc32.h"

namespace pupwave {
namespace {

// Bit at a time, reflected polynomial 0xEDB88320: the definition, no tables.
std::uint32_t crc32_bitwise(std::span<const std::uint8_t> bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::uint8_t b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc & 1u) ? 0xEDB88320u ^ (crc >> 1) : crc >> 1;
  }
  return ~crc;
}

TEST(Crc32, CheckValueOfTheStandard) {
  constexpr std::string_view text = "123456789";
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  EXPECT_EQ(crc32(bytes), 0xCBF43926u);
  EXPECT_EQ(crc32({}), 0u);
}

TEST(Crc32, EqualsBitwiseAtEveryLengthAndAlignment) {
  std::mt19937 rng(17);
  std::vector<std::uint8_t> data(70000);
  for (auto& b : data) b = std::uint8_t(rng());
  const std::span<const std::uint8_t> all(data);
  for (std::size_t offset = 0; offset < 8; ++offset)
    for (std::size_t length = 0; length < 70; ++length)
      ASSERT_EQ(crc32(all.subspan(offset, length)), crc32_bitwise(all.subspan(offset, length)))
          << "offset " << offset << " length " << length;
  EXPECT_EQ(crc32(all.subspan(3)), crc32_bitwise(all.subspan(3)));
}

TEST(Crc32, ContinuesAcrossSplits) {
  std::mt19937 rng(5);
  std::vector<std::uint8_t> data(1000);
  for (auto& b : data) b = std::uint8_t(rng());
  const std::span<const std::uint8_t> all(data);
  for (std::size_t split : {0u, 1u, 7u, 8u, 13u, 500u, 999u, 1000u})
    EXPECT_EQ(crc32(all.subspan(split), crc32(all.subspan(0, split))), crc32(all)) << split;
}

}  // namespace
}  // namespace pupwave

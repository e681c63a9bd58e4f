// The one chunk layer (codec/format/chunks.h): framing, CRC over tag + length + payload,
// signature and version checks, and the errors a hostile stream gets.
#include <gtest/gtest.h>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/format/crc32.h"

namespace pupwave {
namespace {

std::vector<std::uint8_t> two_chunk_stream() {
  std::vector<std::uint8_t> out;
  write_signature(out, "TEST", 7);
  const std::vector<std::uint8_t> a{1, 2, 3}, b;
  write_chunk(out, "AAAA", a);
  write_chunk(out, "BBBB", b);
  return out;
}

TEST(Chunks, FramingIsTagLengthPayloadCrcOfAllThree) {
  const auto s = two_chunk_stream();
  ASSERT_EQ(s.size(), kSignatureBytes + 2 * kChunkOverhead + 3);
  EXPECT_EQ(s[4], 7);
  EXPECT_EQ(s[9], 3);  // little-endian length
  const std::uint32_t crc = crc32(std::span(s).subspan(kSignatureBytes, 11));
  const std::uint32_t stored = s[16] | (s[17] << 8) | (s[18] << 16) | (std::uint32_t(s[19]) << 24);
  EXPECT_EQ(stored, crc);
}

TEST(Chunks, ReaderReturnsPayloadsInOrder) {
  const auto s = two_chunk_stream();
  ChunkReader r(s, "TEST", 7, "test stream");
  const Chunk a = r.expect("AAAA");
  ASSERT_EQ(a.payload.size(), 3u);
  EXPECT_EQ(a.payload[2], 3);
  const Chunk b = r.next();
  EXPECT_TRUE(b.is("BBBB"));
  EXPECT_TRUE(b.payload.empty());
  EXPECT_TRUE(r.at_end());
  EXPECT_THROW(r.next(), DecodeError);
}

TEST(Chunks, EveryCorruptionIsRejected) {
  const auto good = two_chunk_stream();
  EXPECT_THROW(ChunkReader(good, "TEST", 8, "test stream"), DecodeError);  // version
  EXPECT_THROW(ChunkReader(good, "TESU", 7, "test stream"), DecodeError);  // signature
  const std::span<const std::uint8_t> three = std::span(good).first(3);
  EXPECT_THROW(ChunkReader(three, "TEST", 7, "t"), DecodeError);
  for (std::size_t i = kSignatureBytes; i < good.size(); ++i) {
    auto bad = good;
    bad[i] ^= 0x10;
    ChunkReader r(bad, "TEST", 7, "test stream");
    EXPECT_THROW(
        {
          r.expect("AAAA");
          r.expect("BBBB");
        },
        DecodeError)
        << "byte " << i;
  }
  for (std::size_t n = kSignatureBytes; n < good.size(); ++n) {
    const std::span<const std::uint8_t> prefix = std::span(good).first(n);
    ChunkReader r(prefix, "TEST", 7, "test stream");
    EXPECT_THROW(
        {
          r.expect("AAAA");
          r.expect("BBBB");
        },
        DecodeError)
        << "length " << n;
  }
}

TEST(Chunks, WrongTagNamesBothTags) {
  const auto s = two_chunk_stream();
  ChunkReader r(s, "TEST", 7, "test stream");
  try {
    r.expect("BBBB");
    FAIL() << "no error";
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("expected chunk BBBB, found AAAA"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pupwave

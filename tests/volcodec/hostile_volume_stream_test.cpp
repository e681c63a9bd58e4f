// Hostile volume streams: truncation at every chunk and many points inside, flipped bits,
// random bytes, and crafted headers (absurd dims, bad fields) with valid checksums must all
// give DecodeError, never a crash or an unbounded allocation.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

std::vector<std::uint8_t> sample_stream() {
  VolumeGrid g;
  g.name = "s";
  g.volume = test::sphere_level_set({20, 17, 11}, 6.0, 2.0, 0.3);
  VolumeEncodeOptions o;
  o.target = 1e-3;
  o.brick = 8;
  return encode_volumes({g}, o).bytes;
}

TEST(HostileVolumeStream, TruncationIsRejectedEverywhere) {
  const auto bytes = sample_stream();
  for (std::size_t n = 0; n < bytes.size(); n += 1 + n / 16) {
    const std::span<const std::uint8_t> cut(bytes.data(), n);
    EXPECT_THROW(decode_volumes(cut), DecodeError) << n << " of " << bytes.size();
  }
}

TEST(HostileVolumeStream, FlippedBitsAreRejected) {
  const auto bytes = sample_stream();
  std::mt19937 rng(1);
  for (int trial = 0; trial < 300; ++trial) {
    auto bad = bytes;
    const std::size_t at = std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng);
    bad[at] ^= std::uint8_t(1u << (trial % 8));
    EXPECT_THROW(decode_volumes(bad), DecodeError) << "byte " << at;
  }
}

TEST(HostileVolumeStream, RandomBytesAfterTheSignatureAreRejected) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<std::uint8_t> bad{'P', 'U', 'P', 'V', kVolumeStreamVersion};
    for (int i = 0; i < 200; ++i) bad.push_back(std::uint8_t(rng()));
    EXPECT_THROW(decode_volumes(bad), DecodeError);
  }
}

// A stream whose header says `dims` (valid checksum), with no bricks.
std::vector<std::uint8_t> crafted(const Extent& dims, int levels = 3, int brick_log2 = 6) {
  VolumeStreamHeader h;
  h.spec = "cdf97";
  h.levels = levels;
  h.brick_log2 = brick_log2;
  VolumeGrid g;
  g.volume.dims = dims;
  h.grids.push_back(g);
  std::vector<std::uint8_t> out;
  write_volume_signature(out);
  write_header_chunk(out, h);
  return out;
}

TEST(HostileVolumeStream, CraftedHeadersAreRejected) {
  EXPECT_THROW(decode_volumes(crafted({1u << 30, 1u << 30, 1u << 30})), DecodeError);
  EXPECT_THROW(decode_volumes(crafted({65536, 65536, 2})), DecodeError);
  EXPECT_THROW(decode_volumes(crafted({0, 4, 4})), DecodeError);
  EXPECT_THROW(decode_volumes(crafted({4, 4, 4}, 9)), DecodeError);      // levels above log2(brick)
  EXPECT_THROW(decode_volumes(crafted({4, 4, 4}, 3, 20)), DecodeError);  // absurd brick
  EXPECT_THROW(decode_volumes(crafted({4, 4, 4})), DecodeError);         // a dense grid without bricks
}

// A dense max-error stream (coefficient coder) parsed, changed and written again with valid CRCs.
std::vector<std::uint8_t> coef_stream_changed(const std::function<void(ParsedVolumeStream&)>& change) {
  VolumeGrid g;
  g.name = "c";
  g.volume = test::smooth_volume({20, 12, 9}, VoxelType::f32, 50.0);
  VolumeEncodeOptions o;
  o.mode = VolumeRateMode::max_error;
  o.target = 1e-3;
  o.brick = 16;
  o.block = 16;
  const std::vector<std::uint8_t> bytes = encode_volumes({g}, o).bytes;  // the codewords point into it
  ParsedVolumeStream s = parse_volume_stream(bytes);
  EXPECT_EQ(s.header.coder, 1u);
  change(s);
  std::vector<std::uint8_t> out;
  write_volume_signature(out);
  write_header_chunk(out, s.header);
  for (const BrickChunk& b : s.bricks) write_brick_chunk(out, b);
  return out;
}

void expect_refused(const std::vector<std::uint8_t>& bytes, const std::string& message) {
  try {
    decode_volumes(bytes);
    ADD_FAILURE() << "decoded; expected: " << message;
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(HostileVolumeStream, CoefficientCoderFieldsAreChecked) {
  EXPECT_NO_THROW(decode_volumes(coef_stream_changed([](ParsedVolumeStream&) {})));
  expect_refused(coef_stream_changed([](ParsedVolumeStream& s) { s.header.coder = 2; }), "coefficient coder");
  expect_refused(coef_stream_changed([](ParsedVolumeStream& s) {
                   s.header.reversible = true;
                   s.header.spec = "cdf53";
                 }),
                 "coefficient coder");
  expect_refused(coef_stream_changed([](ParsedVolumeStream& s) {
                   for (BlockEntry& e : s.bricks[0].entries)
                     if (e.planes >= 2) e.passes = 2;
                 }),
                 "one pass");
  // Coefficient codewords read as bit-plane ones (coder 0): wrong values or a DecodeError, no crash.
  try {
    decode_volumes(coef_stream_changed([](ParsedVolumeStream& s) { s.header.coder = 0; }));
  } catch (const DecodeError&) {
  }
}

TEST(HostileVolumeStream, ValidStreamDecodes) {
  EXPECT_NO_THROW(decode_volumes(sample_stream()));
  EXPECT_TRUE(is_volume_stream(sample_stream()));
}

}  // namespace
}  // namespace pupwave

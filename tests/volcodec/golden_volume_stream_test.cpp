// Golden checksums of encoded volume streams, as tests/codec/golden_stream_test.cpp pins image
// streams: any change to the PUPV layout, the chunk framing, brick coding, the quantizer or the
// outlier list changes them. When a format change is deliberate, bump kVolumeStreamVersion,
// update docs/bitstream.md and these values; an encoder-only change (a different step choice)
// updates the lossy values without a version bump (as the modelled step choice and the max-error
// reconstruction offset 0.5 did). Version 3 (sparse-native grids) changed only the version byte
// of these box-grid streams. Version 4 added VHDR's coder byte, codes max-error streams with the
// coefficient coder and changed the bit-plane coder's contexts: all four changed.
// Version 5 (the block coder's priors retrained) changed all four (by the version byte
// at least). Version 6 (outlier corrections range coded) changed all four: the
// lossless and step streams by the version byte only; the estimated outlier-list size in the
// step choice (encoder only) changed the sphere stream once more. The max-error quantizer's
// rounding offset 0.375 with delta 0.125 (encoder only) changed both max-error streams.
// Version 7 (dense grids with missing values, inactive values as a zstd frame) changed all six:
// the dense streams by the version byte only, the sphere level sets by their MASK too.
#include <gtest/gtest.h>

#include "codec/error.h"
#include "codec/format/chunks.h"
#include "codec/format/crc32.h"
#include "codec/volume/volume_codec.h"
#include "codec/volume/volume_format.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

std::vector<std::uint8_t> encode_golden(Volume v, VolumeRateMode mode, double target, const char* spec) {
  VolumeGrid g;
  g.name = "golden";
  g.volume = std::move(v);
  VolumeEncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = spec;
  o.brick = 16;
  o.block = 16;
  o.executor = &serial_executor();
  return encode_volumes({g}, o).bytes;
}

std::uint32_t stream_crc(Volume v, VolumeRateMode mode, double target, const char* spec) {
  return crc32(encode_golden(std::move(v), mode, target, spec));
}

// The version 3 form of a bit-plane coded stream of this version: the same chunks without
// VHDR's coder byte (the fifth byte of its payload).
std::vector<std::uint8_t> as_version3(std::span<const std::uint8_t> v4) {
  ChunkReader r(v4, "PUPV", kVolumeStreamVersion, "volume stream");
  std::vector<std::uint8_t> out;
  write_signature(out, "PUPV", 3);
  while (!r.at_end()) {
    const Chunk c = r.next();
    std::vector<std::uint8_t> payload(c.payload.begin(), c.payload.end());
    if (c.is("VHDR")) {
      EXPECT_EQ(payload[4], 0u);  // bit-plane coder
      payload.erase(payload.begin() + 4);
    }
    const char tag[5] = {c.tag[0], c.tag[1], c.tag[2], c.tag[3], 0};
    write_chunk(out, tag, payload);
  }
  return out;
}

TEST(GoldenVolumeStream, LosslessStreamIsUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({21, 17, 9}, VoxelType::u16, 4000.0), VolumeRateMode::lossless, 0,
                       "cdf53"),
            2267000840u);
}

TEST(GoldenVolumeStream, ErrorBoundedStreamsAreUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({21, 17, 9}, VoxelType::f32, 10.0), VolumeRateMode::max_error,
                       1e-2, "cdf97"),
            2773282474u);
  EXPECT_EQ(stream_crc(test::sphere_level_set({24, 24, 24}, 7.0, 2.5, 0.3), VolumeRateMode::max_error, 1e-3,
                       "cdf97"),
            2238579705u);
}

// A PUPs bank through the generic lifting (6- and 9-tap steps, whole-sample boundaries, bricks
// of 1 to 16 samples a side): values from main's build before the fast lifting paths, which
// must leave every coefficient, hence the stream, unchanged.
TEST(GoldenVolumeStream, PupsErrorBoundedStreamsAreUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({21, 17, 9}, VoxelType::f32, 10.0), VolumeRateMode::max_error,
                       1e-2, "pups:cinpact-interp-vm4"),
            307045846u);
  EXPECT_EQ(stream_crc(test::sphere_level_set({24, 24, 24}, 7.0, 2.5, 0.3), VolumeRateMode::max_error, 1e-3,
                       "pups:cinpact-interp-vm4"),
            1424982892u);
}

TEST(GoldenVolumeStream, StepStreamIsUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({19, 13, 11}, VoxelType::f64, 1.0, 3), VolumeRateMode::step, 1e-3,
                       "cdf53"),
            4044249221u);
}

// Version 3 streams (older bit-plane contexts, no coder byte) are refused, not misdecoded.
TEST(GoldenVolumeStream, Version3StreamsAreRefused) {
  const auto v4 = encode_golden(test::smooth_volume({21, 17, 9}, VoxelType::u16, 4000.0),
                                VolumeRateMode::lossless, 0, "cdf53");
  const auto v3 = as_version3(v4);
  ASSERT_EQ(v3[4], 3u);
  EXPECT_THROW(decode_volumes(v3), DecodeError);
}

// Version 4 streams (the block coder's priors before their retraining) are refused too: the
// same chunks would decode to other values.
TEST(GoldenVolumeStream, Version4StreamsAreRefused) {
  auto v4 = encode_golden(test::smooth_volume({21, 17, 9}, VoxelType::u16, 4000.0), VolumeRateMode::lossless,
                          0, "cdf53");
  ASSERT_EQ(v4[4], kVolumeStreamVersion);
  v4[4] = 4;
  EXPECT_THROW(decode_volumes(v4), DecodeError);
}

// Version 5 streams (outlier lists as zstd frames of varints) are refused: their lists would
// decode as range-coded corrections, wrong and silently.
TEST(GoldenVolumeStream, Version5StreamsAreRefused) {
  auto v5 = encode_golden(test::smooth_volume({21, 17, 9}, VoxelType::f32, 10.0), VolumeRateMode::max_error,
                          1e-2, "cdf97");
  ASSERT_EQ(v5[4], kVolumeStreamVersion);
  v5[4] = 5;
  EXPECT_THROW(decode_volumes(v5), DecodeError);
}

}  // namespace
}  // namespace pupwave

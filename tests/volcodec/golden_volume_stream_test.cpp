// Golden checksums of encoded volume streams, as tests/codec/golden_stream_test.cpp pins image
// streams: any change to the PUPV layout, the chunk framing, brick coding, the quantizer or the
// outlier list changes them. When a format change is deliberate, bump kVolumeStreamVersion,
// update docs/bitstream.md and these values; an encoder-only change (a different step choice)
// updates the lossy values without a version bump (as the modelled step choice and the max-error
// reconstruction offset 0.5 of issue 17 did). Version 3 (sparse-native grids) changed only the version byte
// of these box-grid streams. Version 4 (issue 20: the block coder's far-neighbour contexts and
// priors) changed all four.
#include <gtest/gtest.h>

#include "codec/format/crc32.h"
#include "codec/volume/volume_codec.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

std::uint32_t stream_crc(Volume v, VolumeRateMode mode, double target, const char* spec) {
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
  return crc32(encode_volumes({g}, o).bytes);
}

TEST(GoldenVolumeStream, LosslessStreamIsUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({21, 17, 9}, VoxelType::u16, 4000.0), VolumeRateMode::lossless, 0,
                       "cdf53"),
            2687415381u);
}

TEST(GoldenVolumeStream, ErrorBoundedStreamsAreUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({21, 17, 9}, VoxelType::f32, 10.0), VolumeRateMode::max_error,
                       1e-2, "cdf97"),
            2658119283u);
  EXPECT_EQ(stream_crc(test::sphere_level_set({24, 24, 24}, 7.0, 2.5, 0.3), VolumeRateMode::max_error, 1e-3,
                       "cdf97"),
            2478161850u);
}

TEST(GoldenVolumeStream, StepStreamIsUnchanged) {
  EXPECT_EQ(stream_crc(test::smooth_volume({19, 13, 11}, VoxelType::f64, 1.0, 3), VolumeRateMode::step, 1e-3,
                       "cdf53"),
            1926496580u);
}

}  // namespace
}  // namespace pupwave

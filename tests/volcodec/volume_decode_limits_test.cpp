// The volume decode limit (DecodeLimits): voxels of all grids at full resolution, refused
// before any mask or output is allocated, at every level.
#include <gtest/gtest.h>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

TEST(VolumeDecodeLimits, AllGridsAtFullResolutionCount) {
  VolumeGrid a, b;
  a.name = "a";
  a.volume = test::smooth_volume({17, 23, 9}, VoxelType::f32, 10.0);
  b.name = "b";
  b.volume = test::smooth_volume({8, 8, 8}, VoxelType::f32, 10.0);
  VolumeEncodeOptions o;
  o.brick = 8;
  o.target = 0.1;
  const auto bytes = encode_volumes({a, b}, o).bytes;
  const std::size_t voxels = 17 * 23 * 9 + 8 * 8 * 8;
  EXPECT_EQ(decode_volumes(bytes, 0, serial_executor(), DecodeLimits{voxels}).size(), 2u);
  for (int level : {0, 1})
    EXPECT_THROW(decode_volumes(bytes, level, serial_executor(), DecodeLimits{voxels - 1}), DecodeError);
}

}  // namespace
}  // namespace pupwave

// The public API's volume decode of a sparse-native stream (what `pupwave compress` makes of a
// .vdb): the arrays are the grid's dense active bounding box with its mask, holding the grid's
// voxels (not zeros from dropped blocks).
#include <gtest/gtest.h>

#include <cstring>

#include "codec/volume/volume_codec.h"
#include "pupwave/pupwave.hpp"

namespace pupwave {
namespace {

TEST(ApiSparseNative, DecodedArraysAreTheDenseBoxOfTheBlocks) {
  VolumeGrid g;
  g.name = "blocks";
  g.volume.type = VoxelType::f32;
  g.volume.background = 0.5;
  g.origin = {8, 0, -8};
  g.volume.dims = {24, 8, 16};
  for (const std::array<std::int64_t, 3> origin : {std::array<std::int64_t, 3>{8, 0, -8}, {24, 0, 0}}) {
    VolumeBlock b;
    b.origin = origin;
    b.volume = Volume({8, 8, 8}, VoxelType::f32);
    b.volume.background = 0.5;
    b.volume.active.assign(b.volume.count(), 0);
    for (std::size_t i = 0; i < b.volume.count(); ++i) {
      b.volume.active[i] = i % 3 == 0 ? 1 : 0;
      b.volume.samples[i] = b.volume.active[i] ? double(float(0.01 * double(i))) : (i % 7 == 0 ? -0.5 : 0.5);
    }
    g.blocks.push_back(b);
  }
  VolumeEncodeOptions o;
  o.mode = VolumeRateMode::max_error;
  o.target = 1e-3;
  const auto bytes = encode_volumes({g}, o).bytes;
  VolumeGrid expected = decode_volumes(bytes)[0];
  make_dense_box(expected, 1 << 20);
  const auto out = api::decompress_volume(bytes);
  ASSERT_EQ(out.size(), 1u);
  const api::Volume& v = out[0];
  EXPECT_EQ((std::array<std::size_t, 3>{v.dims[0], v.dims[1], v.dims[2]}), expected.volume.dims);
  EXPECT_EQ(v.origin, expected.origin);
  ASSERT_EQ(v.data.size(), expected.volume.count() * 4);
  EXPECT_EQ(v.active, expected.volume.active);
  std::size_t differ = 0, active = 0;
  for (std::size_t i = 0; i < expected.volume.count(); ++i) {
    float f = 0;
    std::memcpy(&f, v.data.data() + 4 * i, 4);
    differ += f != float(expected.volume.samples[i]);
    active += v.active[i];
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_EQ(active, g.active_voxels());
}

}  // namespace
}  // namespace pupwave

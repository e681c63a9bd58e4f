// Sparse box grids decoded as blocks of their non-empty bricks (SparseBoxForm::blocks, what .vdb
// output uses): the same voxels, masks and inactive values as the dense box form at
// every level, with nothing allocated for bricks that hold only inactive background.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <vector>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"

namespace pupwave {
namespace {

// wmag91 (a real turbulence field, testimages/README.md) as a sparse box: active above the
// median, inactive voxels of every state (background, -background, other values), and the
// region x >= 64 (whole bricks of 16) inactive background.
VolumeGrid sparse_wmag91() {
  VolumeGrid g;
  g.name = "wmag";
  g.origin = {-5, 3, 10};
  g.volume = Volume({91, 91, 91}, VoxelType::f32);
  g.volume.background = 0.5;
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/wmag91.float", std::ios::binary);
  std::vector<float> raw(g.volume.count());
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * 4));
  EXPECT_TRUE(in.good()) << "cannot read wmag91.float";
  std::vector<float> sorted = raw;
  std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
  const float median = sorted[sorted.size() / 2];
  Volume& v = g.volume;
  v.active.assign(v.count(), 0);
  for (std::size_t z = 0; z < 91; ++z)
    for (std::size_t y = 0; y < 91; ++y)
      for (std::size_t x = 0; x < 91; ++x) {
        const std::size_t i = v.index(x, y, z);
        v.samples[i] = raw[i];
        if (x >= 64) {
          v.samples[i] = v.background;
        } else if (raw[i] > median) {
          v.active[i] = 1;
        } else if (x % 7 == 0) {
          v.samples[i] = -v.background;
        } else if (x % 3 != 0) {
          v.samples[i] = v.background;
        }  // else: an inactive voxel with its own value
      }
  return g;
}

void expect_same_grid(const VolumeGrid& box, VolumeGrid blocks, int level) {
  make_dense_box(blocks, std::size_t(1) << 24);
  EXPECT_EQ(blocks.origin, box.origin) << level;
  EXPECT_EQ(blocks.index_to_world, box.index_to_world) << level;
  ASSERT_EQ(blocks.volume.dims, box.volume.dims) << level;
  EXPECT_EQ(blocks.volume.active, box.volume.active) << level;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < box.volume.count(); ++i)
    differ += blocks.volume.samples[i] != box.volume.samples[i];
  EXPECT_EQ(differ, 0u) << level;
}

TEST(SparseBoxBlocks, BlocksFormMatchesTheBoxFormAtEveryLevel) {
  const VolumeGrid g = sparse_wmag91();
  VolumeEncodeOptions o;
  o.target = 1e-3;
  o.brick = 16;
  o.levels = 2;
  const auto bytes = encode_volumes({g}, o).bytes;
  for (int level = 0; level <= 2; ++level) {
    const auto box = decode_volumes(bytes, level, serial_executor(), {}, SparseBoxForm::box);
    const auto blocks = decode_volumes(bytes, level, serial_executor(), {}, SparseBoxForm::blocks);
    ASSERT_EQ(box.size(), 1u);
    ASSERT_EQ(blocks.size(), 1u);
    ASSERT_TRUE(blocks[0].is_blocked());
    // 6^3 bricks; those of x >= 64 (2 of 6 along x) hold only background and are not allocated.
    EXPECT_EQ(blocks[0].blocks.size(), 4u * 6 * 6) << level;
    EXPECT_EQ(blocks[0].active_voxels(), box[0].volume.active_count()) << level;
    expect_same_grid(box[0], blocks[0], level);
  }
  EXPECT_EQ(decode_volumes(bytes)[0].volume.active, g.volume.active);
}

TEST(SparseBoxBlocks, AnAllBackgroundBoxIsAnEmptyGridAndItsLimitIsItsContent) {
  VolumeGrid g;
  g.name = "empty";
  g.volume = Volume({40, 30, 20}, VoxelType::f32);
  g.volume.active.assign(g.volume.count(), 0);
  VolumeEncodeOptions o;
  o.brick = 8;
  const auto bytes = encode_volumes({g}, o).bytes;
  // The box form holds every voxel, the blocks form none: a limit of 1 voxel refuses one only.
  EXPECT_THROW(decode_volumes(bytes, 0, serial_executor(), {1}, SparseBoxForm::box), DecodeError);
  const auto blocks = decode_volumes(bytes, 0, serial_executor(), {1}, SparseBoxForm::blocks);
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_TRUE(blocks[0].blocks.empty());
  EXPECT_EQ(blocks[0].volume.dims, (Extent{0, 0, 0}));
  EXPECT_EQ(blocks[0].active_voxels(), 0u);
}

}  // namespace
}  // namespace pupwave

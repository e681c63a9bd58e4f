// Sparse-native volume coding: grids held as blocks and tiles code in memory that follows their
// blocks (not their bounding box), tiles come back as tiles, and the bound holds on every
// active voxel.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/error.h"
#include "codec/volume/volume_codec.h"

namespace pupwave {
namespace {

// An 8^3 block at `origin` of smooth values, about half of its voxels active.
VolumeBlock smooth_block(const std::array<std::int64_t, 3>& origin, unsigned seed) {
  VolumeBlock b;
  b.origin = origin;
  b.volume = Volume({8, 8, 8}, VoxelType::f32);
  b.volume.background = 0.5;
  b.volume.active.assign(b.volume.count(), 0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  for (std::size_t i = 0; i < b.volume.count(); ++i) {
    b.volume.active[i] = coin(rng) < 0.5 ? 1 : 0;
    b.volume.samples[i] =
        b.volume.active[i] ? double(float(std::sin(0.3 * double(i)) + coin(rng))) : (i % 7 == 0 ? -0.5 : 0.5);
  }
  b.volume.samples[3] = 0.125;  // an inactive voxel holding neither +-background
  b.volume.active[3] = 0;
  return b;
}

// A grid whose blocks lie 10^5 voxels apart in each axis, with an active 128^3 tile of 1.0 and an
// inactive tile of -0.5.
VolumeGrid wide_grid() {
  VolumeGrid g;
  g.name = "wide";
  g.grid_class = GridClass::fog_volume;
  g.volume.type = VoxelType::f32;
  g.volume.background = 0.5;
  g.origin = {-8, -8, -8};
  g.volume.dims = {100008, 100008, 100008};
  g.blocks.push_back(smooth_block({-8, -8, -8}, 1));
  g.blocks.push_back(smooth_block({99992, 99992, 99992}, 2));
  g.blocks.push_back(smooth_block({40000, 8, 99992}, 3));
  g.tiles.push_back({{4096, 0, 0}, 128, 1.0, true});
  g.tiles.push_back({{0, 4096, 0}, 8, -0.5, false});
  return g;
}

TEST(SparseNative, WideGridCodesInMemoryOfItsBlocks) {
  const VolumeGrid g = wide_grid();
  VolumeEncodeOptions o;
  o.mode = VolumeRateMode::max_error;
  o.target = 1e-3;
  const auto r = encode_volumes({g}, o);
  // bpv counts active voxels: the 128^3 tile is 2M of them and costs a few bytes.
  EXPECT_NEAR(r.bpv, double(r.bytes.size()) * 8.0 / double(g.active_voxels()), 1e-12);
  EXPECT_LT(r.bytes.size(), 4000u);
  const auto out = decode_volumes(r.bytes);
  ASSERT_EQ(out.size(), 1u);
  const VolumeGrid& d = out[0];
  // What the decoder allocated: the three 8^3 blocks, nothing of the 10^15-voxel box.
  ASSERT_EQ(d.blocks.size(), 3u);
  std::size_t allocated = d.volume.samples.size();
  for (const VolumeBlock& b : d.blocks) allocated += b.volume.samples.size();
  EXPECT_EQ(allocated, 3u * 512u);
  EXPECT_EQ(d.tiles, g.tiles);  // tiles come back as tiles, exactly
  EXPECT_EQ(d.origin, g.origin);
  EXPECT_EQ(d.volume.dims, g.volume.dims);
  EXPECT_EQ(d.grid_class, GridClass::fog_volume);
  EXPECT_EQ(d.active_voxels(), g.active_voxels());
  for (std::size_t k = 0; k < 3; ++k) {
    const Volume& a = g.blocks[k].volume;
    const Volume& b = d.blocks[k].volume;
    EXPECT_EQ(d.blocks[k].origin, g.blocks[k].origin);
    ASSERT_EQ(b.dims, a.dims);
    EXPECT_EQ(b.active, a.active);
    for (std::size_t i = 0; i < a.count(); ++i) {
      if (a.active[i])
        EXPECT_LE(std::abs(a.samples[i] - b.samples[i]), 1e-3) << "block " << k << " voxel " << i;
      else
        EXPECT_EQ(a.samples[i], b.samples[i]) << "inactive voxel " << i << " of block " << k;
    }
  }
  const std::string info = describe_volume_stream(r.bytes);
  EXPECT_NE(info.find(std::to_string(g.active_voxels()) + " active voxels, 1 active tile(s), 3 block(s)"),
            std::string::npos)
      << info;
}

TEST(SparseNative, ConstantTileAloneCostsBytes) {
  VolumeGrid g;
  g.name = "tile";
  g.volume.type = VoxelType::f32;
  g.volume.dims = {128, 128, 128};
  g.tiles.push_back({{0, 0, 0}, 128, 1.0, true});
  for (std::int64_t k = 0; k < 200; ++k)  // many tiles (a level set's inside): 37 bytes each
    g.tiles.push_back({{-1024, 8 * k, 0}, 8, -3.0, false});
  const auto r = encode_volumes({g}, VolumeEncodeOptions{});
  EXPECT_LT(r.bytes.size(), 1000u + 200u * 37u);
  const auto out = decode_volumes(r.bytes);
  EXPECT_TRUE(out[0].blocks.empty());
  EXPECT_EQ(out[0].tiles, g.tiles);
  EXPECT_EQ(r.max_error, 0.0);
}

TEST(SparseNative, CoarseLevelKeepsBlocksSparse) {
  const VolumeGrid g = wide_grid();
  VolumeEncodeOptions o;
  o.brick = 8;
  o.levels = 2;
  const auto bytes = encode_volumes({g}, o).bytes;
  const auto out = decode_volumes(bytes, 1);
  ASSERT_EQ(out[0].blocks.size(), 3u);
  EXPECT_EQ(out[0].blocks[1].origin, (std::array<std::int64_t, 3>{49996, 49996, 49996}));
  EXPECT_EQ(out[0].blocks[1].volume.dims, (Extent{4, 4, 4}));
  EXPECT_EQ(out[0].tiles[0].edge, 64u);
}

TEST(SparseNative, EmptyGridAndBadBlocksRefused) {
  VolumeGrid g;
  g.name = "nothing";
  g.volume.dims = {8, 8, 8};
  g.tiles.push_back({{0, 0, 0}, 8, 3.0, false});  // inactive only
  EXPECT_THROW(encode_volumes({g}, VolumeEncodeOptions{}), EncodeError);
  VolumeGrid bad = wide_grid();
  bad.blocks[0].volume.samples.pop_back();
  EXPECT_THROW(encode_volumes({bad}, VolumeEncodeOptions{}), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave

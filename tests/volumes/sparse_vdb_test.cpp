// OpenVDB grids read sparse-native: scattered voxels over a range of 10^4 and active tiles code
// without a dense box, tiles come back as tiles, and every voxel meets the bound.
#include <openvdb/tools/Prune.h>

#include <random>

#include "tools/volume_io.h"
#include "volumes/volume_test_util.h"

namespace pupwave::test {
namespace {

// 200 voxels at random places of [0, 10^4)^3 plus an active 128^3 tile of 1.0.
openvdb::FloatGrid::Ptr scattered_grid() {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("scattered");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> at(0, 9999);
  std::uniform_real_distribution<float> value(0.1f, 2.0f);
  auto acc = grid->getAccessor();
  for (int i = 0; i < 200; ++i) acc.setValueOn(openvdb::Coord(at(rng), at(rng), at(rng)), value(rng));
  grid->tree().fill(openvdb::CoordBBox::createCube(openvdb::Coord(128 * 40, 0, 128), 128), 1.0f, true);
  grid->insertMeta("author", openvdb::StringMetadata("test"));
  return grid;
}

TEST_F(VolumeTest, ScatteredVoxelsReadAsBlocksAndTiles) {
  write_grids({scattered_grid()}, dir_ / "in.vdb");
  const auto grids = cli::read_vdb(dir_ / "in.vdb");
  ASSERT_EQ(grids.size(), 1u);
  const VolumeGrid& g = grids[0];
  EXPECT_LE(g.blocks.size(), 200u);
  std::size_t held = 0;
  for (const VolumeBlock& b : g.blocks) held += b.volume.count();
  EXPECT_LE(held, 200u * 512u);  // at most one leaf per voxel, never the 10^12-voxel box
  EXPECT_EQ(g.active_tiles(), 1u);
  EXPECT_EQ(g.active_voxels(), 200u + 128u * 128u * 128u);
}

TEST_F(VolumeTest, ScatteredVoxelsRoundTripThroughTheCli) {
  const auto in = scattered_grid();
  write_grids({in}, dir_ / "in.vdb");
  const CliResult c =
      run_cli({"compress", (dir_ / "in.vdb").string(), (dir_ / "s.pw").string(), "--max-error", "1e-3"});
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("bits per active voxel"), std::string::npos) << c.output;
  // Smaller than OpenVDB's own file of the same grid (a leaf per scattered voxel in both).
  EXPECT_LT(fs::file_size(dir_ / "s.pw"), fs::file_size(dir_ / "in.vdb"))
      << fs::file_size(dir_ / "s.pw") << " vs " << fs::file_size(dir_ / "in.vdb");
  const CliResult info = run_cli({"info", (dir_ / "s.pw").string()});
  EXPECT_NE(info.output.find(std::to_string(200 + 128 * 128 * 128) + " active voxels, 1 active tile(s)"),
            std::string::npos)
      << info.output;
  const CliResult d = run_cli({"decompress", (dir_ / "s.pw").string(), (dir_ / "out.vdb").string()});
  ASSERT_EQ(d.exit_code, 0) << d.output;
  const auto back = openvdb::gridPtrCast<openvdb::FloatGrid>(read_grids(dir_ / "out.vdb").at(0));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->getName(), "scattered");
  EXPECT_EQ(back->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(back->metaValue<std::string>("author"), "test");
  EXPECT_EQ(back->activeVoxelCount(), in->activeVoxelCount());
  EXPECT_EQ(back->tree().activeTileCount(), in->tree().activeTileCount());  // the tile stays a tile
  auto acc = back->getConstAccessor();
  for (auto it = in->cbeginValueOn(); it; ++it) {
    float v = 0.0f;
    ASSERT_TRUE(acc.probeValue(it.getCoord(), v)) << it.getCoord();
    EXPECT_LE(std::abs(v - *it), 1e-3) << it.getCoord();
  }
}

}  // namespace
}  // namespace pupwave::test

// OpenVDB grids read sparse-native: scattered voxels over a range of 10^4 and active tiles code
// without a dense box, tiles come back as tiles, and every voxel meets the bound.
#include <openvdb/tools/Prune.h>

#include <map>
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

namespace pupwave::test {
namespace {

// Float density, double temperature, vec3s velocity, int32 and bool grids with names,
// transforms, classes, backgrounds and metadata, and file metadata.
openvdb::GridPtrVec multi_grids() {
  auto density = random_grid<openvdb::FloatGrid>({-5, 3, 10}, {21, 17, 13}, 0.4, 1);
  density->setName("density");
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  density->insertMeta("units", openvdb::StringMetadata("kg/m3"));
  auto temperature = random_grid<openvdb::DoubleGrid>({0, 0, 0}, {9, 11, 7}, 0.6, 2);
  temperature->setName("temperature");
  temperature->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3s(0, 0, 1));
  velocity->setName("velocity");
  velocity->setGridClass(openvdb::GRID_STAGGERED);
  auto mask = openvdb::Int32Grid::create(-1);
  mask->setName("mask");
  auto flags = openvdb::BoolGrid::create(false);
  flags->setName("flags");
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> at(-40, 40);
  for (int i = 0; i < 300; ++i) {
    const openvdb::Coord c(at(rng), at(rng), at(rng));
    velocity->tree().setValueOn(c, openvdb::Vec3s(float(c.x()) * 0.1f, 1.5f, -float(i)));
    mask->tree().setValueOn(c, i * 1000003);
    flags->tree().setValueOn(c, i % 2 == 0);
  }
  mask->insertMeta("count", openvdb::Int64Metadata(300));
  // Metadata of types the stream has no kind for (every type is kept).
  density->insertMeta("camera", openvdb::Mat4DMetadata(openvdb::Mat4d(openvdb::Mat4d::identity() * 2.0)));
  velocity->insertMeta("window", openvdb::Vec2IMetadata(openvdb::Vec2i(3, -4)));
  return {density, temperature, velocity, mask, flags};
}

TEST_F(VolumeTest, InfoListsEveryGridOfAVdbFile) {
  write_grids(multi_grids(), dir_ / "multi.vdb");
  const CliResult r = run_cli({"info", (dir_ / "multi.vdb").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* want : {"5 grid(s)", "'density': class fog volume, type float", "'temperature'",
                           "type double", "'velocity': class staggered, type vec3s", "'mask'", "type int32",
                           "'flags'", "type bool", "voxel size 0.5 x 0.5 x 0.5"})
    EXPECT_NE(r.output.find(want), std::string::npos) << want << " in\n" << r.output;
}

// File-level metadata of several types, as OpenVDB writes it beside the grids.
openvdb::MetaMap file_metadata() {
  openvdb::MetaMap m;
  m.insertMeta("creator", openvdb::StringMetadata("pupwave test"));
  m.insertMeta("frame", openvdb::Int32Metadata(42));
  m.insertMeta("time", openvdb::DoubleMetadata(1.25));
  m.insertMeta("origin", openvdb::Vec3DMetadata(openvdb::Vec3d(1, 2, 3)));
  m.insertMeta("frustum", openvdb::Mat4SMetadata(openvdb::Mat4s(openvdb::Mat4s::identity() * 3.0f)));
  return m;
}

void write_with_file_metadata(const openvdb::GridPtrVec& grids, const fs::path& path) {
  openvdb::io::File file(path.string());
  file.write(grids, file_metadata());
  file.close();
}

openvdb::MetaMap read_file_metadata(const fs::path& path) {
  openvdb::io::File file(path.string());
  file.open(false);
  const openvdb::MetaMap::Ptr m = file.getMetadata();
  file.close();
  return *m;
}

void expect_file_metadata(const fs::path& path) {
  const openvdb::MetaMap m = read_file_metadata(path);
  EXPECT_EQ(m.metaValue<std::string>("creator"), "pupwave test");
  EXPECT_EQ(m.metaValue<openvdb::Int32>("frame"), 42);
  EXPECT_EQ(m.metaValue<double>("time"), 1.25);
  EXPECT_EQ(m.metaValue<openvdb::Vec3d>("origin"), openvdb::Vec3d(1, 2, 3));
  EXPECT_EQ(m.metaValue<openvdb::Mat4s>("frustum"), openvdb::Mat4s(openvdb::Mat4s::identity() * 3.0f));
}

TEST_F(VolumeTest, MultiGridFileRoundTripsEveryGridType) {
  write_with_file_metadata(multi_grids(), dir_ / "multi.vdb");
  const openvdb::GridPtrVec in = read_grids(dir_ / "multi.vdb");  // OpenVDB lists grids by name
  const CliResult c =
      run_cli({"compress", (dir_ / "multi.vdb").string(), (dir_ / "m.pw").string(), "--max-error", "1e-3"});
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const CliResult d = run_cli({"decompress", (dir_ / "m.pw").string(), (dir_ / "out.vdb").string()});
  ASSERT_EQ(d.exit_code, 0) << d.output;
  const CliResult info = run_cli({"info", (dir_ / "m.pw").string()});
  EXPECT_NE(info.output.find("'velocity', component 2 of a vec3s grid"), std::string::npos) << info.output;
  const openvdb::GridPtrVec out = read_grids(dir_ / "out.vdb");
  ASSERT_EQ(out.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(out[i]->getName(), in[i]->getName());
    EXPECT_EQ(out[i]->valueType(), in[i]->valueType());
    EXPECT_EQ(out[i]->getGridClass(), in[i]->getGridClass());
    EXPECT_EQ(out[i]->transform(), in[i]->transform());
    EXPECT_EQ(out[i]->activeVoxelCount(), in[i]->activeVoxelCount());
  }
  // Names in OpenVDB's order: density, flags, mask, temperature, velocity.
  EXPECT_EQ(out[0]->metaValue<std::string>("units"), "kg/m3");
  EXPECT_EQ(out[0]->metaValue<openvdb::Mat4d>("camera"), openvdb::Mat4d(openvdb::Mat4d::identity() * 2.0));
  EXPECT_EQ(out[2]->metaValue<openvdb::Int64>("count"), 300);
  EXPECT_EQ(out[4]->metaValue<openvdb::Vec2i>("window"), openvdb::Vec2i(3, -4));
  expect_file_metadata(dir_ / "out.vdb");
  // Lossless grids: bit exact values and topology, backgrounds included.
  const auto m_in = openvdb::gridPtrCast<openvdb::Int32Grid>(in[2]);
  const auto m_out = openvdb::gridPtrCast<openvdb::Int32Grid>(out[2]);
  ASSERT_TRUE(m_in && m_out);
  EXPECT_TRUE(same_voxels(*m_in, *m_out));
  const auto b_in = openvdb::gridPtrCast<openvdb::BoolGrid>(in[1]);
  const auto b_out = openvdb::gridPtrCast<openvdb::BoolGrid>(out[1]);
  ASSERT_TRUE(b_in && b_out);
  EXPECT_TRUE(same_voxels(*b_in, *b_out));
  const auto v_in = openvdb::gridPtrCast<openvdb::Vec3SGrid>(in[4]);
  const auto v_out = openvdb::gridPtrCast<openvdb::Vec3SGrid>(out[4]);
  ASSERT_TRUE(v_in && v_out);
  // Vector grids: lossy per component, the bound held by each component of every active voxel.
  EXPECT_EQ(v_out->background(), openvdb::Vec3s(0, 0, 1));
  EXPECT_TRUE(v_out->tree().hasSameTopology(v_in->tree()));
  auto vacc = v_out->getConstAccessor();
  std::size_t lossy = 0;
  for (auto it = v_in->cbeginValueOn(); it; ++it) {
    const openvdb::Vec3s got = vacc.getValue(it.getCoord());
    for (int c = 0; c < 3; ++c)
      EXPECT_LE(std::abs(got[c] - (*it)[c]), 1e-3) << it.getCoord() << " component " << c;
    lossy += got != *it;
  }
  EXPECT_GT(lossy, 0u) << "the vector grid was coded lossy, not copied";
  // Lossy grids: the bound on every active voxel, topology kept.
  const auto f_in = openvdb::gridPtrCast<openvdb::FloatGrid>(in[0]);
  const auto f_out = openvdb::gridPtrCast<openvdb::FloatGrid>(out[0]);
  ASSERT_TRUE(f_in && f_out);
  EXPECT_TRUE(f_out->tree().hasSameTopology(f_in->tree()));
  auto acc = f_out->getConstAccessor();
  for (auto it = f_in->cbeginValueOn(); it; ++it)
    EXPECT_LE(std::abs(acc.getValue(it.getCoord()) - *it), 1e-3);
  const auto d_in = openvdb::gridPtrCast<openvdb::DoubleGrid>(in[3]);
  const auto d_out = openvdb::gridPtrCast<openvdb::DoubleGrid>(out[3]);
  ASSERT_TRUE(d_in && d_out);
  auto dacc = d_out->getConstAccessor();
  for (auto it = d_in->cbeginValueOn(); it; ++it)
    EXPECT_LE(std::abs(dacc.getValue(it.getCoord()) - *it), 1e-3);
}

// lod keeps the integer and bool grids (no pyramid for them) instead of dropping them, makes one
// of vector grids per component, and keeps the file metadata.
TEST_F(VolumeTest, LodCopiesOtherGridTypes) {
  const openvdb::GridPtrVec in = multi_grids();
  write_with_file_metadata(in, dir_ / "multi.vdb");
  const CliResult r =
      run_cli({"lod", (dir_ / "multi.vdb").string(), (dir_ / "lod.vdb").string(), "--levels", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::map<std::string, openvdb::GridBase::Ptr> out;
  for (const auto& g : read_grids(dir_ / "lod.vdb")) out[g->getName()] = g;
  EXPECT_EQ(out.size(), 9u);   // density, temperature, velocity, mask at levels 0 and 1; flags copied
  for (std::size_t i : {4}) {  // flags in multi_grids() (vdb_lod skips bool grids; never dropped here)
    const std::string name = in[i]->getName();
    ASSERT_TRUE(out.count(name)) << name;
    EXPECT_EQ(out[name]->activeVoxelCount(), in[i]->activeVoxelCount()) << name;
    EXPECT_EQ(out[name]->valueType(), in[i]->valueType()) << name;
  }
  EXPECT_TRUE(out.count("density_level_1"));
  ASSERT_TRUE(out.count("velocity_level_1"));
  EXPECT_EQ(out["velocity_level_1"]->valueType(), "vec3s");
  EXPECT_EQ(out["velocity_level_1"]->getGridClass(), openvdb::GRID_STAGGERED);
  ASSERT_TRUE(out.count("mask_level_1"));  // integer grids get levels, as in vdb_lod
  EXPECT_EQ(out["mask_level_1"]->valueType(), "int32");
  expect_file_metadata(dir_ / "lod.vdb");
}

// A vector grid's levels are the levels of its components, each made as for a scalar grid.
TEST_F(VolumeTest, LodOfVectorGridIsPerComponent) {
  const auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(multi_grids()[2]);
  openvdb::GridPtrVec parts;
  for (int c = 0; c < 3; ++c) {
    auto g = openvdb::FloatGrid::create(v->background()[c]);
    for (auto it = v->cbeginValueOn(); it; ++it) g->tree().setValueOn(it.getCoord(), (*it)[c]);
    g->setName("c" + std::to_string(c));
    parts.push_back(g);
  }
  write_grids({v}, dir_ / "v.vdb");
  write_grids(parts, dir_ / "parts.vdb");
  for (const char* name : {"v", "parts"}) {
    const fs::path in = dir_ / (std::string(name) + ".vdb"), out = dir_ / (std::string(name) + "_lod.vdb");
    const CliResult r = run_cli({"lod", in.string(), out.string(), "--levels", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  std::map<std::string, openvdb::GridBase::Ptr> levels;
  for (const auto& g : read_grids(dir_ / "v_lod.vdb")) levels[g->getName()] = g;
  for (const auto& g : read_grids(dir_ / "parts_lod.vdb")) levels[g->getName()] = g;
  for (int k = 1; k <= 2; ++k) {
    const auto vk = openvdb::gridPtrCast<openvdb::Vec3SGrid>(levels["velocity_level_" + std::to_string(k)]);
    ASSERT_TRUE(vk) << k;
    std::size_t checked = 0;
    for (int c = 0; c < 3; ++c) {
      const auto ck = openvdb::gridPtrCast<openvdb::FloatGrid>(
          levels["c" + std::to_string(c) + "_level_" + std::to_string(k)]);
      ASSERT_TRUE(ck) << k << ' ' << c;
      EXPECT_EQ(vk->activeVoxelCount(), ck->activeVoxelCount());
      auto acc = vk->getConstAccessor();
      for (auto it = ck->cbeginValueOn(); it; ++it, ++checked) {
        ASSERT_TRUE(acc.isValueOn(it.getCoord()));
        ASSERT_EQ(acc.getValue(it.getCoord())[c], *it) << "level " << k << " component " << c;
      }
    }
    EXPECT_GT(checked, 300u);
  }
}

}  // namespace
}  // namespace pupwave::test

// Round trips of raw and OpenVDB volumes through tools/volume_io, checked against OpenVDB's own
// reading of the files (values, active topology, background, class, transform, metadata).
#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "tools/volume_io.h"
#include "volumes/volume_test_util.h"

namespace pupwave::test {
namespace {

using cli::read_raw_volume;
using cli::read_vdb;
using cli::read_vdb_dense;
using cli::write_raw_volume;
using cli::write_vdb;

TEST(VolumeTypes, ParseDimsAndTypes) {
  EXPECT_EQ(cli::parse_dims("91,91,91"), (Extent{91, 91, 91}));
  EXPECT_EQ(cli::parse_dims("7,5"), (Extent{7, 5, 1}));
  for (const char* bad : {"", "0,4,4", "4,,4", "4,4,4,4", "-3,4,4", "4x4x4", "4,4,"})
    EXPECT_THROW(cli::parse_dims(bad), std::invalid_argument) << bad;
  for (VoxelType t : {VoxelType::u8, VoxelType::u16, VoxelType::f32, VoxelType::f64})
    EXPECT_EQ(parse_voxel_type(to_string(t)), t);
  EXPECT_THROW(parse_voxel_type("f16"), std::invalid_argument);
}

// Raw bytes of odd-sized volumes of every type survive read -> write unchanged, and the values
// read are the little-endian numbers written by this test.
TEST_F(VolumeTest, RawRoundTripEveryType) {
  const Extent dims{7, 5, 3};
  const std::size_t n = 7 * 5 * 3;
  std::mt19937 rng(3);
  for (VoxelType type : {VoxelType::u8, VoxelType::u16, VoxelType::f32, VoxelType::f64}) {
    std::vector<double> expected(n);
    std::vector<char> bytes(n * bytes_per_voxel(type));
    for (std::size_t i = 0; i < n; ++i) {
      const auto r = static_cast<std::uint32_t>(rng());
      char* p = bytes.data() + i * bytes_per_voxel(type);
      if (type == VoxelType::u8) {
        const std::uint8_t v = std::uint8_t(r);
        std::memcpy(p, &v, 1);
        expected[i] = v;
      }
      if (type == VoxelType::u16) {
        const std::uint16_t v = std::uint16_t(r);
        std::memcpy(p, &v, 2);
        expected[i] = v;
      }
      if (type == VoxelType::f32) {
        const float v = float(r) * 1e-7f - 200.0f;
        std::memcpy(p, &v, 4);
        expected[i] = v;
      }
      if (type == VoxelType::f64) {
        const double v = double(r) * 1e-9 - 2.0;
        std::memcpy(p, &v, 8);
        expected[i] = v;
      }
    }
    const fs::path in = dir_ / ("in_" + to_string(type) + ".raw"),
                   out = dir_ / ("out_" + to_string(type) + ".raw");
    std::ofstream(in, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    const Volume v = read_raw_volume(in, dims, type);
    EXPECT_EQ(v.dims, dims);
    EXPECT_EQ(v.samples, expected) << to_string(type);
    EXPECT_FALSE(v.is_sparse());
    write_raw_volume(v, out);
    std::ifstream back(out, std::ios::binary);
    const std::vector<char> written((std::istreambuf_iterator<char>(back)), std::istreambuf_iterator<char>());
    EXPECT_EQ(written, bytes) << to_string(type);
  }
}

TEST_F(VolumeTest, RawIntegerWriteRoundsAndClamps) {
  Volume v({4, 1, 1}, VoxelType::u8);
  v.samples = {-3.0, 2.6, 300.0, std::numeric_limits<double>::quiet_NaN()};
  write_raw_volume(v, dir_ / "c.raw");
  EXPECT_EQ(read_raw_volume(dir_ / "c.raw", {4, 1, 1}, VoxelType::u8).samples,
            (std::vector<double>{0, 3, 255, 0}));
}

TEST_F(VolumeTest, RawSharedSimulationField) {
  const Volume v =
      read_raw_volume(std::string(PUPWAVE_TESTIMAGES_DIR) + "/wmag91.float", {91, 91, 91}, VoxelType::f32);
  const auto [lo, hi] = std::minmax_element(v.samples.begin(), v.samples.end());
  EXPECT_NEAR(*hi - *lo, 265.25, 0.01);  // the value range quoted in testimages/README.md
}

// Writes grids with write_vdb after read_vdb and compares with OpenVDB's view of both files.
template <class GridT>
void expect_vdb_round_trip(const fs::path& in, const fs::path& out) {
  write_vdb(read_vdb(in), out);
  const openvdb::GridPtrVec a = read_grids(in), b = read_grids(out);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto ga = openvdb::gridPtrCast<GridT>(a[i]);
    auto gb = openvdb::gridPtrCast<GridT>(b[i]);
    ASSERT_TRUE(ga && gb) << "grid type changed";
    EXPECT_EQ(ga->getName(), gb->getName());
    EXPECT_EQ(ga->getGridClass(), gb->getGridClass());
    EXPECT_EQ(ga->transform().baseMap()->getAffineMap()->getMat4(),
              gb->transform().baseMap()->getAffineMap()->getMat4());
    EXPECT_TRUE(same_voxels(*ga, *gb));
    for (auto it = ga->beginMeta(); it != ga->endMeta(); ++it) {
      if (it->first.rfind("file_", 0) == 0) continue;
      const openvdb::Metadata::ConstPtr m = (*gb)[it->first];
      ASSERT_TRUE(m) << "metadata " << it->first << " lost";
      EXPECT_EQ(m->typeName(), it->second->typeName()) << it->first;
      EXPECT_EQ(m->str(), it->second->str()) << it->first;
    }
  }
}

TEST_F(VolumeTest, VdbLevelSetAndFogFromOpenVdbTools) {
  expect_vdb_round_trip<openvdb::FloatGrid>(testimage("sphere_ls.vdb"), dir_ / "sphere.vdb");
  expect_vdb_round_trip<openvdb::FloatGrid>(testimage("dodeca_fog.vdb"), dir_ / "fog.vdb");
  const auto grids = read_vdb_dense(testimage("sphere_ls.vdb"));
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0].grid_class, GridClass::level_set);
  EXPECT_EQ(grids[0].volume.dims, (Extent{63, 63, 63}));
  EXPECT_EQ(grids[0].origin, (std::array<std::int64_t, 3>{-31, -31, -31}));
  EXPECT_EQ(grids[0].volume.active_count(), 63534u);  // as vdb_print reports
}

// Odd-sized sparse float and double grids with every supported metadata type, a rotated,
// non-uniformly scaled and translated transform, several grids (one repeated name) per file.
TEST_F(VolumeTest, VdbSparseGridsOddSizesMetadataTransform) {
  auto f = random_grid<openvdb::FloatGrid>({-13, 5, 7}, {37, 29, 23}, 0.4, 1);
  auto d = random_grid<openvdb::DoubleGrid>({100, -50, 3}, {9, 31, 17}, 0.7, 2);
  auto f2 = random_grid<openvdb::FloatGrid>({0, 0, 0}, {1, 1, 1}, 1.0, 3);
  f->setName("density");
  f->setGridClass(openvdb::GRID_FOG_VOLUME);
  d->setName("sdf");
  d->setGridClass(openvdb::GRID_LEVEL_SET);
  f2->setName("density");
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(0.5);
  xf->preScale(openvdb::Vec3d(1.0, 2.0, 3.0));
  xf->postRotate(0.3, openvdb::math::Y_AXIS);
  xf->postTranslate(openvdb::Vec3d(1.5, -2.0, 0.25));
  d->setTransform(xf);
  d->insertMeta("units", openvdb::StringMetadata("metres"));
  d->insertMeta("flag", openvdb::BoolMetadata(true));
  d->insertMeta("frame", openvdb::Int32Metadata(-12));
  d->insertMeta("big", openvdb::Int64Metadata(std::int64_t(1) << 40));
  d->insertMeta("gain", openvdb::FloatMetadata(0.1f));
  d->insertMeta("time", openvdb::DoubleMetadata(1.0 / 3.0));
  d->insertMeta("cells", openvdb::Vec3IMetadata(openvdb::Vec3i(1, -2, 3)));
  d->insertMeta("wind", openvdb::Vec3SMetadata(openvdb::Vec3s(0.5f, 0.25f, -1.0f)));
  d->insertMeta("centre", openvdb::Vec3DMetadata(openvdb::Vec3d(1.0 / 7.0, 2.0, 3.0)));
  write_grids({f, f2}, dir_ / "floats.vdb");
  write_grids({d}, dir_ / "doubles.vdb");
  expect_vdb_round_trip<openvdb::FloatGrid>(dir_ / "floats.vdb", dir_ / "floats_out.vdb");
  expect_vdb_round_trip<openvdb::DoubleGrid>(dir_ / "doubles.vdb", dir_ / "doubles_out.vdb");
  const auto read = read_vdb(dir_ / "doubles.vdb");
  EXPECT_EQ(read[0].volume.type, VoxelType::f64);
  EXPECT_EQ(read[0].metadata.at("big").integer, std::int64_t(1) << 40);
  EXPECT_EQ(read_vdb(dir_ / "floats.vdb", "density").size(), 2u);
}

TEST_F(VolumeTest, VdbNamedGridAndUnsupportedTypes) {
  auto f = random_grid<openvdb::FloatGrid>({0, 0, 0}, {5, 6, 7}, 0.5, 4);
  f->setName("a");
  auto m = openvdb::Int32Grid::create();
  m->tree().setValue(openvdb::Coord(1, 2, 3), 7);
  m->setName("mask");
  auto v = openvdb::Vec3SGrid::create();
  v->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1, 2, 3));
  v->setName("velocity");
  write_grids({v, f, m}, dir_ / "mixed.vdb");
  std::vector<std::string> skipped;
  const auto all = read_vdb(dir_ / "mixed.vdb", {}, &skipped);
  // The int32 grid is kept (carried as OpenVDB bytes), never dropped; the vec3s grid becomes its
  // three components (coded lossy, joined again by write_vdb).
  ASSERT_EQ(all.size(), 5u);  // in OpenVDB's order (by name)
  EXPECT_EQ(all[0].name, "a");
  EXPECT_FALSE(all[0].is_opaque());
  EXPECT_EQ(all[1].name, "mask");
  EXPECT_TRUE(all[1].is_opaque());
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(all[2 + c].name, "velocity");
    EXPECT_FALSE(all[2 + c].is_opaque());
    EXPECT_EQ(all[2 + c].active_voxels(), 1u);
  }
  EXPECT_EQ(skipped, (std::vector<std::string>{"mask"}));
  EXPECT_TRUE(read_vdb(dir_ / "mixed.vdb", "mask").at(0).is_opaque());
  write_vdb(all, dir_ / "back.vdb");
  const openvdb::GridPtrVec back = read_grids(dir_ / "back.vdb");
  ASSERT_EQ(back.size(), 3u);
  const auto v_back = openvdb::gridPtrCast<openvdb::Vec3SGrid>(back[2]);
  ASSERT_TRUE(v_back);
  EXPECT_TRUE(same_voxels(*v, *v_back));
  try {
    read_vdb(dir_ / "mixed.vdb", "nope");
    FAIL() << "missing grid accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'a'"), std::string::npos) << e.what();  // lists the grids
  }
}

// A dense Volume (no mask) becomes a grid with every voxel active; an empty grid stays empty.
TEST_F(VolumeTest, VdbDenseAndEmptyGrids) {
  VolumeGrid dense;
  dense.name = "dense";
  dense.origin = {-3, 4, 5};
  dense.volume = Volume({3, 4, 5}, VoxelType::f32);
  for (std::size_t i = 0; i < dense.volume.count(); ++i)
    dense.volume.samples[i] = double(i % 3);  // zeros included
  VolumeGrid empty;
  empty.name = "empty";
  empty.volume.background = 2.0;
  write_vdb({dense, empty}, dir_ / "d.vdb");
  const auto back = read_vdb_dense(dir_ / "d.vdb");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].origin, dense.origin);
  EXPECT_EQ(back[0].volume.samples, dense.volume.samples);
  EXPECT_EQ(back[0].volume.active_count(), 60u);
  EXPECT_EQ(back[1].volume.count(), 0u);
  EXPECT_EQ(back[1].volume.background, 2.0);
}

}  // namespace
}  // namespace pupwave::test

namespace pupwave::test {
namespace {

// The CLI path: the real simulation field raw -> .vdb -> raw comes back byte for byte.
TEST_F(VolumeTest, ConvertVolumeCliRoundTrip) {
  const std::string wmag = std::string(PUPWAVE_TESTIMAGES_DIR) + "/wmag91.float";
  const fs::path vdb = dir_ / "wmag.vdb", raw = dir_ / "wmag.raw";
  CliResult r = run_cli(
      {"convert-volume", wmag, vdb.string(), "--dims", "91,91,91", "--dtype", "f32", "--name", "wmag"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli({"convert-volume", vdb.string(), raw.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream a(wmag, std::ios::binary), b(raw, std::ios::binary);
  EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), std::istreambuf_iterator<char>(),
                         std::istreambuf_iterator<char>(b), std::istreambuf_iterator<char>()));
  EXPECT_EQ(read_grids(vdb)[0]->getName(), "wmag");
  const CliResult no_dims = run_cli({"convert-volume", wmag, (dir_ / "x.vdb").string()});
  EXPECT_EQ(no_dims.exit_code, 1);
  EXPECT_NE(no_dims.output.find("--dims"), std::string::npos) << no_dims.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.vdb"));
}

}  // namespace
}  // namespace pupwave::test

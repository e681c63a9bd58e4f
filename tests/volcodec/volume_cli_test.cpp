// CLI cases: raw and .vdb volumes through `pupwave compress` / `decompress`, --level, and
// rejected inputs that must exit non-zero with a clear message and leave no output file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/run_cli.h"
#include "tools/volume_io.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;
using test::run_cli;

class VolumeCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("pupwave_volcodec_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(VolumeCli, RawFloatRoundTripWithinTheBound) {
  const Volume v = test::smooth_volume({17, 23, 9}, VoxelType::f32, 50.0);
  cli::write_raw_volume(v, path("in.raw"));
  auto r = run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "17,23,9", "--dtype", "f32",
                    "--max-error", "0.01", "--brick", "8"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli({"decompress", path("v.pw"), path("out.raw")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Volume out = cli::read_raw_volume(path("out.raw"), v.dims, VoxelType::f32);
  EXPECT_LE(test::worst_error(v, out), 0.01);
}

TEST_F(VolumeCli, RawU16IsLosslessByDefault) {
  const Volume v = test::smooth_volume({9, 14, 5}, VoxelType::u16, 60000.0);
  cli::write_raw_volume(v, path("in.raw"));
  ASSERT_EQ(
      run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "9,14,5", "--dtype", "u16"}).exit_code, 0);
  ASSERT_EQ(run_cli({"decompress", path("v.pw"), path("out.raw")}).exit_code, 0);
  EXPECT_EQ(cli::read_raw_volume(path("out.raw"), v.dims, VoxelType::u16).samples, v.samples);
}

TEST_F(VolumeCli, VdbRoundTripKeepsTopologyAndBackground) {
  for (const char* name : {"sphere_ls.vdb", "dodeca_fog.vdb"}) {
    const std::string in = std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
    auto r = run_cli({"compress", in, path("v.pw"), "--max-error", "1e-3", "--transform", "cdf53"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = run_cli({"decompress", path("v.pw"), path("out.vdb")});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto a = cli::read_vdb_dense(in), b = cli::read_vdb_dense(path("out.vdb"));
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t g = 0; g < a.size(); ++g) {
      EXPECT_EQ(a[g].name, b[g].name);
      EXPECT_EQ(a[g].grid_class, b[g].grid_class);
      EXPECT_EQ(a[g].origin, b[g].origin);
      EXPECT_EQ(a[g].volume.dims, b[g].volume.dims);
      EXPECT_EQ(a[g].volume.background, b[g].volume.background);
      EXPECT_EQ(a[g].volume.active, b[g].volume.active) << name;
      EXPECT_LE(test::worst_error(a[g].volume, b[g].volume), 1e-3) << name;
    }
  }
}

TEST_F(VolumeCli, LevelGivesTheReducedDims) {
  const Volume v = test::smooth_volume({33, 20, 7}, VoxelType::f32, 1.0);
  cli::write_raw_volume(v, path("in.raw"));
  ASSERT_EQ(run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "33,20,7", "--dtype", "f32",
                     "--step", "0.001", "--brick", "16", "--levels", "2"})
                .exit_code,
            0);
  ASSERT_EQ(run_cli({"decompress", path("v.pw"), path("l2.raw"), "--level", "2"}).exit_code, 0);
  EXPECT_EQ(fs::file_size(path("l2.raw")), std::uintmax_t(9 * 5 * 2 * 4));
  const auto r = run_cli({"decompress", path("v.pw"), path("l3.raw"), "--level", "3"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(path("l3.raw")));
}

TEST_F(VolumeCli, DamagedStreamsAndBadInputsLeaveNoOutput) {
  const Volume v = test::smooth_volume({12, 10, 8}, VoxelType::f32, 1.0);
  cli::write_raw_volume(v, path("in.raw"));
  ASSERT_EQ(
      run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "12,10,8", "--dtype", "f32"}).exit_code,
      0);
  std::ifstream f(path("v.pw"), std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  for (std::size_t cut : {std::size_t(3), std::size_t(40), bytes.size() / 2, bytes.size() - 1}) {
    std::ofstream(path("cut.pw"), std::ios::binary).write(bytes.data(), std::streamsize(cut));
    const auto r = run_cli({"decompress", path("cut.pw"), path("out.raw")});
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("out.raw")));
  }
  bytes[bytes.size() / 2] ^= 0x10;
  std::ofstream(path("flip.pw"), std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
  EXPECT_NE(run_cli({"decompress", path("flip.pw"), path("out.raw")}).exit_code, 0);
  EXPECT_FALSE(fs::exists(path("out.raw")));
  auto r = run_cli(
      {"compress", path("in.raw"), path("bad.pw"), "--dims", "100000,100000,100000", "--dtype", "f32"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(path("bad.pw")));
  r = run_cli(
      {"compress", path("in.raw"), path("bad.pw"), "--dims", "12,10,8", "--dtype", "f32", "--lossless"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(path("bad.pw")));
}

}  // namespace
}  // namespace pupwave

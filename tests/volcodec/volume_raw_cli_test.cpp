// Raw volumes through the CLI in their own type: a u8 file (mapped read-only, encoded from a
// view) comes back byte for byte, to a file and to stdout (decoded into a u8 buffer); the stream
// is written to the output file chunk by chunk, yet a failed encode leaves no output and never
// clobbers an existing file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "cli/run_cli.h"
#include "tools/atomic_file.h"
#include "tools/volume_io.h"
#include "volcodec/volcodec_test_util.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;
using test::run_cli;

class VolumeRawCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pupwave_rawcli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(VolumeRawCli, U8RawRoundTripsByteForByte) {
  const Volume v = test::smooth_volume({37, 21, 11}, VoxelType::u8, 255.0);
  cli::write_raw_volume(v, path("in.raw"));
  auto r = run_cli(
      {"compress", path("in.raw"), path("v.pw"), "--dims", "37,21,11", "--dtype", "u8", "--brick", "16"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(std::to_string(fs::file_size(path("v.pw"))) + " bytes"), std::string::npos)
      << r.output;
  r = run_cli({"decompress", path("v.pw"), path("out.raw")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto original = cli::read_file_bytes(path("in.raw"));
  EXPECT_EQ(cli::read_file_bytes(path("out.raw")), original);
  r = test::run_shell_output(std::string(PUPWAVE_CLI) + " decompress '" + path("v.pw") + "' - -q > '" +
                             path("stdout.raw") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(cli::read_file_bytes(path("stdout.raw")), original);
}

TEST_F(VolumeRawCli, FailedEncodeLeavesTheOutputUntouched) {
  Volume v = test::smooth_volume({9, 8, 7}, VoxelType::f32, 1.0);
  v.samples[100] = std::numeric_limits<double>::quiet_NaN();
  cli::write_raw_volume(v, path("nan.raw"));
  {
    std::ofstream keep(path("v.pw"));
    keep << "keep me";
  }
  const auto r = run_cli({"compress", path("nan.raw"), path("v.pw"), "--dims", "9,8,7", "--dtype", "f32"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("non-finite"), std::string::npos) << r.output;
  EXPECT_EQ(fs::file_size(path("v.pw")), 7u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 2);  // no temporary left
}

}  // namespace
}  // namespace pupwave

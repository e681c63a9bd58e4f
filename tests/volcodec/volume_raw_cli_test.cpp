// Raw volumes through the CLI in their own type: a u8 file (mapped read-only, encoded from a
// view) comes back byte for byte, to a file and to stdout (decoded into a u8 buffer); the stream
// is written to the output file chunk by chunk, yet a failed encode leaves no output and never
// clobbers an existing file. A u8 bound below 1 codes lossless and says so; decoding to a file
// (its slabs unmapped once written) gives the bytes decoding to stdout does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

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

// The CLI's max-error mode codes float volumes with pups:cinpact-interp-vm4 unless --transform
// says otherwise: the default stream is the explicit vm4 one, not the cdf97 one.
TEST_F(VolumeRawCli, MaxErrorDefaultsToTheVm4Bank) {
  const Volume v = test::smooth_volume({37, 21, 11}, VoxelType::f32, 10.0);
  cli::write_raw_volume(v, path("in.raw"));
  auto encode = [&](const std::string& out, std::vector<std::string> extra) {
    std::vector<std::string> args = {"compress", path("in.raw"), path(out), "--dims",
                                     "37,21,11", "--dtype",      "f32",     "--max-error-rel",
                                     "1e-3",     "--brick",      "16",      "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return cli::read_file_bytes(path(out));
  };
  const auto by_default = encode("d.pw", {});
  EXPECT_EQ(by_default, encode("vm4.pw", {"--transform", "pups:cinpact-interp-vm4"}));
  EXPECT_NE(by_default, encode("cdf97.pw", {"--transform", "cdf97"}));
}

// An integer volume's errors are whole numbers: a bound below 1 allows none, and the CLI codes
// the lossless stream (smaller than transform coding plus a correction for most voxels) and says
// so; --max-error-rel 1e-3 of a u8 range (0.255) is such a bound.
TEST_F(VolumeRawCli, U8BoundBelowOneCodesLosslessAndSaysSo) {
  const Volume v = test::smooth_volume({37, 21, 11}, VoxelType::u8, 255.0);
  cli::write_raw_volume(v, path("in.raw"));
  const std::vector<std::string> raw = {"--dims", "37,21,11", "--dtype", "u8", "--brick", "16"};
  const auto compress = [&](const std::string& out, std::vector<std::string> flags) {
    std::vector<std::string> args = {"compress", path("in.raw"), path(out)};
    args.insert(args.end(), raw.begin(), raw.end());
    args.insert(args.end(), flags.begin(), flags.end());
    return run_cli(args);
  };
  auto r = compress("lossless.pw", {"--lossless"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("coded lossless instead"), std::string::npos) << r.output;
  for (const std::vector<std::string>& flags : {std::vector<std::string>{"--max-error", "0.3"},
                                                std::vector<std::string>{"--max-error-rel", "1e-3"}}) {
    r = compress("bound.pw", flags);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("allows no error"), std::string::npos) << flags[0] << r.output;
    EXPECT_NE(r.output.find("coded lossless instead"), std::string::npos) << flags[0] << r.output;
    EXPECT_EQ(cli::read_file_bytes(path("bound.pw")), cli::read_file_bytes(path("lossless.pw"))) << flags[0];
  }
  r = compress("two.pw", {"--max-error", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("coded lossless instead"), std::string::npos) << r.output;
  ASSERT_EQ(run_cli({"decompress", path("two.pw"), path("two.raw")}).exit_code, 0);
  EXPECT_LE(test::worst_error(v, cli::read_raw_volume(path("two.raw"), v.dims, VoxelType::u8)), 2.0);
}

// Decoding to a raw file unmaps each z-slab of the output once written (whole pages: planes of
// 64x64 u8 voxels are 4 KiB, slabs of --brick 8 are 8 planes): the file must hold what the
// decode to stdout (into memory, nothing unmapped) gives, byte for byte.
TEST_F(VolumeRawCli, DecodeToFileReleasingSlabsEqualsDecodeToStdout) {
  for (const char* type : {"u8", "f32"}) {
    const VoxelType t = std::string(type) == "u8" ? VoxelType::u8 : VoxelType::f32;
    const Volume v = test::smooth_volume({64, 64, 37}, t, 255.0);
    cli::write_raw_volume(v, path("in.raw"));
    auto r = run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "64,64,37", "--dtype", type,
                      "--brick", "8", "--max-error", "0.5"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = run_cli({"decompress", path("v.pw"), path("out.raw"), "--threads", "2"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    r = test::run_shell_output(std::string(PUPWAVE_CLI) + " decompress '" + path("v.pw") + "' - -q > '" +
                               path("stdout.raw") + "'");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto file = cli::read_file_bytes(path("out.raw"));
    EXPECT_EQ(file.size(), v.count() * (t == VoxelType::u8 ? 1u : 4u)) << type;
    EXPECT_EQ(file, cli::read_file_bytes(path("stdout.raw"))) << type;
    if (t == VoxelType::u8) EXPECT_EQ(file, cli::read_file_bytes(path("in.raw")));  // 0.5: lossless
  }
}

TEST_F(VolumeRawCli, FailedEncodeLeavesTheOutputUntouched) {
  Volume v = test::smooth_volume({9, 8, 7}, VoxelType::f32, 1.0);
  cli::write_raw_volume(v, path("in.raw"));
  {
    std::ofstream keep(path("v.pw"));
    keep << "keep me";
  }
  // A bound finer than the coder resolves is found once the input is read and the output opened.
  const auto r = run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "9,8,7", "--dtype", "f32",
                          "--max-error", "1e-30"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("finer than the volume coder resolves"), std::string::npos) << r.output;
  EXPECT_EQ(fs::file_size(path("v.pw")), 7u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 2);  // no temporary left
}

// A raw float file with NaN, an infinity and --fill-value voxels: they come back byte for byte,
// the rest within the bound, and `pupwave info` counts them.
TEST_F(VolumeRawCli, MissingValuesComeBackExactAndInfoCountsThem) {
  Volume v = test::smooth_volume({19, 17, 13}, VoxelType::f32, 10.0);
  for (std::size_t i = 0; i < v.count(); i += 5) v.samples[i] = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 1; i < 200; i += 2) v.samples[i] = -999.0;
  v.samples[2] = std::numeric_limits<double>::infinity();
  cli::write_raw_volume(v, path("in.raw"));
  auto r = run_cli({"compress", path("in.raw"), path("v.pw"), "--dims", "19,17,13", "--dtype", "f32",
                    "--max-error", "0.01", "--fill-value", "-999"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_cli({"decompress", path("v.pw"), path("out.raw")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto in = cli::read_file_bytes(path("in.raw")), out = cli::read_file_bytes(path("out.raw"));
  ASSERT_EQ(in.size(), out.size());
  std::size_t missing = 0;
  for (std::size_t i = 0; i < v.count(); ++i) {
    float a = 0, b = 0;
    std::memcpy(&a, in.data() + 4 * i, 4);
    std::memcpy(&b, out.data() + 4 * i, 4);
    if (!std::isfinite(a) || a == -999.0f) {
      ++missing;
      EXPECT_EQ(std::memcmp(in.data() + 4 * i, out.data() + 4 * i, 4), 0) << i;
    } else {
      EXPECT_LE(std::abs(double(a) - double(b)), 0.01) << i;
    }
  }
  r = run_cli({"info", path("v.pw")});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(std::to_string(missing) + " missing voxels"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace pupwave

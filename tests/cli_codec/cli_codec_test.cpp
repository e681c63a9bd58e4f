// End-to-end tests of `pupwave compress` / `pupwave decompress` through the real binary on
// the test photographs: rate targets, lossless, reduced resolution, and rejected inputs.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "codec/format/crc32.h"
#include "codec/image/image_metrics.h"
#include "tools/atomic_file.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int status = 0;
  std::string output;  // stdout and stderr
};

CliRun run_cli(const std::string& args) {
  const std::string command = std::string(PUPWAVE_CLI) + " " + args + " 2>&1";
  CliRun r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return {-1, "popen failed"};
  char buf[4096];
  while (std::fgets(buf, sizeof buf, pipe)) r.output += buf;
  r.status = pclose(pipe);
  return r;
}

class CliCodec : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pupwave_cli_codec_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string tmp(const std::string& name) const { return (dir_ / name).string(); }
  static std::string image(const std::string& name) {
    return std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
  }
  fs::path dir_;
};

double psnr(const std::string& a, const std::string& b) {
  return compare_images(cli::read_image(a), cli::read_image(b)).overall.psnr;
}

TEST_F(CliCodec, BppTargetIsMetOnAPhotograph) {
  for (const char* name : {"camera.png", "astronaut.png"}) {
    const CliRun c = run_cli("compress " + image(name) + " " + tmp("a.pw") + " --bpp 0.5");
    ASSERT_EQ(c.status, 0) << c.output;
    const CliRun d = run_cli("decompress " + tmp("a.pw") + " " + tmp("a.png"));
    ASSERT_EQ(d.status, 0) << d.output;
    const double bpp = double(fs::file_size(tmp("a.pw"))) * 8.0 / (512.0 * 512.0);
    EXPECT_LE(bpp, 0.5);
    EXPECT_GE(bpp, 0.495);
    EXPECT_GT(psnr(image(name), tmp("a.png")), 30.0) << name;
  }
}

TEST_F(CliCodec, PsnrTargetIsMetAndReported) {
  const CliRun c = run_cli("compress " + image("coffee.png") + " " + tmp("c.pw") + " --psnr 36");
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("PSNR"), std::string::npos);
  ASSERT_EQ(run_cli("decompress " + tmp("c.pw") + " " + tmp("c.png")).status, 0);
  const double p = psnr(image("coffee.png"), tmp("c.png"));
  EXPECT_GE(p, 35.9);
  EXPECT_LE(p, 37.0);
}

TEST_F(CliCodec, LosslessIsBitExact) {
  for (const char* name : {"camera.png", "chelsea.png"}) {
    ASSERT_EQ(run_cli("compress " + image(name) + " " + tmp("l.pw") + " --lossless").status, 0);
    ASSERT_EQ(run_cli("decompress " + tmp("l.pw") + " " + tmp("l.png")).status, 0);
    EXPECT_EQ(cli::read_image(image(name)).samples, cli::read_image(tmp("l.png")).samples) << name;
  }
}

TEST_F(CliCodec, ReducedResolutionDecoding) {
  ASSERT_EQ(run_cli("compress " + image("astronaut.png") + " " + tmp("r.pw") + " --step 2").status, 0);
  const CliRun d = run_cli("decompress " + tmp("r.pw") + " " + tmp("r.png") + " --level 2");
  ASSERT_EQ(d.status, 0) << d.output;
  const Image low = cli::read_image(tmp("r.png"));
  EXPECT_EQ(low.width, 128u);
  EXPECT_EQ(low.height, 128u);
  EXPECT_EQ(low.channels, 3u);
  EXPECT_NE(run_cli("decompress " + tmp("r.pw") + " " + tmp("bad.png") + " --level 40").status, 0);
  EXPECT_FALSE(fs::exists(tmp("bad.png")));
}

TEST_F(CliCodec, BadStreamsFailWithoutOutput) {
  ASSERT_EQ(run_cli("compress " + image("chelsea.png") + " " + tmp("g.pw") + " --bpp 0.5").status, 0);
  const auto good = cli::read_file_bytes(tmp("g.pw"));
  std::mt19937 rng(1);
  std::vector<std::vector<std::uint8_t>> bad = {{}, {good.begin(), good.begin() + 100}};
  bad.emplace_back(good.begin(), good.end() - 1);
  bad.push_back(good);
  bad.back()[good.size() / 2] ^= 0x10;  // a flipped payload bit
  bad.emplace_back(3000);
  for (auto& b : bad.back()) b = std::uint8_t(rng());
  for (std::size_t k = 0; k < bad.size(); ++k) {
    std::ofstream(tmp("bad.pw"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bad[k].data()), std::streamsize(bad[k].size()));
    const CliRun d = run_cli("decompress " + tmp("bad.pw") + " " + tmp("bad.png"));
    EXPECT_NE(d.status, 0) << "case " << k;
    EXPECT_NE(d.output.find("pupwave: error"), std::string::npos) << d.output;
    EXPECT_FALSE(fs::exists(tmp("bad.png"))) << "case " << k;
  }
}

TEST_F(CliCodec, BadOptionsFailWithoutOutput) {
  for (const char* args : {" --transform nope", " --lossless --transform cdf97", " --bpp 1 --psnr 30"}) {
    const CliRun c = run_cli("compress " + image("camera.png") + " " + tmp("o.pw") + args);
    EXPECT_NE(c.status, 0) << args;
    EXPECT_FALSE(fs::exists(tmp("o.pw"))) << args;
  }
}

// Pins the streams of a real photograph (see tests/codec/golden_stream_test.cpp): the bit-plane
// coder's lossless stream, and the lc coder's (the --lossless default).
TEST_F(CliCodec, GoldenLosslessStreamOfCamera) {
  ASSERT_EQ(
      run_cli("compress " + image("camera.png") + " " + tmp("g.pw") + " --lossless --entropy ebcot").status,
      0);
  EXPECT_EQ(crc32(cli::read_file_bytes(tmp("g.pw"))), 2862832164u);  // stream version 6
  ASSERT_EQ(run_cli("compress " + image("camera.png") + " " + tmp("l.pw") + " --lossless").status, 0);
  EXPECT_EQ(crc32(cli::read_file_bytes(tmp("l.pw"))), 210865946u);  // stream version 6, entropy coder 3
}

}  // namespace
}  // namespace pupwave

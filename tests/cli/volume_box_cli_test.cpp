// `pupwave decompress --box` on wmag91 (a real turbulence field, testimages/README.md): the raw
// output is, byte for byte, the box cut out of the whole decode at the same level (lossy f32 and
// lossless u16 streams); bad boxes, malformed ones and --box on an image are refused by name.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli/run_cli.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;
using test::run_cli;

class VolumeBoxCli : public ::testing::Test {
 public:
  std::string out(const std::string& name) const { return (dir_ / name).string(); }

 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_box_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string wmag91() { return std::string(PUPWAVE_TESTIMAGES_DIR) + "/wmag91.float"; }
  fs::path dir_;
};

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Box {
  std::size_t lo[3], hi[3];
  std::string flag() const {
    return std::to_string(lo[0]) + "," + std::to_string(lo[1]) + "," + std::to_string(lo[2]) + ":" +
           std::to_string(hi[0]) + "," + std::to_string(hi[1]) + "," + std::to_string(hi[2]);
  }
};

// The level-`level` voxels of a raw grid of `dims` (at that level) whose footprint meets `box`.
std::vector<char> crop(const std::vector<char>& whole, const std::size_t dims[3], std::size_t bytes,
                       const Box& box, int level) {
  std::size_t first[3], n[3];
  for (int a = 0; a < 3; ++a) {
    first[a] = box.lo[a] >> level;
    n[a] = ((box.hi[a] - 1) >> level) + 1 - first[a];
  }
  std::vector<char> out;
  for (std::size_t z = first[2]; z < first[2] + n[2]; ++z)
    for (std::size_t y = first[1]; y < first[1] + n[1]; ++y) {
      const auto row = whole.begin() + std::ptrdiff_t((first[0] + dims[0] * (y + dims[1] * z)) * bytes);
      out.insert(out.end(), row, row + std::ptrdiff_t(n[0] * bytes));
    }
  return out;
}

// Decodes `stream` whole and by box at each level; the box output must be the crop.
void expect_boxes_are_crops(const VolumeBoxCli& t, const std::string& stream, std::size_t bytes,
                            const std::vector<int>& levels) {
  const std::vector<Box> boxes = {{{20, 30, 10}, {70, 40, 80}}, {{90, 0, 45}, {91, 1, 46}}};
  for (int level : levels) {
    auto r = run_cli({"decompress", stream, t.out("whole.raw"), "--level", std::to_string(level)});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::size_t n = (91 + (std::size_t(1) << level) - 1) >> level;
    const std::size_t dims[3] = {n, n, n};
    const auto whole = read_bytes(t.out("whole.raw"));
    ASSERT_EQ(whole.size(), n * n * n * bytes);
    for (const Box& box : boxes) {
      r = run_cli(
          {"decompress", stream, t.out("box.raw"), "--level", std::to_string(level), "--box", box.flag()});
      ASSERT_EQ(r.exit_code, 0) << r.output;
      EXPECT_TRUE(read_bytes(t.out("box.raw")) == crop(whole, dims, bytes, box, level))
          << "level " << level << " box " << box.flag();
    }
  }
}

TEST_F(VolumeBoxCli, LossyBoxIsTheCropOfTheWholeDecode) {
  const auto r = run_cli({"compress", wmag91(), out("v.pw"), "--dims", "91,91,91", "--dtype", "f32",
                          "--max-error", "0.05", "--brick", "32", "--levels", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_boxes_are_crops(*this, out("v.pw"), 4, {0, 2});
}

TEST_F(VolumeBoxCli, LosslessBoxIsTheCropOfTheWholeDecode) {
  // wmag91 quantized to u16 (its range 0..265.25 times 200), coded lossless.
  std::vector<float> field(91 * 91 * 91);
  std::ifstream(wmag91(), std::ios::binary)
      .read(reinterpret_cast<char*>(field.data()), std::streamsize(field.size() * 4));
  std::vector<std::uint16_t> quantized(field.size());
  for (std::size_t i = 0; i < field.size(); ++i) quantized[i] = std::uint16_t(std::lround(field[i] * 200.0f));
  std::ofstream(out("u16.raw"), std::ios::binary)
      .write(reinterpret_cast<const char*>(quantized.data()), std::streamsize(quantized.size() * 2));
  const auto r = run_cli({"compress", out("u16.raw"), out("v.pw"), "--dims", "91,91,91", "--dtype", "u16",
                          "--lossless", "--brick", "32", "--levels", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_boxes_are_crops(*this, out("v.pw"), 2, {1});
  // At level 0 a lossless box is the original's box itself.
  ASSERT_EQ(run_cli({"decompress", out("v.pw"), out("box.raw"), "--box", "3,4,5:9,8,7"}).exit_code, 0);
  std::vector<char> expected;
  for (std::size_t z = 5; z < 7; ++z)
    for (std::size_t y = 4; y < 8; ++y)
      for (std::size_t x = 3; x < 9; ++x) {
        const char* v = reinterpret_cast<const char*>(&quantized[x + 91 * (y + 91 * z)]);
        expected.insert(expected.end(), v, v + 2);
      }
  EXPECT_TRUE(read_bytes(out("box.raw")) == expected);
}

void expect_error(const test::CliResult& r, const std::vector<std::string>& needles) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("pupwave: error: "), std::string::npos) << r.output;
  for (const std::string& needle : needles)
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in:\n" << r.output;
}

TEST_F(VolumeBoxCli, BadBoxesAreRefusedByName) {
  auto r = run_cli(
      {"compress", wmag91(), out("v.pw"), "--dims", "91,91,91", "--dtype", "f32", "--max-error", "1", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_error(run_cli({"decompress", out("v.pw"), out("b.raw"), "--box", "0,0,0:91,92,91"}),
               {out("v.pw"), "box [0,91) x [0,92) x [0,91)", "outside grid", "91x91x91"});
  expect_error(run_cli({"decompress", out("v.pw"), out("b.raw"), "--box", "5,5,5:4,9,9"}),
               {out("v.pw"), "box [5,4) x [5,9) x [5,9)", "inverted"});
  expect_error(run_cli({"decompress", out("v.pw"), out("b.raw"), "--box", "1,2:3,4"}),
               {"invalid --box '1,2:3,4'"});
  expect_error(run_cli({"decompress", out("v.pw"), out("b.raw"), "--box", "-1,0,0:4,4,4"}),
               {"invalid --box"});
  EXPECT_FALSE(fs::exists(out("b.raw")));
  const std::string image = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
  ASSERT_EQ(run_cli({"compress", image, out("i.pw"), "-q"}).exit_code, 0);
  expect_error(run_cli({"decompress", out("i.pw"), out("i.png"), "--box", "0,0,0:1,1,1"}),
               {out("i.pw"), "--box applies to volume streams only"});
}

}  // namespace
}  // namespace pupwave

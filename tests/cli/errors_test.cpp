// CLI error cases: a clear message, a non-zero exit and no output file left behind.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/run_cli.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;

class CliErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(dir_);
  }
  // Files in the work folder other than the given inputs: an aborted command must leave none.
  std::size_t leftovers(std::size_t inputs) const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n - inputs;
  }
  fs::path dir_;
  const std::string camera_ = std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png";
};

void expect_failure(const test::CliResult& r, const std::string& needle) {
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in:\n" << r.output;
  EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << r.output;
}

TEST_F(CliErrors, MissingInputFile) {
  expect_failure(test::run_cli({"convert", (dir_ / "nope.png").string(), (dir_ / "out.png").string()}),
                 "nope.png");
  expect_failure(test::run_cli({"info", (dir_ / "nope.png").string()}), "nope.png");
  EXPECT_EQ(leftovers(0), 0u);
}

TEST_F(CliErrors, UnsupportedInputFormat) {
  std::ofstream(dir_ / "notes.txt") << "plain text, not an image\n";
  expect_failure(test::run_cli({"convert", (dir_ / "notes.txt").string(), (dir_ / "out.png").string()}),
                 "cannot read");
  EXPECT_EQ(leftovers(1), 0u);
}

TEST_F(CliErrors, DecompressingAnImageFileSaysItIsNoStream) {
  const auto r = test::run_cli({"decompress", camera_, (dir_ / "out.png").string()});
  expect_failure(r, "not a pupwave image stream (bad signature)");
  EXPECT_EQ(r.output.find("pupwave pupwave"), std::string::npos) << r.output;
  EXPECT_EQ(leftovers(0), 0u);
}

// A damaged stream's error names the file it came from, for images and volumes, in decompress and info.
TEST_F(CliErrors, DamagedStreamErrorsNameTheFile) {
  const std::string image = (dir_ / "camera.pw").string(), volume = (dir_ / "wmag.pw").string();
  ASSERT_EQ(test::run_cli({"compress", camera_, image, "-q"}).exit_code, 0);
  ASSERT_EQ(test::run_cli({"compress", std::string(PUPWAVE_TESTIMAGES_DIR) + "/wmag91.float", volume,
                           "--dims", "91,91,91", "--dtype", "f32", "-q"})
                .exit_code,
            0);
  for (const auto& [whole, output] : {std::pair{image, "out.png"}, std::pair{volume, "out.raw"}}) {
    const std::string cut = whole + ".cut";
    fs::copy_file(whole, cut);
    fs::resize_file(cut, fs::file_size(whole) / 2);
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"decompress", cut, (dir_ / output).string()}, {"info", cut}}) {
      const auto r = test::run_cli(args);
      expect_failure(r, "error: " + cut + ": corrupt or truncated stream");
    }
  }
  EXPECT_EQ(leftovers(4), 0u);
}

TEST_F(CliErrors, UnsupportedOutputFormat) {
  expect_failure(test::run_cli({"convert", camera_, (dir_ / "out.xyz123").string()}),
                 "unsupported image format");
  EXPECT_EQ(leftovers(0), 0u);
}

TEST_F(CliErrors, DirectoryAsOutput) {
  fs::create_directory(dir_ / "sub.png");
  expect_failure(test::run_cli({"convert", camera_, (dir_ / "sub.png").string()}), "is a directory");
  EXPECT_TRUE(fs::is_directory(dir_ / "sub.png"));
  EXPECT_EQ(leftovers(1), 0u);
}

TEST_F(CliErrors, UnwritablePath) {
  expect_failure(test::run_cli({"convert", camera_, (dir_ / "missing" / "out.png").string()}),
                 "does not exist");
  if (::geteuid() != 0) {  // root ignores permission bits; the missing-folder case covers it there
    fs::permissions(dir_, fs::perms::owner_write, fs::perm_options::remove);
    expect_failure(test::run_cli({"convert", camera_, (dir_ / "out.png").string()}), "cannot write");
    fs::permissions(dir_, fs::perms::owner_write, fs::perm_options::add);
  }
  EXPECT_EQ(leftovers(0), 0u);
}

TEST_F(CliErrors, ExistingOutputIsNotClobberedOnFailure) {
  const fs::path out = dir_ / "keep.pgm";
  std::ofstream(out) << "precious";
  // Two channels cannot go into a PGM: the write fails after the output was opened.
  pupwave::Image grey_alpha(4, 4, 2, SampleType::u8);
  cli::write_image(grey_alpha, dir_ / "ga.png");
  expect_failure(test::run_cli({"convert", (dir_ / "ga.png").string(), out.string()}), "cannot write");
  std::ifstream in(out);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "precious");
  EXPECT_EQ(leftovers(2), 0u);
}

TEST_F(CliErrors, UnknownSubcommandAndMissingArguments) {
  EXPECT_NE(test::run_cli({"frobnicate"}).exit_code, 0);
  EXPECT_NE(test::run_cli({"psnr", camera_}).exit_code, 0);
  EXPECT_NE(test::run_cli({}).exit_code, 0);
}

TEST(CliHelp, EverySubcommandHasHelp) {
  for (const char* sub : {"info", "psnr", "convert", "compress", "decompress"}) {
    const auto r = test::run_cli({sub, "--help"});
    EXPECT_EQ(r.exit_code, 0) << sub << "\n" << r.output;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
}

TEST(CliConvert, RoundTripThroughEveryFormatKeepsPixels) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_conv_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string astronaut = std::string(PUPWAVE_TESTIMAGES_DIR) + "/astronaut.png";
  const Image ref = cli::read_image(astronaut);
  for (const char* ext : {".tif", ".ppm", ".png", ".exr"}) {
    const fs::path out = dir / (std::string("a") + ext);
    const auto r = test::run_cli({"convert", astronaut, out.string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    Image back = cli::read_image(out);
    if (back.type != ref.type) back = cli::convert_sample_type(back, ref.type);
    EXPECT_EQ(back.samples, ref.samples) << ext;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pupwave

// Rate targets from the command line: targets that never misfire or exceed the lossless
// file, tight bounds honoured or refused up front, every numeric option validated, --levels
// capped, parse errors reported like other errors, '-' as stdin/stdout, --quiet/--verbose.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "cli/run_cli.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;
using test::run_cli;

class RateCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_rate_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string out(const std::string& name) const { return (dir_ / name).string(); }
  static std::string image(const std::string& name) {
    return std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
  }
  fs::path dir_;
};

// The number after `key` in the CLI's report (NaN if absent).
double number_after(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return std::nan("");
  return std::atof(text.c_str() + at + key.size());
}

std::vector<char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_error(const test::CliResult& r, const std::string& needle) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("pupwave: error: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in:\n" << r.output;
}

// chelsea --psnr 30 must not give a lossless-quality file (494,759 bytes, PSNR inf).
TEST_F(RateCli, PsnrTargetGivesASmallFileJustAboveTheTarget) {
  for (const auto& [name, target] :
       std::vector<std::pair<std::string, double>>{{"chelsea.png", 30.0}, {"astronaut.png", 50.0}}) {
    const auto r = run_cli({"compress", image(name), out("a.pw"), "--psnr", std::to_string(target)});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const double psnr = number_after(r.output, "PSNR ");
    EXPECT_GE(psnr, target) << r.output;
    EXPECT_LE(psnr, target + 0.15) << r.output;
    EXPECT_LT(fs::file_size(out("a.pw")), fs::file_size(image(name)));
  }
}

// camera --bpp 8, --bpp 1000 and --psnr 100 ask for more than the 126,108-byte lossless file; they
// get at most that.
TEST_F(RateCli, NoRateTargetExceedsTheLosslessFile) {
  ASSERT_EQ(run_cli({"compress", image("camera.png"), out("l.pw"), "--lossless"}).exit_code, 0);
  const auto lossless = fs::file_size(out("l.pw"));
  for (const std::vector<std::string>& rate : {std::vector<std::string>{"--bpp", "8"},
                                               {"--bpp", "1000"},
                                               {"--psnr", "100"},
                                               {"--psnr", "200"},
                                               {"--step", "1e-9"},
                                               {"--step", "0.001"}}) {
    auto args = std::vector<std::string>{"compress", image("camera.png"), out("r.pw")};
    args.insert(args.end(), rate.begin(), rate.end());
    const auto r = run_cli(args);
    SCOPED_TRACE(rate[0] + " " + rate[1]);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("coded lossless instead"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("lossless (PSNR inf)"), std::string::npos) << r.output;
    EXPECT_EQ(fs::file_size(out("r.pw")), lossless);
  }
  // A target lossy coding meets with a smaller file stays lossy and says nothing of lossless.
  const auto r = run_cli({"compress", image("camera.png"), out("r.pw"), "--bpp", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("lossless"), std::string::npos) << r.output;
  EXPECT_LT(fs::file_size(out("r.pw")), lossless);
}

// Float images have no lossless mode: bounds past float precision are refused up front.
TEST_F(RateCli, FloatImageBoundsPastFloatPrecisionAreRefused) {
  const Image grey = cli::read_image(image("camera.png"));
  Image f(grey.width, grey.height, 1, SampleType::f32);
  for (std::size_t y = 0; y < grey.height; ++y)
    for (std::size_t x = 0; x < grey.width; ++x) f.at(0, x, y) = grey.at(0, x, y) / 255.0f;
  cli::write_image(f, out("camera.exr"));
  expect_error(run_cli({"compress", out("camera.exr"), out("a.pw"), "--psnr", "200"}),
               "highest target is 120 dB");
  expect_error(run_cli({"compress", out("camera.exr"), out("a.pw"), "--step", "1e-9"}),
               "the finest step for this image is");
  EXPECT_FALSE(fs::exists(out("a.pw")));
  const auto r = run_cli({"compress", out("camera.exr"), out("a.pw"), "--psnr", "90"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GE(number_after(r.output, "PSNR "), 90.0) << r.output;
}

// --max-error 1e-6 on wmag91 and 1e-8 on a double grid of values 1..2 are refused up front, not
// part-way through with "quantization index too large for the block coder".
TEST_F(RateCli, VolumeBoundsPastThePrecisionAreRefusedUpFront) {
  const auto r = run_cli({"compress", image("wmag91.float"), out("v.pw"), "--dims", "91,91,91", "--dtype",
                          "f32", "--max-error", "1e-6"});
  expect_error(r, "the finest error bound for samples up to");
  EXPECT_EQ(r.output.find("block coder"), std::string::npos) << r.output;
  {
    std::FILE* f = std::fopen(out("ramp.f64").c_str(), "wb");
    for (int i = 0; i < 32 * 32 * 32; ++i) {
      const double v = 1.0 + double(i) / (32.0 * 32.0 * 32.0);
      std::fwrite(&v, sizeof v, 1, f);
    }
    std::fclose(f);
  }
  expect_error(run_cli({"compress", out("ramp.f64"), out("v.pw"), "--dims", "32,32,32", "--dtype", "f64",
                        "--max-error", "1e-8"}),
               "the finest error bound for samples up to 2 is 1.91e-06");
  EXPECT_FALSE(fs::exists(out("v.pw")));
  const auto ok = run_cli({"compress", out("ramp.f64"), out("v.pw"), "--dims", "32,32,32", "--dtype", "f64",
                           "--max-error", "2e-6"});
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_LE(number_after(ok.output, "max error "), 2e-6) << ok.output;
}

// NaN is refused, never ignored (falling back to --psnr 40); --bpp 0 names its range in words,
// not as a 309-digit number.
TEST_F(RateCli, EveryNumericOptionIsValidated) {
  const std::string cam = image("camera.png");
  const std::vector<std::vector<std::string>> cases = {
      {"compress", cam, out("a.pw"), "--psnr", "nan"},
      {"compress", cam, out("a.pw"), "--bpp", "nan"},
      {"compress", cam, out("a.pw"), "--step", "nan"},
      {"compress", cam, out("a.pw"), "--bpp", "0"},
      {"compress", cam, out("a.pw"), "--psnr", "-3"},
      {"compress", cam, out("a.pw"), "--psnr", "inf"},
      {"compress", cam, out("a.pw"), "--step", "-inf"},
      {"compress", cam, out("a.pw"), "--max-error", "nan"},
      {"compress", cam, out("a.pw"), "--bpv", "-1"},
      {"decompress", cam, out("a.png"), "--level", "-1"},
      {"lod", cam, out("a.vdb"), "--levels", "-2"},
      {"generate-volume", out("g.raw"), "--feed", "nan"},
      {"convert-volume", cam, out("a.vdb"), "--voxel-size", "0"},
      {"mesh", "decompose", image("pig.off"), out("a.pwm"), "--max-error", "-1"},
      {"filters", "design", "--weight", "cinpact", "--c", "nan"},
  };
  for (const auto& args : cases) {
    const auto r = run_cli(args);
    SCOPED_TRACE(args[0] + " " + args[args.size() - 2] + " " + args.back());
    expect_error(r, args[args.size() - 2]);
    EXPECT_TRUE(r.output.find("number") != std::string::npos) << r.output;
    EXPECT_FALSE(std::regex_search(r.output, std::regex("[0-9]{20}"))) << r.output;
    EXPECT_FALSE(fs::exists(out("a.pw")));
  }
}

// --levels 32 on a 33x65 image is refused, not coded at 8.7 dB.
TEST_F(RateCli, LevelsBeyondTheImageAreRefused) {
  const Image cam = cli::read_image(image("camera.png"));
  Image crop(33, 65, 1, cam.type);
  for (std::size_t y = 0; y < 65; ++y)
    for (std::size_t x = 0; x < 33; ++x) crop.at(0, x, y) = cam.at(0, x + 200, y + 100);
  cli::write_image(crop, out("crop.png"));
  expect_error(run_cli({"compress", out("crop.png"), out("a.pw"), "--levels", "32"}),
               "--levels 32 is more than a 33x65 image takes (at most 6)");
  const auto r = run_cli({"compress", out("crop.png"), out("a.pw"), "--levels", "6", "--psnr", "37"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_GE(number_after(r.output, "PSNR "), 37.0) << r.output;
}

// Parse errors exit 1 with the usual prefix (CLI11's own exits, 105/106/109, lack it); typos get
// the closest name.
TEST_F(RateCli, ParseErrorsReadLikeOtherErrorsAndSuggestNames) {
  expect_error(run_cli({"compress", image("camera.png"), out("a.pw"), "--psnrr", "30"}),
               "did you mean --psnr?");
  expect_error(run_cli({"compres", image("camera.png"), out("a.pw")}), "did you mean 'compress'?");
  expect_error(run_cli({"compress", image("camera.png")}), "OUT");
  expect_error(run_cli({"compress", image("camera.png"), out("a.pw"), "--threads", "x"}), "--threads");
  const auto bad = run_cli({"compress", image("camera.png"), out("a.pw"), "--entropy", "lzma"});
  expect_error(bad, "(one of auto, ebcot, pc, lc, ht)");
  EXPECT_EQ(bad.output.find("->"), std::string::npos) << bad.output;
  const auto help = run_cli({"compress", "--help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.output.find("->"), std::string::npos) << help.output;
}

// zstd is no image coder (its stream byte is retired): --entropy zstd is refused, nothing written.
TEST_F(RateCli, RetiredZstdCoderIsRefused) {
  const auto r = run_cli({"compress", image("camera.png"), out("a.pw"), "--entropy", "zstd", "--bpp", "1"});
  expect_error(r, "unknown entropy coder zstd (one of auto, ebcot, pc, lc, ht)");
  EXPECT_FALSE(fs::exists(out("a.pw")));
}

TEST_F(RateCli, DashIsStdinAndStdoutWithStatusOnStderr) {
  const std::string cli = test::shell_quote(PUPWAVE_CLI);
  const auto c = test::run_shell_output(
      cli + " compress - - --psnr 38 < " + test::shell_quote(image("camera.png")) + " > " +
      test::shell_quote(out("a.pw")) + " 2> " + test::shell_quote(out("status.txt")));
  ASSERT_EQ(c.exit_code, 0);
  EXPECT_GT(fs::file_size(out("status.txt")), 0u);  // the status line went to stderr
  const auto d = test::run_shell_output(cli + " decompress - - < " + test::shell_quote(out("a.pw")) + " > " +
                                        test::shell_quote(out("b.png")) + " 2>/dev/null");
  ASSERT_EQ(d.exit_code, 0);
  const Image a = cli::read_image(image("camera.png"));
  const Image b = cli::read_image(out("b.png"));
  const double psnr = compare_images(a, b).overall.psnr;
  EXPECT_GE(psnr, 38.0);
  EXPECT_LE(psnr, 38.15);
}

TEST_F(RateCli, QuietPrintsNothingAndVerboseMore) {
  const auto q = run_cli({"compress", image("camera.png"), out("a.pw"), "--quiet"});
  ASSERT_EQ(q.exit_code, 0);
  EXPECT_EQ(q.output, "");
  EXPECT_TRUE(fs::exists(out("a.pw")));
  const auto d = run_cli({"decompress", out("a.pw"), out("a.png"), "-q"});
  ASSERT_EQ(d.exit_code, 0);
  EXPECT_EQ(d.output, "");
  const auto v = run_cli({"compress", image("camera.png"), out("a.pw"), "--verbose"});
  ASSERT_EQ(v.exit_code, 0);
  EXPECT_NE(v.output.find("transform cdf97"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("base step"), std::string::npos) << v.output;
  // Errors still print with --quiet.
  expect_error(run_cli({"compress", image("camera.png"), out("a.pw"), "--quiet", "--psnr", "nan"}), "--psnr");
}

// --effort 2 (the per-band base-step choice and RDOQ) fits the same budget at a higher
// PSNR than the default on a photograph; --effort is refused where it would be ignored.
TEST_F(RateCli, EffortTwoGivesAHigherPsnrWithinTheSameBudget) {
  const auto fast = run_cli(
      {"compress", image("coffee.png"), out("e1.pw"), "--bpp", "1", "--entropy", "ebcot", "--report-psnr"});
  const auto slow = run_cli({"compress", image("coffee.png"), out("e2.pw"), "--bpp", "1", "--entropy",
                             "ebcot", "--effort", "2", "--report-psnr"});
  ASSERT_EQ(fast.exit_code, 0) << fast.output;
  ASSERT_EQ(slow.exit_code, 0) << slow.output;
  const auto budget = std::uintmax_t(1.0 * 600 * 400 / 8);  // coffee.png is 600x400
  EXPECT_LE(fs::file_size(out("e2.pw")), budget);
  EXPECT_GT(number_after(slow.output, "PSNR "), number_after(fast.output, "PSNR ") + 0.02) << slow.output;
  expect_error(run_cli({"compress", image("coffee.png"), out("a.pw"), "--psnr", "40", "--effort", "2"}),
               "--effort applies to --bpp targets only");
  // The default coder of a photograph (pc) has one search: effort is the bit-plane coder's.
  expect_error(run_cli({"compress", image("coffee.png"), out("a.pw"), "--bpp", "1", "--effort", "2"}),
               "--effort applies to the bit-plane coder: add --entropy ebcot");
  const auto bad = run_cli({"compress", image("coffee.png"), out("a.pw"), "--bpp", "1", "--effort", "3"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--effort"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(out("a.pw")));
}

// --tune visual keeps the budget and codes other bytes; it is refused where nothing is tuned.
TEST_F(RateCli, TuneVisualKeepsTheBudgetAndIsRefusedWhereItWouldBeIgnored) {
  const auto psnr = run_cli({"compress", image("coffee.png"), out("p.pw"), "--bpp", "0.5"});
  const auto visual =
      run_cli({"compress", image("coffee.png"), out("v.pw"), "--bpp", "0.5", "--tune", "visual"});
  ASSERT_EQ(psnr.exit_code, 0) << psnr.output;
  ASSERT_EQ(visual.exit_code, 0) << visual.output;
  EXPECT_LE(fs::file_size(out("v.pw")), std::uintmax_t(0.5 * 600 * 400 / 8));
  EXPECT_NE(read_bytes(out("p.pw")), read_bytes(out("v.pw")));
  expect_error(run_cli({"compress", image("coffee.png"), out("a.pw"), "--lossless", "--tune", "visual"}),
               "--tune visual applies to lossy coding, not --lossless");
  const auto bad = run_cli({"compress", image("coffee.png"), out("a.pw"), "--tune", "sharp"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--tune"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(out("a.pw")));
}

}  // namespace
}  // namespace pupwave

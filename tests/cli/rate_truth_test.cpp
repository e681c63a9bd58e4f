// Rate targets that tell the truth: a target the written file misses is said in one
// `warning:` line on stderr giving the target and what the file reached (exit 0), or
// with --strict is an error that writes nothing; a met target prints no warning; no status line
// claims a fit that did not happen.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "cli/run_cli.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;
using test::run_cli;
using test::shell_quote;

// What a run printed on stdout and on stderr, apart.
struct Split {
  int exit_code = -1;
  std::string out, err;
};

class RateTruth : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave_rate_truth_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string out(const std::string& name) const { return (dir_ / name).string(); }
  static std::string testimage(const std::string& name) {
    return std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
  }
  // Runs the CLI with stderr captured apart from stdout (stdout goes to a file in the folder).
  Split run_split(const std::vector<std::string>& args) const {
    std::string command = shell_quote(PUPWAVE_CLI);
    for (const auto& a : args) command += " " + shell_quote(a);
    const std::string stdout_file = out("stdout.txt");
    const auto r = test::run_shell_output(command + " 2>&1 >" + shell_quote(stdout_file) + " </dev/null");
    Split s{r.exit_code, contents(stdout_file), r.output};
    fs::remove(stdout_file);
    return s;
  }
  // A w x h crop of the astronaut photograph (textured suit), saved as PNG.
  std::string astronaut_crop(std::size_t w, std::size_t h) const {
    static const Image full = cli::read_image(testimage("astronaut.png"));  // read once
    Image crop(w, h, full.channels, full.type);
    for (std::size_t c = 0; c < full.channels; ++c)
      for (std::size_t y = 0; y < h; ++y)
        for (std::size_t x = 0; x < w; ++x) crop.at(c, x, y) = full.at(c, 200 + x, 150 + y);
    const std::string path = out("crop" + std::to_string(w) + "x" + std::to_string(h) + ".png");
    cli::write_image(crop, path);
    return path;
  }
  // A w^3 crop of testimages/wmag91.float (91^3 float32, x fastest), saved raw.
  std::string wmag_crop(std::size_t w) const {
    const std::string all = contents(testimage("wmag91.float"));
    EXPECT_EQ(all.size(), std::size_t(91 * 91 * 91 * 4));
    std::string crop;
    for (std::size_t z = 40; z < 40 + w; ++z)
      for (std::size_t y = 40; y < 40 + w; ++y) crop += all.substr(4 * (40 + 91 * (y + 91 * z)), 4 * w);
    const std::string path = out("wmag" + std::to_string(w) + ".raw");
    std::ofstream(path, std::ios::binary) << crop;
    return path;
  }
  // Files in the test folder (a refused run must leave no temporary file behind).
  std::size_t file_count() const {
    return std::size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  static std::string contents(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  fs::path dir_;
};

// The number right before `key` in text ("... (186 bpp)" -> 186 for " bpp)"); NaN if absent.
double number_before(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos || at == 0) return std::nan("");
  const auto start = text.find_last_of("( ", at - 1);
  return std::atof(text.c_str() + start + 1);
}

bool has(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

std::size_t count(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

// Crops of a photograph whose header alone exceeds --bpp 1 (2x2: 110 bytes, 220 bpp) are written
// with one warning, never silently and never with the claim "the lossless file fits --bpp 1".
TEST_F(RateTruth, TinyImagesMissingTheBudgetAreWrittenWithOneWarning) {
  for (const auto& [w, h] : std::vector<std::pair<std::size_t, std::size_t>>{{2, 2}, {1, 1}, {3, 5}}) {
    const std::string in = astronaut_crop(w, h), pw = out("tiny.pw");
    const Split r = run_split({"compress", in, pw, "--bpp", "1"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_TRUE(fs::exists(pw)) << r.err;
    const std::size_t bytes = fs::file_size(pw);
    const double bpp = 8.0 * double(bytes) / double(w * h);
    EXPECT_GT(bpp, 1.0);
    EXPECT_EQ(r.err.rfind("warning: --bpp 1 not met: " + pw + " is " + std::to_string(bytes) + " bytes", 0),
              0u)
        << r.err;
    EXPECT_EQ(count(r.err, "\n"), 1u) << r.err;  // one line, the warning
    EXPECT_NEAR(number_before(r.err, " bpp) for this"), bpp, 1e-3 * bpp) << r.err;
    EXPECT_TRUE(has(r.err, "for this " + std::to_string(w) + "x" + std::to_string(h) +
                               " image; its header and chunk framing alone take "))
        << r.err;
    EXPECT_FALSE(has(r.out, "fits")) << r.out;
    fs::remove(pw);
  }
}

TEST_F(RateTruth, StrictRefusesAMissedBudgetAndWritesNothing) {
  for (const auto& [w, h] : std::vector<std::pair<std::size_t, std::size_t>>{{2, 2}, {1, 1}, {3, 5}}) {
    const std::string in = astronaut_crop(w, h), pw = out("strict.pw");
    const std::size_t before = file_count();
    const Split r = run_split({"compress", in, pw, "--bpp", "1", "--strict"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err.rfind("pupwave: error: --bpp 1 not met: the stream is ", 0), 0u) << r.err;
    EXPECT_TRUE(has(r.err, " bpp) for this")) << r.err;
    EXPECT_TRUE(has(r.err, "; " + pw + " not written (--strict)\n")) << r.err;
    EXPECT_FALSE(has(r.err, "warning:")) << r.err;
    EXPECT_FALSE(fs::exists(pw));
    EXPECT_EQ(file_count(), before);  // no temporary file left either
    // An existing output stays as it was.
    std::ofstream(pw, std::ios::binary) << "an earlier file";
    const auto again = run_cli({"compress", in, pw, "--bpp", "1", "--strict"});
    EXPECT_EQ(again.exit_code, 1) << again.output;
    EXPECT_EQ(contents(pw), "an earlier file");
    fs::remove(pw);
  }
}

// forest_hdr.exr (a 512x256 half-float photograph) at --bpp 0.5 comes out at 0.74 bpp from the ht
// coder. Whatever a coder reaches, the warning is there exactly when the file is over the budget,
// and gives its true size.
TEST_F(RateTruth, WarningIsThereExactlyWhenTheFileIsOverTheBudget) {
  for (const std::string entropy : {"ht", "ebcot"}) {
    const std::string pw = out(entropy + ".pw");
    const Split r =
        run_split({"compress", testimage("forest_hdr.exr"), pw, "--bpp", "0.5", "--entropy", entropy});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::size_t bytes = fs::file_size(pw);
    const bool over = 8.0 * double(bytes) > 0.5 * 512.0 * 256.0;
    EXPECT_EQ(has(r.err, "warning: --bpp 0.5 not met: " + pw + " is " + std::to_string(bytes) + " bytes"),
              over)
        << entropy << ": " << bytes << " bytes; " << r.err;
    EXPECT_EQ(count(r.err, "warning:"), over ? 1u : 0u) << r.err;
    EXPECT_FALSE(has(r.err, "header and chunk framing")) << r.err;  // the framing is not why here
  }
}

// --strict to stdout: not a byte reaches stdout, and the error says so.
// A PSNR beyond what lossy coding of a float image reaches (forest_hdr.exr, log-PSNR 115 dB)
// writes the finest stream (not "quantization index too large" and no file), with a warning
// giving what it reaches, and --strict refuses it.
TEST_F(RateTruth, UnreachablePsnrOnAFloatImageIsWrittenAndWarned) {
  const std::string pw = out("deep.pw"), png = out("deep.exr");
  const Split r = run_split({"compress", testimage("forest_hdr.exr"), pw, "--psnr", "115"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("warning: --psnr 115 not met: " + pw + " reaches log-PSNR ", 0), 0u) << r.err;
  const double reached = number_before(r.err, " dB");
  EXPECT_GT(reached, 60.0) << r.err;
  EXPECT_LT(reached, 115.0) << r.err;
  EXPECT_EQ(run_cli({"decompress", pw, png, "-q"}).exit_code, 0);
  const auto strict =
      run_cli({"compress", testimage("forest_hdr.exr"), out("s.pw"), "--psnr", "115", "--strict"});
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
  EXPECT_FALSE(fs::exists(out("s.pw")));
}

TEST_F(RateTruth, StrictToStdoutWritesNoBytes) {
  const Split r = run_split({"compress", astronaut_crop(2, 2), "-", "--bpp", "1", "--strict"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.out.size(), 0u);
  EXPECT_TRUE(has(r.err, "; nothing written to stdout (--strict)")) << r.err;
}

// --quiet keeps the warning (a missed target is never silent) and nothing else; --strict still
// fails loudly.
TEST_F(RateTruth, QuietKeepsTheWarningAndTheStrictError) {
  const std::string in = astronaut_crop(2, 2);
  const auto quiet = run_split({"compress", in, out("q.pw"), "--bpp", "1", "--quiet"});
  EXPECT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.out, "");
  EXPECT_EQ(quiet.err.rfind("warning: --bpp 1 not met: ", 0), 0u) << quiet.err;
  EXPECT_EQ(quiet.err.find('\n'), quiet.err.size() - 1) << quiet.err;  // that line alone
  const auto strict = run_cli({"compress", in, out("s.pw"), "--bpp", "1", "--quiet", "--strict"});
  EXPECT_EQ(strict.exit_code, 1);
  EXPECT_TRUE(has(strict.output, "pupwave: error: --bpp 1 not met")) << strict.output;
}

// Targets the file meets: no warning, and --strict writes it. Where the lossless file is what
// meets a budget, the status line says it fits, and it does.
TEST_F(RateTruth, MetTargetsPrintNoWarning) {
  const std::string photo = testimage("astronaut.png");
  for (const std::vector<std::string>& rate :
       {std::vector<std::string>{"--bpp", "1"}, {"--psnr", "35"}, {"--bpp", "0.5", "--entropy", "ebcot"}}) {
    std::vector<std::string> args{"compress", photo, out("met.pw"), "--strict"};
    args.insert(args.end(), rate.begin(), rate.end());
    const Split r = run_split(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(fs::exists(out("met.pw")));
    fs::remove(out("met.pw"));
  }
  const Split r = run_split({"compress", astronaut_crop(2, 2), out("fits.pw"), "--bpp", "2000", "--strict"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  ASSERT_TRUE(fs::exists(out("fits.pw")));
  EXPECT_TRUE(has(r.out, "the lossless file fits --bpp 2000")) << r.out;
  EXPECT_LE(8.0 * double(fs::file_size(out("fits.pw"))) / 4.0, 2000.0);
}

// Volumes: a 2^3 crop of a real field cannot meet --bpv 1 (the stream's head alone is larger):
// warned, or with --strict refused with the file (streamed through the atomic writer) untouched.
TEST_F(RateTruth, VolumeBpvMissIsWarnedOrRefused) {
  const std::string raw = wmag_crop(2), pw = out("v.pw");
  const Split r = run_split({"compress", raw, pw, "--dims", "2,2,2", "--dtype", "f32", "--bpv", "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(pw));
  const double bpv = 8.0 * double(fs::file_size(pw)) / 8.0;
  EXPECT_EQ(r.err.rfind(
                "warning: --bpv 1 not met: " + pw + " is " + std::to_string(fs::file_size(pw)) + " bytes", 0),
            0u)
      << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1u) << r.err;
  EXPECT_NEAR(number_before(r.err, " bpv)"), bpv, 1e-3 * bpv) << r.err;
  std::ofstream(pw, std::ios::binary) << "an earlier file";
  const std::size_t before = file_count();
  const Split strict =
      run_split({"compress", raw, pw, "--dims", "2,2,2", "--dtype", "f32", "--bpv", "1", "--strict"});
  EXPECT_EQ(strict.exit_code, 1) << strict.err;
  EXPECT_EQ(strict.err.rfind("pupwave: error: --bpv 1 not met: the stream is ", 0), 0u) << strict.err;
  EXPECT_TRUE(has(strict.err, pw + " not written (--strict)")) << strict.err;
  EXPECT_EQ(contents(pw), "an earlier file");
  EXPECT_EQ(file_count(), before);
  // The default error bound is met (guaranteed): no warning. So is --bpv 2 on the whole field.
  const Split bound =
      run_split({"compress", raw, out("b.pw"), "--dims", "2,2,2", "--dtype", "f32", "--strict"});
  EXPECT_EQ(bound.exit_code, 0) << bound.err;
  EXPECT_EQ(bound.err, "");
  const Split met = run_split({"compress", testimage("wmag91.float"), out("full.pw"), "--dims", "91,91,91",
                               "--dtype", "f32", "--bpv", "2", "--strict"});
  EXPECT_EQ(met.exit_code, 0) << met.err;
  EXPECT_EQ(met.err, "");
}

// A PSNR beyond a float volume's own precision (200 dB on a 2x2x2 crop of wmag91) writes the
// finest stream the coder's index range allows, with a warning giving what it reaches (not a
// "quantization indices beyond the coder's range" error and no file).
TEST_F(RateTruth, UnreachableVolumePsnrIsWrittenAndWarned) {
  const std::string raw = wmag_crop(2), pw = out("deep.pw");
  const Split r = run_split({"compress", raw, pw, "--dims", "2,2,2", "--dtype", "f32", "--psnr", "200"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(pw));
  EXPECT_EQ(r.err.rfind("warning: --psnr 200 not met: " + pw, 0), 0u) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1u) << r.err;
}

}  // namespace
}  // namespace pupwave

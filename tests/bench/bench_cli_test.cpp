// End-to-end runs of `pupwave bench` on a tiny crop of a test photograph: the outputs exist and
// have the promised columns and tables, missing anchor tools are skipped with a note, failures
// are reported without losing the other results.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tools/bench/process.h"
#include "tools/bench/rd_report.h"
#include "tools/image_io.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

// Positions of results.csv columns the tests read.
constexpr std::size_t kMaxError = 11, kSsim = 12, kMsSsim = 13, kButteraugli = 14, kSetting = 17,
                      kStatus = 18;

struct CliRun {
  int exit_code = -1;
  std::string output;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs the CLI with `env_path` as its PATH (through env(1), so the test's own PATH is untouched).
CliRun run_cli(const std::vector<std::string>& args, const fs::path& log, const std::string& env_path) {
  std::vector<std::string> argv = {"/usr/bin/env", "PATH=" + env_path, PUPWAVE_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  const ProcessResult r = run_process(argv, log);
  return {r.exit_code, read_text(log)};
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

// Fatal (through ASSERT_NO_FATAL_FAILURE) unless every row of results.csv has the current
// columns, so the column positions above index real cells.
void check_results_columns(const std::vector<std::vector<std::string>>& rows) {
  ASSERT_FALSE(rows.empty());
  ASSERT_EQ(rows[0], results_csv_columns());
  for (const auto& row : rows) ASSERT_EQ(row.size(), rows[0].size());
}

class BenchCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pupwave-bench-test-" + std::to_string(getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A 96x64 crop of a real photograph keeps every codec run to a few milliseconds.
    const Image full = cli::read_image(fs::path(PUPWAVE_TESTIMAGES_DIR) / "astronaut.png");
    Image crop(96, 64, 3, full.type);
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t y = 0; y < crop.height; ++y)
        for (std::size_t x = 0; x < crop.width; ++x) crop.at(c, x, y) = full.at(c, x + 200, y + 150);
    image_ = dir_ / "crop.png";
    cli::write_image(crop, image_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_, image_;
};

TEST_F(BenchCli, SmallRdRunWritesAllOutputs) {
  const fs::path out = dir_ / "rd";
  fs::create_directories(out / "plots");
  std::ofstream(out / "plots" / "stale.svg") << "<svg/>";  // from an earlier run on other images
  const CliRun r =
      run_cli({"bench", "rd", "--images", image_.string(), "--transforms", "cdf97,cdf53", "--bpp", "0.5,2",
               "--anchors", "openjpeg,jxl", "--jobs", "2", "--out", out.string()},
              dir_ / "log.txt", environment_path());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = read_csv(out / "results.csv");
  ASSERT_NO_FATAL_FAILURE(check_results_columns(rows));
  ASSERT_EQ(rows.size(), 1u + 4 * 2) << "header + (2 transforms + 2 anchors) x 2 rates";
  std::map<std::string, std::vector<double>> psnr_by_codec;
  std::map<std::string, std::vector<std::array<double, 3>>>
      perceptual_by_codec;  // SSIM, MS-SSIM, butteraugli
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][0], "crop");
    EXPECT_EQ(rows[i][kStatus], "ok");
    const double target = std::stod(rows[i][6]), bpp = std::stod(rows[i][8]), psnr = std::stod(rows[i][9]);
    EXPECT_NEAR(bpp, 8.0 * std::stod(rows[i][7]) / (96 * 64), 1e-8);  // 10 significant digits
    EXPECT_GT(psnr, 15.0);
    EXPECT_TRUE(std::isfinite(std::stod(rows[i][10])));  // luma PSNR of a colour image
    if (rows[i][5] == "pupwave") {
      EXPECT_NEAR(bpp, target, 0.1 * target) << rows[i][4];
    }
    psnr_by_codec[rows[i][4]].push_back(psnr);
    for (std::size_t col : {kSsim, kMsSsim}) {
      const double v = std::stod(rows[i][col]);
      EXPECT_GT(v, 0.3) << rows[0][col];
      EXPECT_LE(v, 1.0) << rows[0][col];
    }
    perceptual_by_codec[rows[i][4]].push_back(
        {std::stod(rows[i][kSsim]), std::stod(rows[i][kMsSsim]), std::stod(rows[i][kButteraugli])});
  }
  ASSERT_EQ(psnr_by_codec.size(), 4u);
  for (const auto& [codec, p] : psnr_by_codec) EXPECT_LT(p[0], p[1]) << codec << ": more bits, higher PSNR";
  for (const auto& [codec, p] : perceptual_by_codec) {
    EXPECT_LT(p[0][0], p[1][0]) << codec << ": more bits, higher SSIM";
    EXPECT_LT(p[0][1], p[1][1]) << codec << ": more bits, higher MS-SSIM";
    EXPECT_GT(p[0][2], p[1][2]) << codec << ": more bits, smaller butteraugli distance";
  }

  const std::string summary = read_text(out / "summary.md");
  EXPECT_NE(summary.find("## Mean over 1 image(s)"), std::string::npos);
  EXPECT_NE(summary.find("| codec | 0.5 bpp | 2 bpp | BD-PSNR (dB) | BD-rate (%) |"), std::string::npos);
  EXPECT_NE(summary.find("| BD-rate vs cdf97 (%) | MS-SSIM BD-rate (%) |"), std::string::npos);
  // The perceptual table: SSIM / MS-SSIM / butteraugli of OpenJPEG at 0.5 bpp.
  const auto& oj = perceptual_by_codec["openjpeg"][0];
  EXPECT_NE(
      summary.find("| openjpeg | " + fixed(oj[0], 4) + " / " + fixed(oj[1], 4) + " / " + fixed(oj[2], 3)),
      std::string::npos)
      << summary;
  for (const char* codec : {"| cdf97 |", "| cdf53 |", "| openjpeg | ", "| jxl |"})
    EXPECT_NE(summary.find(codec), std::string::npos) << codec;
  EXPECT_NE(summary.find("| openjpeg | " + fixed(psnr_by_codec["openjpeg"][0], 2)), std::string::npos);
  for (const std::string plot : {"plots/crop.svg", "plots/crop-ms-ssim.svg", "plots/crop-vs-openjpeg.svg"}) {
    EXPECT_NE(summary.find("![crop: " + plot + "](" + plot + ")"), std::string::npos) << plot;
    EXPECT_NE(read_text(out / plot).find("<svg"), std::string::npos) << plot;
  }
  EXPECT_FALSE(fs::exists(out / "plots" / "stale.svg"));
  // The relative plot's data: OpenJPEG against itself is 0 dB at its own points.
  const std::string data = read_text(out / "plots" / "crop.dat");
  const auto block = data.find("# openjpeg\n");
  ASSERT_NE(block, std::string::npos);
  std::istringstream first_point(data.substr(block + 11));
  double bpp = 0, psnr = 0, delta = 1;
  first_point >> bpp >> psnr >> delta;
  EXPECT_NEAR(psnr, psnr_by_codec["openjpeg"][0], 1e-6);
  EXPECT_EQ(delta, 0.0);
  double ms_ssim_db = 0;
  first_point >> ms_ssim_db;
  EXPECT_NEAR(ms_ssim_db, -10 * std::log10(1 - perceptual_by_codec["openjpeg"][0][1]), 1e-5);
}

// butteraugli (installed by scripts/install-deps.sh) finds no difference in a lossless file
// and a clear one at a low rate.
TEST_F(BenchCli, ButteraugliDistanceIsZeroWhenLosslessAndLargeAtALowRate) {
  ASSERT_TRUE(find_tool("butteraugli", environment_path()))
      << "butteraugli not in PATH (scripts/install-deps.sh)";
  const fs::path out = dir_ / "rd";
  const CliRun r = run_cli({"bench", "rd", "--images", image_.string(), "--transforms", "cdf53", "--bpp",
                            "0.5,24", "--anchors", "none", "--out", out.string()},
                           dir_ / "log.txt", environment_path());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = read_csv(out / "results.csv");
  ASSERT_NO_FATAL_FAILURE(check_results_columns(rows));
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_EQ(rows[2][kMaxError], "0") << "24 bpp must be coded lossless";
  EXPECT_EQ(rows[2][kSsim], "1");
  EXPECT_EQ(rows[2][kMsSsim], "1");
  EXPECT_LT(std::stod(rows[2][kButteraugli]), 0.01);
  EXPECT_GT(std::stod(rows[1][kButteraugli]), 1.0) << "0.5 bpp on a 96x64 photograph is visibly distorted";
}

// The modern anchors (AVIF, HEVC intra, WebP) reach the target rate by bisecting their quantiser
// and are compared with both references: OpenJPEG and pupwave's cdf97.
TEST_F(BenchCli, ModernAnchorsHitTheirRatesAndAreComparedWithCdf97) {
  const fs::path out = dir_ / "rd";
  const CliRun r =
      run_cli({"bench", "rd", "--images", image_.string(), "--transforms", "cdf97", "--bpp", "1,4",
               "--anchors", "openjpeg,avif,hevc,webp", "--jobs", "2", "--out", out.string()},
              dir_ / "log.txt", environment_path());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = read_csv(out / "results.csv");
  ASSERT_NO_FATAL_FAILURE(check_results_columns(rows));
  ASSERT_EQ(rows.size(), 1u + 5 * 2) << "header + (cdf97 + 4 anchors) x 2 rates";
  std::map<std::string, std::vector<double>> psnr_by_codec;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i][kStatus], "ok") << rows[i][4];
    const double target = std::stod(rows[i][6]), bpp = std::stod(rows[i][8]);
    // Integer quantisers step the size by a few percent at these sizes; a miss of a third would
    // mean the search ran the wrong way.
    EXPECT_NEAR(bpp, target, 0.35 * target)
        << rows[i][4] << " at " << target << " bpp: " << rows[i][kSetting];
    psnr_by_codec[rows[i][4]].push_back(std::stod(rows[i][9]));
  }
  for (const char* codec : {"avif", "hevc", "webp"}) {
    ASSERT_EQ(psnr_by_codec[codec].size(), 2u) << codec;
    EXPECT_GT(psnr_by_codec[codec][0], 20.0) << codec;
    EXPECT_LT(psnr_by_codec[codec][0], psnr_by_codec[codec][1]) << codec << ": more bits, higher PSNR";
  }
  const std::string summary = read_text(out / "summary.md");
  EXPECT_NE(summary.find("| BD-rate (%) | BD-rate vs cdf97 (%) |"), std::string::npos);
  // cdf97 against itself: 0.0 in its own column.
  const auto row = summary.find("| cdf97 | " + fixed(psnr_by_codec["cdf97"][0], 2));
  ASSERT_NE(row, std::string::npos) << summary;
  EXPECT_NE(summary.substr(row, summary.find('\n', row) - row).find("| 0.0 |"), std::string::npos);
}

TEST_F(BenchCli, MissingAnchorToolsAreSkippedWithANote) {
  const fs::path out = dir_ / "rd", empty = dir_ / "empty-path";
  fs::create_directories(empty);
  const CliRun r = run_cli({"bench", "rd", "--images", image_.string(), "--transforms", "cdf97", "--bpp", "1",
                            "--jobs", "1", "--out", out.string()},
                           dir_ / "log.txt", empty.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("anchor openjpeg skipped: opj_compress not found"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("anchor jxl skipped: cjxl not found"), std::string::npos) << r.output;
  for (const char* anchor : {"avif", "hevc", "webp"})
    EXPECT_NE(r.output.find(std::string("anchor ") + anchor + " skipped:"), std::string::npos) << anchor;
  const std::string summary = read_text(out / "summary.md");
  EXPECT_NE(summary.find("> Note: anchor openjpeg skipped"), std::string::npos);
  EXPECT_NE(summary.find("> Note: anchor jxl skipped"), std::string::npos);
  EXPECT_NE(summary.find("> Note: plots not drawn: gnuplot not found"), std::string::npos);
  EXPECT_NE(summary.find("> Note: butteraugli not found in PATH"), std::string::npos);
  const auto rows = read_csv(out / "results.csv");
  ASSERT_NO_FATAL_FAILURE(check_results_columns(rows));
  ASSERT_EQ(rows.size(), 2u);  // header + cdf97 at 1 bpp
  EXPECT_EQ(rows[1][kButteraugli], "");
  EXPECT_FALSE(rows[1][kMsSsim].empty()) << "SSIM and MS-SSIM need no tool";
  EXPECT_NE(summary.find("| cdf97 |"), std::string::npos);
  EXPECT_EQ(summary.find("| openjpeg |"), std::string::npos);
}

TEST_F(BenchCli, FailedJobsAreListedAndTheRunFails) {
  // /bin/false as "pupwave" makes every codec job fail; the anchors' results must survive.
  const fs::path out = dir_ / "rd";
  const CliRun r = run_cli({"bench", "rd", "--images", image_.string(), "--transforms", "cdf97", "--bpp", "1",
                            "--anchors", "openjpeg", "--cli", "/bin/false", "--out", out.string()},
                           dir_ / "log.txt", environment_path());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("1 of 2 rd jobs failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("pupwave: error: 1 job(s) failed"), std::string::npos) << r.output;
  const auto rows = read_csv(out / "results.csv");
  ASSERT_NO_FATAL_FAILURE(check_results_columns(rows));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1][kStatus].rfind("failed: false failed (exit 1)", 0), 0u) << rows[1][kStatus];
  EXPECT_EQ(rows[2][kStatus], "ok");
  const std::string summary = read_text(out / "summary.md");
  EXPECT_NE(summary.find("## Failed jobs"), std::string::npos);
  EXPECT_NE(summary.find("| cdf97 | n/a | n/a | n/a | n/a | n/a | n/a |"), std::string::npos) << summary;
  // The failed codec keeps its (empty) data block, so gnuplot's `index` still matches the key.
  EXPECT_NE(read_text(out / "plots" / "crop.dat").find("# cdf97\n? ? ? ?\n\n\n# openjpeg\n"),
            std::string::npos);
}

TEST_F(BenchCli, BadArgumentsAreRejectedBeforeAnyWork) {
  const fs::path out = dir_ / "rd";
  for (const auto& bad : std::vector<std::vector<std::string>>{
           {"--transforms", "no-such-transform"}, {"--bpp", "0"}, {"--bpp", "x"}, {"--anchors", "bogus"}}) {
    std::vector<std::string> args = {"bench", "rd", "--images", image_.string(), "--out", out.string()};
    args.insert(args.end(), bad.begin(), bad.end());
    const CliRun r = run_cli(args, dir_ / "log.txt", environment_path());
    EXPECT_EQ(r.exit_code, 1) << bad[1];
    EXPECT_NE(r.output.find("pupwave: error:"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out / "results.csv"));
    fs::remove(dir_ / "log.txt");
  }
}

// A folder of mixed photographs runs on those the harness takes; a 16-bit one named alone is refused.
TEST_F(BenchCli, ImagesItCannotTakeAreSkippedInAFolderAndRefusedByName) {
  const fs::path folder = dir_ / "images", out = dir_ / "rd";
  fs::create_directories(folder);
  fs::copy_file(image_, folder / "crop.png");
  const fs::path deep = fs::path(PUPWAVE_TESTIMAGES_DIR) / "courtyard16.png";
  fs::copy_file(deep, folder / "courtyard16.png");
  const CliRun r = run_cli({"bench", "rd", "--images", folder.string(), "--transforms", "cdf97", "--bpp", "1",
                            "--anchors", "none", "--jobs", "1", "--out", out.string()},
                           dir_ / "log.txt", environment_path());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("skipped " + (folder / "courtyard16.png").string()), std::string::npos) << r.output;
  const auto rows = read_csv(out / "results.csv");
  ASSERT_NO_FATAL_FAILURE(check_results_columns(rows));
  ASSERT_EQ(rows.size(), 2u);  // header + crop at 1 bpp
  EXPECT_EQ(rows[1][0], "crop");
  EXPECT_NE(read_text(out / "summary.md").find("> Note: skipped"), std::string::npos);

  const CliRun alone = run_cli({"bench", "rd", "--images", deep.string(), "--out", (dir_ / "alone").string()},
                               dir_ / "alone.txt", environment_path());
  EXPECT_EQ(alone.exit_code, 1) << alone.output;
  EXPECT_NE(alone.output.find("courtyard16.png: the harness takes 8-bit grey or RGB images"),
            std::string::npos)
      << alone.output;
}

TEST_F(BenchCli, CoarseRunWritesItsTable) {
  const fs::path out = dir_ / "coarse";
  const CliRun r = run_cli({"bench", "coarse", "--images", image_.string(), "--transforms", "cdf97,cdf53",
                            "--levels", "1..2", "--out", out.string()},
                           dir_ / "log.txt", environment_path());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = read_csv(out / "coarse.csv");
  ASSERT_EQ(rows.size(), 1u + 2 * 2);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"image", "transform", "levels", "psnr_luma_db", "status"}));
  const std::string summary = read_text(out / "summary.md");
  EXPECT_NE(summary.find("| transform | L=1 | L=2 |"), std::string::npos);
  EXPECT_NE(
      summary.find("| cdf97 | " + fixed(std::stod(rows[1][3]), 2) + " | " + fixed(std::stod(rows[2][3]), 2)),
      std::string::npos);
}

// A custom spec's own commas (inside its parentheses) do not split the --transforms list, in
// both experiments.
TEST_F(BenchCli, CustomSpecWithCommasIsOneTransform) {
  const std::string custom = "pups:cinpact(c=3,sigma=7.27,l=14)";
  const CliRun coarse = run_cli({"bench", "coarse", "--images", image_.string(), "--transforms",
                                 "cdf97," + custom, "--levels", "1", "--out", (dir_ / "coarse").string()},
                                dir_ / "log.txt", environment_path());
  ASSERT_EQ(coarse.exit_code, 0) << coarse.output;
  const auto rows = read_csv(dir_ / "coarse" / "coarse.csv");
  ASSERT_EQ(rows.size(), 1u + 2);  // header, cdf97, the custom bank
  EXPECT_NE(read_text(dir_ / "coarse" / "coarse.csv").find("cinpact"), std::string::npos);
  const CliRun rd = run_cli({"bench", "rd", "--images", image_.string(), "--transforms", "cdf97," + custom,
                             "--bpp", "1", "--anchors", "none", "--out", (dir_ / "rd").string()},
                            dir_ / "log2.txt", environment_path());
  ASSERT_EQ(rd.exit_code, 0) << rd.output;
  EXPECT_NE(read_text(dir_ / "rd" / "summary.md").find("pups:cinpact"), std::string::npos);
}

}  // namespace
}  // namespace pupwave::bench

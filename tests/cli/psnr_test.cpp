// `pupwave psnr` against hand-computed values and against OpenImageIO's own comparison.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebufalgo.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <regex>

#include "cli/run_cli.h"
#include "codec/image/image_metrics.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {
namespace fs = std::filesystem;

TEST(Metrics, HandComputedValues) {
  Image a(2, 2, 1, SampleType::u8), b(2, 2, 1, SampleType::u8);
  a.samples = {10, 20, 30, 40};
  b.samples = {12, 20, 27, 40};  // errors 2, 0, -3, 0: MSE = 13/4
  const ImageError e = compare_images(a, b);
  EXPECT_DOUBLE_EQ(e.overall.mse, 3.25);
  EXPECT_DOUBLE_EQ(e.overall.max_abs, 3.0);
  EXPECT_NEAR(e.overall.psnr, 10 * std::log10(255.0 * 255.0 / 3.25), 1e-12);
  EXPECT_NEAR(e.overall.psnr, 43.01197, 1e-5);
  EXPECT_FALSE(e.has_luma);
}

TEST(Metrics, LumaAndPerChannel) {
  Image a(1, 1, 3, SampleType::u16), b(1, 1, 3, SampleType::u16);
  a.samples = {100, 200, 300};
  b.samples = {110, 200, 290};  // R +10, B -10: luma diff = 0.299*10 - 0.114*10 = 1.85
  const ImageError e = compare_images(a, b);
  EXPECT_DOUBLE_EQ(e.peak, 65535.0);
  EXPECT_DOUBLE_EQ(e.channels[0].mse, 100.0);
  EXPECT_DOUBLE_EQ(e.channels[1].mse, 0.0);
  EXPECT_TRUE(std::isinf(e.channels[1].psnr));
  EXPECT_NEAR(e.overall.mse, 200.0 / 3.0, 1e-12);
  ASSERT_TRUE(e.has_luma);
  EXPECT_NEAR(e.luma.mse, 1.85 * 1.85, 1e-9);
}

TEST(Metrics, FloatPeakIsReferenceRange) {
  Image a(3, 1, 1, SampleType::f32), b(3, 1, 1, SampleType::f32);
  a.samples = {-1.0f, 0.0f, 3.0f};
  b.samples = {-1.0f, 0.5f, 3.0f};
  const ImageError e = compare_images(a, b);
  EXPECT_DOUBLE_EQ(e.peak, 4.0);
  EXPECT_NEAR(e.overall.psnr, 10 * std::log10(16.0 / (0.25 / 3.0)), 1e-9);
}

TEST(Metrics, ShapeMismatchIsRejected) {
  EXPECT_THROW(compare_images(Image(2, 2, 1, SampleType::u8), Image(2, 3, 1, SampleType::u8)),
               std::invalid_argument);
}

// Reads the PSNR of a row ("all", "luma", "R", ...) from `pupwave psnr` output.
double psnr_row(const std::string& output, const std::string& row) {
  std::smatch m;
  const std::regex re("(^|\\n)" + row + " +[0-9.e+-]+ +([0-9.]+|inf) ");
  if (!std::regex_search(output, m, re)) return std::nan("");
  return m[2] == "inf" ? INFINITY : std::stod(m[2]);
}

// Distorts a real photograph (JPEG at low quality) and compares with OpenImageIO's PSNR.
TEST(PsnrCli, AgreesWithOpenImageIoOnTestImages) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_psnr_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* name : {"camera.png", "astronaut.png", "coffee.png", "chelsea.png"}) {
    const fs::path ref = fs::path(PUPWAVE_TESTIMAGES_DIR) / name;
    const fs::path distorted = dir / (std::string(name) + ".jpg");
    OIIO::ImageBuf src(ref.string());
    src.specmod().attribute("Compression", "jpeg:30");
    ASSERT_TRUE(src.write(distorted.string())) << src.geterror();
    const OIIO::ImageBuf dst(distorted.string());
    const auto cmp = OIIO::ImageBufAlgo::compare(src, dst, 0.0f, 0.0f);
    const auto r = test::run_cli({"psnr", ref.string(), distorted.string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const double ours = psnr_row(r.output, "all");
    EXPECT_NEAR(ours, cmp.PSNR, 0.01) << name << "\n" << r.output;
    EXPECT_GT(ours, 20.0);
    EXPECT_LT(ours, 45.0);
  }
  fs::remove_all(dir);
}

TEST(PsnrCli, IdenticalImagesGiveInfinity) {
  const std::string ref = std::string(PUPWAVE_TESTIMAGES_DIR) + "/astronaut.png";
  const auto r = test::run_cli({"psnr", ref, ref});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::isinf(psnr_row(r.output, "all"))) << r.output;
  EXPECT_TRUE(std::isinf(psnr_row(r.output, "luma"))) << r.output;
}

// NaN and infinity (as --keep-nonfinite keeps them): given back, the finite samples get their
// PSNR; lost, the error is infinite (-inf dB, never the "inf" of identical images).
TEST(PsnrCli, NonFiniteSamplesAreComparedByIdentity) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_psnr_nf_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Image ref = cli::read_image(fs::path(PUPWAVE_TESTIMAGES_DIR) / "forest_hdr.exr");
  ref.samples[100] = NAN;
  ref.samples[ref.plane_size() + 200] = INFINITY;
  Image near = ref;
  for (std::size_t i = 1000; i < 2000; ++i) near.samples[i] *= 1.01f;
  Image lost = ref;
  lost.samples[ref.plane_size() + 200] = 1.0f;
  cli::write_image(ref, dir / "ref.exr");
  cli::write_image(near, dir / "near.exr");
  cli::write_image(lost, dir / "lost.exr");
  const auto kept = test::run_cli({"psnr", (dir / "ref.exr").string(), (dir / "near.exr").string()});
  ASSERT_EQ(kept.exit_code, 0) << kept.output;
  const double psnr = psnr_row(kept.output, "all");
  EXPECT_TRUE(std::isfinite(psnr) && psnr > 40.0) << kept.output;
  const auto r = test::run_cli({"psnr", (dir / "ref.exr").string(), (dir / "lost.exr").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("\\nG +inf +-inf "))) << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("\\nR +[0-9.]+ +inf "))) << r.output;  // R identical
  fs::remove_all(dir);
}

TEST(PsnrCli, DifferentSizesAreAClearError) {
  const std::string dir = PUPWAVE_TESTIMAGES_DIR;
  const auto r = test::run_cli({"psnr", dir + "/astronaut.png", dir + "/coffee.png"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("differ"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace pupwave

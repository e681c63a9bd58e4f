// Float (HDR) images are coded in the log domain: on a real HDR photograph the default setting
// keeps every well-populated decade of luminance within 3 % median relative error and never
// turns a non-negative sample negative. Coded linearly, the dark decades would be lost, which is
// what these tests catch.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "codec/image/image_codec.h"
#include "codec/image/transfer.h"
#include "hdr/hdr_test_util.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {

// testimages/forest_hdr.exr: HDRI Haven "forest" from Debian's blender-data (testimages/README.md).
Image forest() { return cli::read_image(std::string(PUPWAVE_TESTIMAGES_DIR) + "/forest_hdr.exr"); }

double luminance(const Image& img, std::size_t i) {
  return 0.2126 * img.plane(0)[i] + 0.7152 * img.plane(1)[i] + 0.0722 * img.plane(2)[i];
}

// Median relative luminance error per decade (floor(log10 Y)) of decades holding >= 1 % of pixels.
std::map<int, double> median_error_per_decade(const Image& ref, const Image& dec) {
  std::map<int, std::vector<double>> errors;
  for (std::size_t i = 0; i < ref.plane_size(); ++i) {
    const double y = luminance(ref, i);
    if (y <= 0.0) continue;  // no relative error of black
    errors[int(std::floor(std::log10(y)))].push_back(std::abs(luminance(dec, i) - y) / y);
  }
  std::map<int, double> medians;
  for (auto& [decade, e] : errors) {
    if (double(e.size()) < 0.01 * double(ref.plane_size())) continue;
    std::nth_element(e.begin(), e.begin() + std::ptrdiff_t(e.size() / 2), e.end());
    medians[decade] = e[e.size() / 2];
  }
  return medians;
}

std::size_t sign_flips(const Image& ref, const Image& dec) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < ref.samples.size(); ++i) n += ref.samples[i] >= 0.0f && dec.samples[i] < 0.0f;
  return n;
}

TEST(HdrTransfer, TransferRoundTripsAndKeepsSign) {
  for (double x : {0.0, 1e-7, 6.1e-5, 0.5, 1.0, 943.0, 65504.0, -0.25, -3000.0}) {
    const double v = to_transfer(x, Transfer::log2);
    EXPECT_NEAR(from_transfer(v, Transfer::log2), x, 1e-12 + 1e-12 * std::abs(x)) << x;
    EXPECT_EQ(std::signbit(v), std::signbit(x)) << x;
  }
  // One stop up is one unit up, well above the offset.
  EXPECT_NEAR(to_transfer(2.0, Transfer::log2) - to_transfer(1.0, Transfer::log2), 1.0, 1e-4);
}

TEST(HdrTransfer, DefaultSettingKeepsEveryDecadeOfARealHdrImage) {
  const Image img = forest();
  ASSERT_EQ(img.type, SampleType::f16);
  const EncodeResult r = encode_image(img, EncodeOptions{});
  EXPECT_EQ(r.metric, "log-PSNR");
  EXPECT_GE(r.psnr, 40.0);
  const Image dec = decode_image(r.bytes);
  const auto medians = median_error_per_decade(img, dec);
  ASSERT_GE(medians.size(), 3u) << "the image spans several decades of luminance";
  for (const auto& [decade, median] : medians) EXPECT_LT(median, 0.03) << "decade 1e" << decade;
  EXPECT_EQ(sign_flips(img, dec), 0u);
  EXPECT_LT(r.bytes.size(), img.plane_size() * 3) << "under half the raw half-float size";
}

TEST(HdrTransfer, LinearCodingLosesTheDarkDecades) {
  // What main did: PSNR against the value range. Some populated decade is off by far more than 3 %.
  const Image img = forest();
  EncodeOptions o;
  o.transfer = Transfer::linear;
  const Image dec = decode_image(encode_image(img, o).bytes);
  double worst = 0.0;
  for (const auto& [decade, median] : median_error_per_decade(img, dec)) worst = std::max(worst, median);
  EXPECT_GT(worst, 0.03);
}

TEST(HdrTransfer, RateTargetIsStatedInLogPsnr) {
  const Image img = forest();
  for (double target : {30.0, 45.0}) {
    EncodeOptions o;
    o.target = target;
    const EncodeResult r = encode_image(img, o);
    const double measured = transfer_psnr(img, decode_image(r.bytes), Transfer::log2);
    EXPECT_GE(measured, target - 0.01) << target;
    EXPECT_NEAR(measured, r.psnr, 0.05) << target;
  }
}

TEST(HdrTransfer, NegativeInputsStayCodable) {
  // A float image with negative values (no clamp at 0) round-trips with its signs.
  Image img(64, 64, 1, SampleType::f32);
  for (std::size_t i = 0; i < img.samples.size(); ++i)
    img.samples[i] = float(std::sin(double(i) * 0.01) * 100.0);
  EncodeOptions o;
  o.target = 50.0;
  const Image dec = decode_image(encode_image(img, o).bytes);
  std::size_t flips = 0;
  for (std::size_t i = 0; i < img.samples.size(); ++i)
    flips += std::abs(img.samples[i]) > 1.0f && std::signbit(img.samples[i]) != std::signbit(dec.samples[i]);
  EXPECT_EQ(flips, 0u);
}

TEST(HdrTransfer, CliNamesTheMetric) {
  const auto dir = test::hdr_temp_dir();
  const std::string in = test::testimage("forest_hdr.exr"), pw = (dir / "forest.pw").string(),
                    out = (dir / "forest_out.exr").string();
  const auto c = test::run_cli({"compress", in, pw});
  ASSERT_EQ(c.exit_code, 0) << c.output;
  EXPECT_NE(c.output.find("log-PSNR 4"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("(PSNR "), std::string::npos) << c.output;
  EXPECT_NE(test::run_cli({"info", pw}).output.find("transfer    log2"), std::string::npos);
  ASSERT_EQ(test::run_cli({"decompress", pw, out}).exit_code, 0);
  const auto p = test::run_cli({"psnr", in, out});
  ASSERT_EQ(p.exit_code, 0) << p.output;
  EXPECT_NE(p.output.find("log-PSNR"), std::string::npos) << p.output;
}

}  // namespace
}  // namespace pupwave

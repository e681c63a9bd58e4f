// The coarse-band reconstruction: exact where the wavelet's vanishing moments say it must be,
// lossy on a real photograph, and worse with every level.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "codec/image/image_metrics.h"
#include "tools/bench/coarse.h"
#include "tools/image_io.h"

namespace pupwave::bench {
namespace {

TEST(Coarse, CdfFiveThreeKeepsAPlaneExactly) {
  // 5/3 predicts odd samples by linear interpolation, so a linear ramp has zero details; with
  // odd sizes 2^k + 1 every level splits odd lines and no boundary sample is a detail, so the
  // coarse band alone rebuilds the plane exactly.
  Image plane(33, 33, 1, SampleType::u8);
  for (std::size_t y = 0; y < 33; ++y)
    for (std::size_t x = 0; x < 33; ++x) plane.at(0, x, y) = static_cast<float>(3 * x + 4 * y);
  for (int levels = 1; levels <= 3; ++levels) {
    const Image rebuilt = coarse_reconstruction(plane, "cdf53", levels);
    EXPECT_EQ(compare_images(plane, rebuilt).overall.max_abs, 0.0) << levels << " levels";
  }
}

TEST(Coarse, ConstantImageSurvivesEveryLevel) {
  Image flat(40, 27, 3, SampleType::u8);
  for (float& v : flat.samples) v = 117.0f;
  for (const char* spec : {"cdf97", "cdf53"})
    EXPECT_EQ(compare_images(flat, coarse_reconstruction(flat, spec, 4)).overall.max_abs, 0.0) << spec;
}

TEST(Coarse, PhotographLosesDetailWithEveryLevel) {
  const Image full = cli::read_image(std::filesystem::path(PUPWAVE_TESTIMAGES_DIR) / "camera.png");
  Image crop(128, 96, 1, full.type);
  for (std::size_t y = 0; y < crop.height; ++y)
    for (std::size_t x = 0; x < crop.width; ++x) crop.at(0, x, y) = full.at(0, x + 180, y + 100);
  double previous = INFINITY;
  for (int levels = 1; levels <= 4; ++levels) {
    const Image rebuilt = coarse_reconstruction(crop, "cdf97", levels);
    const double psnr = compare_images(crop, rebuilt).overall.psnr;
    EXPECT_LT(psnr, previous) << levels << " levels";
    EXPECT_GT(psnr, 10.0);
    for (float v : rebuilt.samples) ASSERT_EQ(v, std::round(v));  // 8-bit like a decoded file
    previous = psnr;
  }
}

TEST(Coarse, LevelsParse) {
  EXPECT_EQ(parse_levels("1..5"), (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(parse_levels("4,2,2"), (std::vector<int>{2, 4}));
  for (const char* bad : {"", "0..3", "a", "3..1", "1,17"})
    EXPECT_THROW(parse_levels(bad), std::invalid_argument) << bad;
}

TEST(Coarse, UnknownTransformIsRejected) {
  Image img(8, 8, 1, SampleType::u8);
  EXPECT_THROW(coarse_reconstruction(img, "no-such-spec", 1), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::bench

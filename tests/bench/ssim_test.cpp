// SSIM and MS-SSIM of the harness: exactly 1 for an image against itself, falling as noise
// grows on a real photograph, and equal to a direct (unseparated, unoptimised) evaluation of
// the published definitions on a real photograph and a distorted copy.
#include "tools/bench/ssim.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <vector>

#include "tools/image_io.h"

namespace pupwave::bench {
namespace {

namespace fs = std::filesystem;

Image test_image(const char* name) { return cli::read_image(fs::path(PUPWAVE_TESTIMAGES_DIR) / name); }

Image crop(const Image& full, std::size_t x0, std::size_t y0, std::size_t w, std::size_t h) {
  Image c(w, h, full.channels, full.type);
  for (std::size_t ch = 0; ch < full.channels; ++ch)
    for (std::size_t y = 0; y < h; ++y)
      for (std::size_t x = 0; x < w; ++x) c.at(ch, x, y) = full.at(ch, x0 + x, y0 + y);
  return c;
}

// The image plus rounded Gaussian noise of standard deviation `sigma`, clamped to 0..255 as a
// decoded 8-bit file would be.
Image with_noise(const Image& img, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Image out = img;
  for (float& v : out.samples) v = static_cast<float>(std::clamp(std::round(v + noise(rng)), 0.0, 255.0));
  return out;
}

// ---- A direct evaluation of the definitions, written independently of tools/bench/ssim.cpp:
// the 2-D Gaussian window applied at each position as a whole, luma per pixel.

using Grid = std::vector<std::vector<double>>;  // [y][x]

Grid luma_grid(const Image& img) {
  Grid g(img.height, std::vector<double>(img.width));
  for (std::size_t y = 0; y < img.height; ++y)
    for (std::size_t x = 0; x < img.width; ++x)
      g[y][x] = img.channels == 1
                    ? img.at(0, x, y)
                    : 0.299 * img.at(0, x, y) + 0.587 * img.at(1, x, y) + 0.114 * img.at(2, x, y);
  return g;
}

struct Direct {
  double ssim = 0.0, cs = 0.0;  // means over the valid window positions
};

Direct direct_ssim(const Grid& a, const Grid& b) {
  double w[11][11], total = 0.0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) total += w[i][j] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / 4.5);
  const double c1 = 2.55 * 2.55, c2 = 7.65 * 7.65;
  const std::size_t h = a.size(), wd = a[0].size();
  double sum_ssim = 0.0, sum_cs = 0.0;
  for (std::size_t y = 0; y + 11 <= h; ++y)
    for (std::size_t x = 0; x + 11 <= wd; ++x) {
      double ma = 0, mb = 0, aa = 0, bb = 0, ab = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          const double k = w[i][j] / total, p = a[y + i][x + j], q = b[y + i][x + j];
          ma += k * p, mb += k * q, aa += k * p * p, bb += k * q * q, ab += k * p * q;
        }
      const double va = aa - ma * ma, vb = bb - mb * mb, cov = ab - ma * mb;
      const double cs = (2 * cov + c2) / (va + vb + c2);
      sum_ssim += (2 * ma * mb + c1) / (ma * ma + mb * mb + c1) * cs, sum_cs += cs;
    }
  const double n = static_cast<double>((h - 10) * (wd - 10));
  return {sum_ssim / n, sum_cs / n};
}

Grid halve(const Grid& g) {
  Grid d(g.size() / 2, std::vector<double>(g[0].size() / 2));
  for (std::size_t y = 0; y < d.size(); ++y)
    for (std::size_t x = 0; x < d[0].size(); ++x)
      d[y][x] = (g[2 * y][2 * x] + g[2 * y][2 * x + 1] + g[2 * y + 1][2 * x] + g[2 * y + 1][2 * x + 1]) / 4;
  return d;
}

TEST(Ssim, AnImageAgainstItselfIsExactlyOne) {
  for (const char* name : {"astronaut.png", "camera.png"}) {
    const Image img = test_image(name);
    EXPECT_EQ(ssim(img, img), 1.0) << name;
    EXPECT_EQ(ms_ssim(img, img), 1.0) << name;
  }
}

TEST(Ssim, FallsAsNoiseGrowsOnAPhotograph) {
  const Image img = test_image("camera.png");
  double last_ssim = 1.0, last_ms = 1.0;
  for (double sigma : {1.0, 3.0, 8.0, 20.0}) {
    const Image noisy = with_noise(img, sigma, 7);
    const double s = ssim(img, noisy), m = ms_ssim(img, noisy);
    EXPECT_LT(s, last_ssim) << "sigma " << sigma;
    EXPECT_LT(m, last_ms) << "sigma " << sigma;
    EXPECT_GT(s, 0.0);
    last_ssim = s, last_ms = m;
  }
  EXPECT_LT(last_ssim, 0.5) << "noise of sigma 20 must hurt SSIM a lot";
}

TEST(Ssim, MatchesADirectEvaluationOnAColourPhotograph) {
  const Image ref = crop(test_image("astronaut.png"), 180, 120, 120, 90);
  const Image dist = with_noise(ref, 6.0, 11);
  const double direct = direct_ssim(luma_grid(ref), luma_grid(dist)).ssim;
  EXPECT_NEAR(ssim(ref, dist), direct, 1e-6);
  EXPECT_LT(direct, 0.95) << "the distortion must be visible to SSIM for the comparison to mean much";
}

// A 120x90 image fits four scales (120x90, 60x45, 30x22, 15x11; 7x5 holds no window), whose
// weights are renormalised to sum 1.
TEST(Ssim, MultiScaleOnASmallImageUsesTheScalesThatFit) {
  const Image ref = crop(test_image("astronaut.png"), 180, 120, 120, 90);
  const Image dist = with_noise(ref, 6.0, 11);
  const std::array<double, 4> weights = {0.0448, 0.2856, 0.3001, 0.2363};
  const double weight_sum = weights[0] + weights[1] + weights[2] + weights[3];
  Grid a = luma_grid(ref), b = luma_grid(dist);
  double expected = 1.0;
  for (std::size_t j = 0; j < weights.size(); ++j) {
    if (j > 0) a = halve(a), b = halve(b);
    const Direct d = direct_ssim(a, b);
    expected *= std::pow(j + 1 == weights.size() ? d.ssim : d.cs, weights[j] / weight_sum);
  }
  EXPECT_NEAR(ms_ssim(ref, dist), expected, 1e-6);
}

TEST(Ssim, OneWindowIsTheSmallestMeasuredImage) {
  const Image img = test_image("camera.png");
  const Image one = crop(img, 100, 100, 11, 11), noisy = with_noise(one, 5.0, 3);
  EXPECT_NEAR(ms_ssim(one, noisy), ssim(one, noisy), 1e-12) << "one scale, weight renormalised to 1";
  const Image small = crop(img, 100, 100, 10, 40);
  EXPECT_TRUE(std::isnan(ssim(small, small)));
  EXPECT_TRUE(std::isnan(ms_ssim(small, small)));
}

TEST(Ssim, ShapeMismatchIsRejected) {
  const Image img = test_image("camera.png");
  EXPECT_THROW(ssim(img, crop(img, 0, 0, 100, 100)), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::bench

#include "tools/bench/ssim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace pupwave::bench {
namespace {

constexpr int kWindow = 11;
constexpr double kSigma = 1.5;
constexpr double kC1 = (0.01 * 255) * (0.01 * 255);
constexpr double kC2 = (0.03 * 255) * (0.03 * 255);
constexpr std::array<double, 5> kScaleWeights = {0.0448, 0.2856, 0.3001, 0.2363, 0.1333};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One channel of doubles, row-major.
struct Plane {
  std::size_t width = 0, height = 0;
  std::vector<double> v;
  double at(std::size_t x, std::size_t y) const { return v[y * width + x]; }
};

// Rec. 601 luma, the same expression as compare_images' luma PSNR.
Plane luma(const Image& img) {
  Plane p{img.width, img.height, std::vector<double>(img.plane_size())};
  for (std::size_t i = 0; i < p.v.size(); ++i)
    p.v[i] = img.channels == 1 ? img.plane(0)[i]
                               : 0.299 * img.plane(0)[i] + 0.587 * img.plane(1)[i] + 0.114 * img.plane(2)[i];
  return p;
}

void check_shapes(const Image& reference, const Image& test) {
  if (reference.width != test.width || reference.height != test.height || reference.channels != test.channels)
    throw std::invalid_argument("ssim: the images differ in size or channel count");
  if (reference.channels != 1 && reference.channels != 3)
    throw std::invalid_argument("ssim: only grey and RGB images are measured");
}

std::array<double, kWindow> gaussian_window() {
  std::array<double, kWindow> g{};
  double sum = 0.0;
  for (int i = 0; i < kWindow; ++i) {
    const double d = i - kWindow / 2;
    g[i] = std::exp(-d * d / (2.0 * kSigma * kSigma));
    sum += g[i];
  }
  for (double& w : g) w /= sum;
  return g;
}

// Gaussian-weighted mean over every window wholly inside the plane ("valid" filtering); the
// 2-D window is the outer product of the 1-D one, so rows and columns are filtered in turn.
Plane filter_valid(const Plane& p) {
  static const auto g = gaussian_window();
  const std::size_t ow = p.width - kWindow + 1, oh = p.height - kWindow + 1;
  Plane rows{ow, p.height, std::vector<double>(ow * p.height)};
  for (std::size_t y = 0; y < p.height; ++y)
    for (std::size_t x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int k = 0; k < kWindow; ++k) s += g[k] * p.at(x + k, y);
      rows.v[y * ow + x] = s;
    }
  Plane out{ow, oh, std::vector<double>(ow * oh)};
  for (std::size_t y = 0; y < oh; ++y)
    for (std::size_t x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int k = 0; k < kWindow; ++k) s += g[k] * rows.at(x, y + k);
      out.v[y * ow + x] = s;
    }
  return out;
}

Plane product(const Plane& a, const Plane& b) {
  Plane p{a.width, a.height, std::vector<double>(a.v.size())};
  for (std::size_t i = 0; i < p.v.size(); ++i) p.v[i] = a.v[i] * b.v[i];
  return p;
}

// Means over the valid window positions of the SSIM map and of its contrast-structure term.
struct SsimMeans {
  double ssim = kNaN, cs = kNaN;
};

SsimMeans ssim_means(const Plane& x, const Plane& y) {
  if (x.width < kWindow || x.height < kWindow) return {};
  const Plane mx = filter_valid(x), my = filter_valid(y);
  const Plane xx = filter_valid(product(x, x)), yy = filter_valid(product(y, y)),
              xy = filter_valid(product(x, y));
  double sum_ssim = 0.0, sum_cs = 0.0;
  for (std::size_t i = 0; i < mx.v.size(); ++i) {
    const double vx = xx.v[i] - mx.v[i] * mx.v[i], vy = yy.v[i] - my.v[i] * my.v[i];
    const double cov = xy.v[i] - mx.v[i] * my.v[i];
    const double cs = (2.0 * cov + kC2) / (vx + vy + kC2);
    const double l = (2.0 * mx.v[i] * my.v[i] + kC1) / (mx.v[i] * mx.v[i] + my.v[i] * my.v[i] + kC1);
    sum_ssim += l * cs, sum_cs += cs;
  }
  const double n = static_cast<double>(mx.v.size());
  return {sum_ssim / n, sum_cs / n};
}

// 2x2 box average; an odd last row or column is dropped.
Plane downsample(const Plane& p) {
  Plane d{p.width / 2, p.height / 2, {}};
  d.v.resize(d.width * d.height);
  for (std::size_t y = 0; y < d.height; ++y)
    for (std::size_t x = 0; x < d.width; ++x)
      d.v[y * d.width + x] = 0.25 * (p.at(2 * x, 2 * y) + p.at(2 * x + 1, 2 * y) + p.at(2 * x, 2 * y + 1) +
                                     p.at(2 * x + 1, 2 * y + 1));
  return d;
}

}  // namespace

double ssim(const Image& reference, const Image& test) {
  check_shapes(reference, test);
  return ssim_means(luma(reference), luma(test)).ssim;
}

double ms_ssim(const Image& reference, const Image& test) {
  check_shapes(reference, test);
  Plane x = luma(reference), y = luma(test);
  std::vector<SsimMeans> scales;
  for (std::size_t j = 0; j < kScaleWeights.size(); ++j) {
    if (j > 0) x = downsample(x), y = downsample(y);
    if (std::min(x.width, x.height) < kWindow) break;
    scales.push_back(ssim_means(x, y));
  }
  if (scales.empty()) return kNaN;
  // The published weights (summing to 1.0001) are used as they are when all five scales fit.
  double weight_sum = 1.0;
  if (scales.size() < kScaleWeights.size())
    weight_sum = std::accumulate(kScaleWeights.begin(), kScaleWeights.begin() + scales.size(), 0.0);
  double result = 1.0;
  for (std::size_t j = 0; j < scales.size(); ++j) {
    const bool coarsest = j + 1 == scales.size();
    const double term = std::max(0.0, coarsest ? scales[j].ssim : scales[j].cs);
    result *= std::pow(term, kScaleWeights[j] / weight_sum);
  }
  return result;
}

}  // namespace pupwave::bench

// BD-PSNR and BD-rate against examples whose answers were worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tools/bench/bd_metrics.h"

namespace pupwave::bench {
namespace {

const double kRates[] = {0.125, 0.25, 0.5, 1.0, 2.0};

// A curve PSNR = f(log10 bpp) sampled at kRates.
template <class F>
std::vector<RdPoint> curve_of_rate(F psnr_of_log_rate) {
  std::vector<RdPoint> c;
  for (double r : kRates) c.push_back({r, psnr_of_log_rate(std::log10(r))});
  return c;
}

TEST(BdMetrics, ParallelLinesDifferByTheirOffset) {
  // B = A + 1 dB everywhere: BD-PSNR is 1 dB. At equal PSNR B needs log10 rate 0.1 lower
  // (slope 10 dB per decade), so BD-rate = 10^-0.1 - 1 = -20.567%.
  const auto a = curve_of_rate([](double x) { return 30.0 + 10.0 * x; });
  const auto b = curve_of_rate([](double x) { return 31.0 + 10.0 * x; });
  EXPECT_NEAR(bd_psnr(a, b), 1.0, 1e-9);
  EXPECT_NEAR(bd_rate(a, b), -20.5672, 1e-3);
  EXPECT_NEAR(bd_psnr(b, a), -1.0, 1e-9);
  EXPECT_NEAR(bd_rate(b, a), 25.8925, 1e-3);  // 10^0.1 - 1
}

TEST(BdMetrics, QuadraticGapIsAveragedOverTheRateRange) {
  // B = A + 3 x^2 with x = log10(bpp) in [a, b] = [log10 0.125, log10 2]. The cubic fit is
  // exact, and the mean of 3 x^2 over [a, b] is (b^3 - a^3) / (b - a) = a^2 + ab + b^2.
  const auto a_curve = curve_of_rate([](double x) { return 30.0 + 10.0 * x; });
  const auto b_curve = curve_of_rate([](double x) { return 30.0 + 10.0 * x + 3.0 * x * x; });
  const double a = std::log10(0.125), b = std::log10(2.0);
  EXPECT_NEAR(bd_psnr(a_curve, b_curve), a * a + a * b + b * b, 1e-9);  // 0.634334 dB
  EXPECT_NEAR(bd_psnr(a_curve, b_curve), 0.634334, 1e-6);
}

TEST(BdMetrics, RateGapUsesLogRateAsAFunctionOfPsnr) {
  // With u = (PSNR - 30) / 10 at PSNR 30, 37.5, 45, 52.5, 60: A has log10 bpp = u, B has
  // u - 0.1 u^2. The mean gap over u in [0, 3] is -0.1 * 9 / 3 = -0.3 decades, so
  // BD-rate = 10^-0.3 - 1 = -49.881%.
  std::vector<RdPoint> a, b;
  for (double u : {0.0, 0.75, 1.5, 2.25, 3.0}) {
    a.push_back({std::pow(10.0, u), 30.0 + 10.0 * u});
    b.push_back({std::pow(10.0, u - 0.1 * u * u), 30.0 + 10.0 * u});
  }
  EXPECT_NEAR(bd_rate(a, b), -49.8813, 1e-3);
}

TEST(BdMetrics, OnlyTheOverlapCounts) {
  // B covers only the upper half of A's rates; the gap is measured there (constant 2 dB).
  const auto a = curve_of_rate([](double x) { return 30.0 + 10.0 * x; });
  std::vector<RdPoint> b = {{0.5, 32.0 + 10.0 * std::log10(0.5)}, {2.0, 32.0 + 10.0 * std::log10(2.0)}};
  EXPECT_NEAR(bd_psnr(a, b), 2.0, 1e-9);
  EXPECT_NEAR(bd_psnr(a, a), 0.0, 1e-12);
  EXPECT_NEAR(bd_rate(a, a), 0.0, 1e-9);
}

TEST(BdMetrics, UnusableCurvesGiveNaN) {
  const auto a = curve_of_rate([](double x) { return 30.0 + 10.0 * x; });
  EXPECT_TRUE(std::isnan(bd_psnr(a, {{1.0, 40.0}})));                // one point
  EXPECT_TRUE(std::isnan(bd_rate(a, {})));                           // no points
  EXPECT_TRUE(std::isnan(bd_psnr(a, {{8.0, 50.0}, {16.0, 53.0}})));  // rates do not overlap
  EXPECT_TRUE(std::isnan(bd_rate(a, {{1.0, 60.0}, {2.0, 70.0}})));   // PSNRs do not overlap
  const double inf = std::numeric_limits<double>::infinity();
  // An infinite PSNR (lossless point) is ignored, leaving the two finite points.
  std::vector<RdPoint> b = {
      {0.125, 21.0 + 10.0 * std::log10(0.125)}, {2.0, 21.0 + 10.0 * std::log10(2.0)}, {8.0, inf}};
  EXPECT_NEAR(bd_psnr(a, b), -9.0, 1e-9);
}

}  // namespace
}  // namespace pupwave::bench

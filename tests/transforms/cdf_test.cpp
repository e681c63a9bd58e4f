// CDF 9/7 and 5/3: perfect reconstruction for every length, agreement with a direct
// JPEG 2000 reference on the symmetrically extended interleaved line, vanishing moments.
#include "transforms/cdf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace pupwave {
namespace {

std::vector<std::size_t> test_lengths() {
  std::vector<std::size_t> ns;
  for (std::size_t n = 1; n <= 300; ++n) ns.push_back(n);
  for (std::size_t n : {511, 512, 513, 1023}) ns.push_back(n);
  return ns;
}

std::vector<double> random_line(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-100.0, 155.0);
  std::vector<double> v(n);
  for (auto& x : v) x = u(rng);
  return v;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

// Direct JPEG 2000 lifting (T.800 Annex F) on the whole-sample symmetrically extended
// interleaved line, independent of the wire rules used by the library.
std::vector<double> reference_analysis(const std::vector<double>& x, bool is97) {
  const auto n = static_cast<std::ptrdiff_t>(x.size());
  const std::ptrdiff_t m = 8;  // margin; each lifting step consumes one sample per side
  std::vector<double> y(static_cast<std::size_t>(n + 2 * m));
  const std::ptrdiff_t p = 2 * (n - 1);
  for (std::ptrdiff_t i = -m; i < n + m; ++i) {
    std::ptrdiff_t j = ((i % p) + p) % p;
    y[static_cast<std::size_t>(i + m)] = x[static_cast<std::size_t>(j < n ? j : p - j)];
  }
  auto at = [&](std::ptrdiff_t i) -> double& { return y[static_cast<std::size_t>(i + m)]; };
  auto step = [&](int parity, double c, std::ptrdiff_t margin) {
    for (std::ptrdiff_t i = -margin; i < n + margin; ++i)
      if (((i % 2) + 2) % 2 == parity) at(i) += c * (at(i - 1) + at(i + 1));
  };
  if (is97) {
    using C = Cdf97Constants;
    step(1, C::alpha, 7), step(0, C::beta, 6), step(1, C::gamma, 5), step(0, C::delta, 4);
  } else {
    step(1, -0.5, 7), step(0, 0.25, 6);
  }
  std::vector<double> out(x.size());
  const std::size_t ne = (x.size() + 1) / 2;
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const double k = is97 ? (i % 2 ? Cdf97Constants::K : 1 / Cdf97Constants::K) : 1.0;
    out[static_cast<std::size_t>(i / 2) + (i % 2 ? ne : 0)] = k * at(i);
  }
  return out;
}

class CdfTest : public ::testing::TestWithParam<const char*> {
 protected:
  Transform1DPtr t() const { return GetParam() == std::string("cdf97") ? make_cdf97() : make_cdf53(); }
  bool is97() const { return GetParam() == std::string("cdf97"); }
};

TEST_P(CdfTest, PerfectReconstructionDouble) {
  const auto tr = t();
  for (std::size_t n : test_lengths()) {
    const auto x = random_line(n, static_cast<unsigned>(n));
    auto y = x;
    tr->analyze(std::span<double>(y));
    tr->synthesize(std::span<double>(y));
    EXPECT_LT(max_abs_diff(x, y), 1e-9 * 255.0) << "n=" << n;
  }
}

TEST_P(CdfTest, PerfectReconstructionFloat) {
  const auto tr = t();
  for (std::size_t n : test_lengths()) {
    const auto x = random_line(n, static_cast<unsigned>(n) + 1000);
    std::vector<float> y(x.begin(), x.end());
    tr->analyze(std::span<float>(y));
    tr->synthesize(std::span<float>(y));
    for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(y[i], x[i], 255.0 * 2e-6) << "n=" << n;
  }
}

TEST_P(CdfTest, MatchesJpeg2000Reference) {
  const auto tr = t();
  for (std::size_t n : test_lengths()) {
    if (n < 2) continue;
    const auto x = random_line(n, static_cast<unsigned>(n) + 7);
    auto y = x;
    tr->analyze(std::span<double>(y));
    EXPECT_LT(max_abs_diff(y, reference_analysis(x, is97())), 1e-10) << "n=" << n;
  }
}

TEST_P(CdfTest, SingleSampleIsIdentity) {
  std::vector<double> v{3.25};
  t()->analyze(std::span<double>(v));
  EXPECT_EQ(v[0], 3.25);
  t()->synthesize(std::span<double>(v));
  EXPECT_EQ(v[0], 3.25);
}

TEST_P(CdfTest, ConstantLineHasUnitDcGain) {
  for (std::size_t n = 2; n <= 40; ++n) {
    std::vector<double> v(n, 7.5);
    t()->analyze(std::span<double>(v));
    for (std::size_t i = 0; i < (n + 1) / 2; ++i) EXPECT_NEAR(v[i], 7.5, 1e-12) << n;
    for (std::size_t i = (n + 1) / 2; i < n; ++i) EXPECT_NEAR(v[i], 0.0, 1e-12) << n;
  }
}

INSTANTIATE_TEST_SUITE_P(Cdf, CdfTest, ::testing::Values("cdf97", "cdf53"));

// The 9/7 analysis high-pass has four vanishing moments: cubics give zero detail away from
// the edges (where symmetric extension breaks the polynomial).
TEST(Cdf97, HighPassAnnihilatesCubics) {
  const std::size_t n = 64, ne = 32;
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double s = (static_cast<double>(i) - 30.0) / 10.0;
    v[i] = 2.0 - 1.5 * s + 0.75 * s * s + 0.4 * s * s * s;
  }
  const double scale = *std::max_element(v.begin(), v.end());
  make_cdf97()->analyze(std::span<double>(v));
  for (std::size_t j = 4; j + 4 < n / 2; ++j) EXPECT_NEAR(v[ne + j], 0.0, 1e-9 * scale) << j;
  // Edge details are not zero: the test would catch a transform that zeroes everything.
  EXPECT_GT(std::abs(v[n - 1]), 1e-3);
}

TEST(Cdf53, IntegerIsBitExactForEveryLength) {
  const auto tr = make_cdf53();
  ASSERT_TRUE(tr->is_reversible());
  std::mt19937 rng(11);
  std::uniform_int_distribution<int32_t> u(-(1 << 20), 1 << 20);
  for (std::size_t n : test_lengths()) {
    std::vector<int32_t> x(n);
    for (auto& v : x) v = u(rng);
    auto y = x;
    tr->analyze(std::span<int32_t>(y));
    tr->synthesize(std::span<int32_t>(y));
    ASSERT_EQ(x, y) << "n=" << n;
  }
}

// Integer 5/3 equals the floor-rounded JPEG 2000 formula computed on the extended line.
TEST(Cdf53, IntegerMatchesJpeg2000Formula) {
  const std::vector<int32_t> x{10, -3, 7, 7, 100, -50, 0, 1, 2};
  auto y = x;
  make_cdf53()->analyze(std::span<int32_t>(y));
  auto fl = [](double v) { return static_cast<int32_t>(std::floor(v)); };
  // d[i] = x[2i+1] - floor((x[2i] + x[2i+2]) / 2); s[i] = x[2i] + floor((d[i-1] + d[i] + 2) / 4)
  std::vector<int32_t> d(4), s(5);
  for (int i = 0; i < 4; ++i) d[i] = x[2 * i + 1] - fl((x[2 * i] + x[2 * i + 2]) / 2.0);
  for (int i = 0; i < 5; ++i) {
    const int32_t dl = d[i == 0 ? 0 : i - 1], dr = d[i < 4 ? i : 3];  // d[-1] = d[0], d[4] = d[3]
    s[i] = x[2 * i] + fl((dl + dr + 2) / 4.0);
  }
  for (int i = 0; i < 5; ++i) EXPECT_EQ(y[i], s[i]);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(y[5 + i], d[i]);
}

TEST(Cdf97, HasNoIntegerForm) {
  std::vector<int32_t> v(8, 1);
  EXPECT_FALSE(make_cdf97()->is_reversible());
  EXPECT_THROW(make_cdf97()->analyze(std::span<int32_t>(v)), std::logic_error);
}

}  // namespace
}  // namespace pupwave

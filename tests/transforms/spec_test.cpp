// Spec strings: every listed spec builds a transform with that canonical spec, which
// reconstructs perfectly on 1-D lines and through the separable engine; unknown specs fail.
#include "transforms/spec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <random>
#include <vector>

#include "transforms/norms.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

TEST(Spec, ListsTheBaselines) {
  const auto specs = transform_specs();
  EXPECT_NE(std::find(specs.begin(), specs.end(), "cdf97"), specs.end());
  EXPECT_NE(std::find(specs.begin(), specs.end(), "cdf53"), specs.end());
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double err = 0;
  for (std::size_t i = 0; i < a.size(); ++i) err = std::max(err, std::abs(a[i] - b[i]));
  return err;
}

std::vector<double> random_samples(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 255);
  std::vector<double> x(n);
  for (auto& v : x) v = u(rng);
  return x;
}

class EverySpec : public ::testing::TestWithParam<std::string> {};

// Every length 1..300 and a few around powers of two, max error under 1e-9 x signal range.
TEST_P(EverySpec, LinesReconstructPerfectly) {
  const auto t = make_transform(GetParam());
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->spec(), GetParam());
  std::mt19937 rng(42);
  std::vector<std::size_t> lengths;
  for (std::size_t n = 1; n <= 300; ++n) lengths.push_back(n);
  for (std::size_t n : {511u, 512u, 513u, 1023u}) lengths.push_back(n);
  for (std::size_t n : lengths) {
    const auto x = random_samples(n, rng);
    auto y = x;
    t->analyze(std::span<double>(y));
    t->synthesize(std::span<double>(y));
    EXPECT_LT(max_abs_diff(x, y), 1e-9 * 255) << "n=" << n;
  }
}

// 2-D and 3-D arrays of odd, even and prime sizes (and 1), 1..8 levels. The bound is
// 1e-9 x signal range plus 1e-12 x the largest coefficient: double rounding is relative to
// the coefficients, and an ill-conditioned bank (pups:cinpact-c3, 1-D condition number up
// to 56) grows white noise to ~2e9 after 6 levels in 2-D, so its round-trip error (~2e-6,
// 1e-15 of the coefficients) is rounding, not a defect of the inverse. For the other
// transforms the coefficients stay near the signal range and the second term is ~1e-9.
TEST_P(EverySpec, ArraysReconstructPerfectly) {
  const auto t = make_transform(GetParam());
  std::mt19937 rng(7);
  for (const Extent& d : {Extent{37, 23, 1}, Extent{64, 1, 31}, Extent{1, 2, 97}, Extent{11, 6, 13},
                          Extent{128, 128, 1}, Extent{9, 16, 8}}) {
    for (int levels = 1; levels <= 8; ++levels) {
      const auto x = random_samples(d[0] * d[1] * d[2], rng);
      auto y = x;
      forward(*t, y.data(), d, levels);
      double largest = 0;
      for (double v : y) largest = std::max(largest, std::abs(v));
      inverse(*t, y.data(), d, levels);
      EXPECT_LT(max_abs_diff(x, y), 1e-9 * 255 + 1e-12 * largest)
          << d[0] << "x" << d[1] << "x" << d[2] << " L" << levels << " largest coefficient " << largest;
    }
  }
}

// synthesis_norms (product of 1-D norms) equals brute-force N-D impulse responses for every
// family, including IIR Kobbelt synthesis and non-orthogonal PUPs banks.
TEST_P(EverySpec, NormsEqualBruteForceImpulseResponses) {
  const auto t = make_transform(GetParam());
  for (const Extent& d : {Extent{21, 13, 1}, Extent{9, 7, 6}}) {
    const int levels = 2;
    const auto norms = synthesis_norms(*t, d, levels);
    const auto bands = subbands(d, levels);
    ASSERT_EQ(norms.size(), bands.size());
    for (std::size_t k = 0; k < bands.size(); ++k) {
      const Subband& b = bands[k];
      std::vector<double> v(d[0] * d[1] * d[2], 0.0);
      const std::size_t x = b.offset[0] + b.size[0] / 2, y = b.offset[1] + b.size[1] / 2,
                        z = b.offset[2] + b.size[2] / 2;
      v[(z * d[1] + y) * d[0] + x] = 1.0;
      inverse(*t, v.data(), d, levels);
      double sum = 0;
      for (double s : v) sum += s * s;
      EXPECT_NEAR(norms[k], std::sqrt(sum), 1e-10 * std::sqrt(sum)) << "band " << k;
      EXPECT_GT(norms[k], 0.0);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Spec, EverySpec, ::testing::ValuesIn(transform_specs()), [](const auto& spec_info) {
  std::string name = spec_info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

TEST(Spec, UnknownSpecListsValidOnes) {
  try {
    make_transform("haar");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cdf97"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("haar"), std::string::npos);
  }
  EXPECT_THROW(make_transform(""), std::invalid_argument);
  EXPECT_THROW(make_transform("CDF97 "), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave

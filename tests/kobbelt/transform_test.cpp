// The Kobbelt wavelet transforms as Transform1D: specs, perfect reconstruction, DC gain.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "transforms/kobbelt/kobbelt_transform.h"

namespace pupwave {
namespace {

// Multi-level analysis/synthesis by recursion on the coarse part (Mallat).
template <class T>
void analyze_levels(const Transform1D& t, std::vector<T>& x, int levels) {
  std::size_t n = x.size();
  for (int l = 0; l < levels && n >= 2; ++l, n = coarse_size(n)) {
    t.analyze(std::span<T>(x.data(), n));
  }
}

template <class T>
void synthesize_levels(const Transform1D& t, std::vector<T>& x, int levels) {
  std::vector<std::size_t> sizes;
  std::size_t n = x.size();
  for (int l = 0; l < levels && n >= 2; ++l, n = coarse_size(n)) sizes.push_back(n);
  for (auto it = sizes.rbegin(); it != sizes.rend(); ++it) {
    t.synthesize(std::span<T>(x.data(), *it));
  }
}

TEST(KobbeltTransform, SpecsRoundTrip) {
  const std::vector<std::string> specs = kobbelt_transform_specs();
  ASSERT_EQ(specs.size(), 8u);
  for (const std::string& spec : specs) {
    ASSERT_EQ(spec.rfind("kobbelt:", 0), 0u);
    EXPECT_EQ(make_kobbelt_transform_from_spec(spec.substr(8))->spec(), spec);
  }
}

TEST(KobbeltTransform, BadSpecNamesTheValidOnes) {
  for (const char* bad : {"", "k5", "-raw", "k2-rawx", "K2"}) {
    try {
      make_kobbelt_transform_from_spec(bad);
      FAIL() << bad;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("kspl-raw"), std::string::npos) << e.what();
    }
  }
}

std::vector<std::size_t> test_lengths() {
  std::vector<std::size_t> lengths;
  for (std::size_t n = 1; n <= 300; ++n) lengths.push_back(n);
  for (std::size_t n : {511u, 512u, 513u, 1023u}) lengths.push_back(n);
  return lengths;
}

// Every spec, every length 1..300 plus 511, 512, 513, 1023, every level count 1..8.
TEST(KobbeltTransform, PerfectReconstructionDouble) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uni(-100.0, 100.0);
  for (const std::string& spec : kobbelt_transform_specs()) {
    const Transform1DPtr t = make_kobbelt_transform_from_spec(spec.substr(8));
    for (std::size_t n : test_lengths()) {
      std::vector<double> original(n);
      for (auto& v : original) v = uni(rng);
      const auto [lo, hi] = std::minmax_element(original.begin(), original.end());
      const double range = std::max(*hi - *lo, 1.0);
      for (int levels = 1; levels <= 8; ++levels) {
        std::vector<double> x = original;
        analyze_levels(*t, x, levels);
        synthesize_levels(*t, x, levels);
        double err = 0;
        for (std::size_t i = 0; i < n; ++i) err = std::max(err, std::abs(x[i] - original[i]));
        ASSERT_LE(err, 1e-9 * range) << spec << " n=" << n << " levels=" << levels;
      }
    }
  }
}

TEST(KobbeltTransform, PerfectReconstructionFloat) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uni(0.0f, 255.0f);
  for (const std::string& spec : kobbelt_transform_specs()) {
    const Transform1DPtr t = make_kobbelt_transform_from_spec(spec.substr(8));
    for (std::size_t n : {1u, 2u, 3u, 7u, 64u, 255u, 256u, 513u}) {
      std::vector<float> original(n);
      for (auto& v : original) v = uni(rng);
      std::vector<float> x = original;
      analyze_levels(*t, x, 6);
      synthesize_levels(*t, x, 6);
      for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(x[i], original[i], 2e-3f) << spec << n;
    }
  }
}

// Details of a constant vanish, so the coarse band of a constant is that constant.
TEST(KobbeltTransform, ConstantGivesZeroDetailAndUnitDcGain) {
  for (const std::string& spec : kobbelt_transform_specs()) {
    const Transform1DPtr t = make_kobbelt_transform_from_spec(spec.substr(8));
    for (std::size_t n : {1u, 2u, 3u, 4u, 5u, 6u, 9u, 100u, 101u}) {
      std::vector<double> x(n, 3.25);
      t->analyze(std::span<double>(x));
      for (std::size_t i = 0; i < n; ++i) {
        ASSERT_NEAR(x[i], i < coarse_size(n) ? 3.25 : 0.0, 1e-12) << spec << " n=" << n;
      }
    }
  }
}

TEST(KobbeltTransform, LengthOneIsIdentity) {
  for (const std::string& spec : kobbelt_transform_specs()) {
    const Transform1DPtr t = make_kobbelt_transform_from_spec(spec.substr(8));
    std::vector<double> x{42.0};
    t->analyze(std::span<double>(x));
    EXPECT_EQ(x[0], 42.0);
    t->synthesize(std::span<double>(x));
    EXPECT_EQ(x[0], 42.0);
  }
}

}  // namespace
}  // namespace pupwave

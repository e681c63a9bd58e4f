// The PUPs filter bank as a Transform1D: perfect reconstruction for every length, interior
// equal to the designed filters, DC normalization, conditioning, specs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "transforms/pups/design.h"
#include "transforms/pups/pups_transform.h"

namespace pupwave::pups {
namespace {

std::vector<std::size_t> lengths() {
  std::vector<std::size_t> n;
  for (std::size_t i = 1; i <= 300; ++i) n.push_back(i);
  for (std::size_t i : {511, 512, 513, 1023}) n.push_back(i);
  return n;
}

std::shared_ptr<const PupsTransform> preset_transform(const std::string& name) {
  return std::static_pointer_cast<const PupsTransform>(make_pups_transform_from_spec(name));
}

std::vector<double> random_line(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-100, 155);
  std::vector<double> x(n);
  for (double& v : x) v = u(rng);
  return x;
}

TEST(PupsTransform, PerfectReconstructionForEveryLength) {
  for (const auto& preset : presets()) {
    const auto t = preset_transform(preset.name);
    for (std::size_t n : lengths()) {
      const std::vector<double> x = random_line(n, static_cast<unsigned>(n));
      const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
      std::vector<double> y = x;
      t->analyze(std::span<double>(y));
      t->synthesize(std::span<double>(y));
      double err = 0;
      for (std::size_t i = 0; i < n; ++i) err = std::max(err, std::abs(y[i] - x[i]));
      ASSERT_LE(err, 1e-9 * std::max(1.0, *hi - *lo)) << preset.name << " n=" << n;
    }
  }
}

TEST(PupsTransform, FloatLinesReconstructToFloatPrecision) {
  const auto t = preset_transform("cinpact-interp-c5-ext");
  for (std::size_t n : {1, 2, 3, 17, 64, 513}) {
    const std::vector<double> xd = random_line(n, 7);
    std::vector<float> x(xd.begin(), xd.end()), y = x;
    t->analyze(std::span<float>(y));
    t->synthesize(std::span<float>(y));
    for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(y[i], x[i], 1e-3) << "n=" << n;
  }
}

// Taps equal after dropping design taps that are zero to rounding (padding of P).
void expect_same_filter(const Filter& realized, const Filter& designed, double scale, int shift,
                        const char* what) {
  double m = 0;
  for (double v : designed.taps) m = std::max(m, std::abs(v));
  for (std::size_t t = 0; t < designed.taps.size(); ++t) {
    const int pos = designed.offset + static_cast<int>(t) + shift;
    const int k = pos - realized.offset;
    const double got = (k >= 0 && k < static_cast<int>(realized.taps.size()))
                           ? realized.taps[static_cast<std::size_t>(k)]
                           : 0.0;
    EXPECT_NEAR(got, designed.taps[t] * scale, 1e-12 * std::max(1.0, m)) << what << " tap " << t;
  }
  EXPECT_LE(realized.taps.size(), designed.taps.size()) << what;
}

TEST(PupsTransform, InteriorFiltersAreTheDesignedOnes) {
  for (const auto& preset : presets()) {
    const auto t = preset_transform(preset.name);
    const FilterBank& d = t->bank();
    const FilterBank& in = t->factorization().interior;
    const double g = t->factorization().dc_gain;
    // The detail index may be re-labelled (an even shift of B and Q together).
    const int shift = in.B.offset - d.B.offset;
    SCOPED_TRACE(preset.name);
    EXPECT_EQ(shift % 2, 0);
    expect_same_filter(in.P, d.P, g, 0, "P");
    expect_same_filter(in.A, d.A, 1 / g, 0, "A");
    expect_same_filter(in.B, d.B, 1, shift, "B");
    expect_same_filter(in.Q, d.Q, 1, shift, "Q");
  }
}

TEST(PupsTransform, InteriorSamplesApplyTheRealizedFilters) {
  const std::size_t n = 400;
  for (const auto& preset : presets()) {
    const auto t = preset_transform(preset.name);
    const FilterBank& in = t->factorization().interior;
    const std::vector<double> x = random_line(n, 3);
    std::vector<double> y = x;
    t->analyze(std::span<double>(y));
    auto apply = [&x](const Filter& f, std::size_t j) {
      double s = 0;
      for (std::size_t k = 0; k < f.taps.size(); ++k)
        s +=
            f.taps[k] * x[static_cast<std::size_t>(2 * static_cast<int>(j) + f.offset + static_cast<int>(k))];
      return s;
    };
    for (std::size_t j = 60; j < 140; ++j) {  // far from both ends for every preset
      EXPECT_NEAR(y[j], apply(in.A, j), 1e-9) << preset.name << " coarse " << j;
      EXPECT_NEAR(y[n / 2 + j], apply(in.B, j), 1e-9) << preset.name << " detail " << j;
    }
    // Synthesis of one interior coarse (detail) impulse is the P (Q) column.
    for (const bool coarse : {true, false}) {
      std::vector<double> z(n, 0.0);
      const std::size_t j = 100;
      z[coarse ? j : n / 2 + j] = 1.0;
      t->synthesize(std::span<double>(z));
      const Filter& f = coarse ? in.P : in.Q;
      for (std::size_t i = 0; i < n; ++i) {
        const int k = static_cast<int>(i) - 2 * static_cast<int>(j) - f.offset;
        const double want =
            (k >= 0 && k < static_cast<int>(f.taps.size())) ? f.taps[static_cast<std::size_t>(k)] : 0.0;
        EXPECT_NEAR(z[i], want, 1e-12) << preset.name << (coarse ? " P" : " Q") << " sample " << i;
      }
    }
  }
}

TEST(PupsTransform, ConstantLineGivesThatConstantAsCoarseBand) {
  for (const auto& preset : presets()) {
    const auto t = preset_transform(preset.name);
    for (std::size_t n = 1; n <= 40; ++n) {
      std::vector<double> y(n, 3.5);
      t->analyze(std::span<double>(y));
      for (std::size_t j = 0; j < (n + 1) / 2; ++j)
        ASSERT_NEAR(y[j], 3.5, 1e-12) << preset.name << " n=" << n << " j=" << j;
    }
  }
}

// Largest values measured over N = 1..300, 511, 512, 513, 1023 (docs/pups.md) plus ~20%.
struct CondBound {
  const char* preset;
  double one_norm, two_norm;
};
constexpr CondBound kCondBounds[] = {
    {"chaikin", 7.0, 4.2},       {"cubic-bspline", 17, 8.0},      {"cinpact-c3", 105, 55},
    {"cinpact-c3-ext", 92, 47},  {"cinpact-interp-c5", 9.3, 4.1}, {"cinpact-interp-c5-ext", 8.8, 3.6},
    {"poly10", 15.1, 7.2},       {"chaikin-ext", 7.4, 3.2},       {"cinpact-interp-vm4", 8.6, 3.4},
    {"poly16-vm4-cg", 8.2, 3.4},
};

TEST(PupsTransform, ConditionNumberIsBounded) {
  for (const auto& b : kCondBounds) {
    const auto t = preset_transform(b.preset);
    for (std::size_t n : lengths())
      ASSERT_LE(analysis_condition_number(*t, n, false), b.one_norm) << b.preset << " n=" << n;
    for (std::size_t n : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 16, 20, 21, 33, 64, 129})
      ASSERT_LE(analysis_condition_number(*t, n, true), b.two_norm) << b.preset << " n=" << n;
  }
}

TEST(PupsTransform, SpecsAreCanonicalAndRoundTrip) {
  EXPECT_EQ(make_pups_transform_from_spec("chaikin")->spec(), "pups:chaikin");
  const auto t = make_pups_transform_from_spec("cinpact-interp(sigma=4.79,c=5,l=32)");
  EXPECT_EQ(t->spec(), "pups:cinpact-interp(c=5,sigma=4.79,l=32)");
  const auto again =
      std::static_pointer_cast<const PupsTransform>(make_pups_transform_from_spec(t->spec().substr(5)));
  EXPECT_EQ(again->bank(), std::static_pointer_cast<const PupsTransform>(t)->bank());
  // Interior filters equal the preset of the same design.
  EXPECT_EQ(again->bank().Q, preset_transform("cinpact-interp-c5-ext")->bank().Q);
  EXPECT_EQ(make_pups_transform_from_spec("bspline(degree=3)")->spec(), "pups:bspline(degree=3,l=0)");
  for (const char* bad : {"", "chaikinn", "bspline(degree=3", "cinpact(c=3,sigma=7.27,l=-2)"})
    EXPECT_THROW(make_pups_transform_from_spec(bad), std::invalid_argument) << bad;
}

TEST(PupsTransform, BoundaryRuleIsPartOfTheSpec) {
  const auto hss = make_pups_transform_from_spec("cinpact-interp(c=5,sigma=4.79,l=8)");
  const auto wss = make_pups_transform_from_spec("cinpact-interp(c=5,sigma=4.79,l=8,boundary=wss)");
  EXPECT_EQ(wss->spec(), "pups:cinpact-interp(c=5,sigma=4.79,l=8,boundary=wss)");
  EXPECT_EQ(make_pups_transform_from_spec("cinpact-interp(c=5,sigma=4.79,l=8,boundary=hss)")->spec(),
            hss->spec());
  EXPECT_EQ(preset_transform("poly16-vm4-cg")->boundary(), BoundaryRule::line_wss);
  // Same filters inside, different ends; both reconstruct (every preset is checked above).
  std::vector<double> a = random_line(64, 3), b = a;
  hss->analyze(std::span<double>(a));
  wss->analyze(std::span<double>(b));
  EXPECT_NEAR(a[16], b[16], 1e-9);
  EXPECT_GT(std::abs(a[0] - b[0]), 1e-6);
  EXPECT_THROW(make_pups_transform_from_spec("cinpact-interp(c=5,sigma=4.79,boundary=zero)"),
               std::invalid_argument);
}

TEST(PupsTransform, SpecCacheIsBounded) {
  for (int s = 200; s < 520; ++s)
    make_pups_transform_from_spec("bspline(degree=1,samples=" + std::to_string(s) + ")");
  EXPECT_LE(pups_transform_cache_size(), 256u);
  EXPECT_GT(pups_transform_cache_size(), 0u);
}

TEST(PupsTransform, BankFromHeaderBytesGivesTheSameTransform) {
  const auto t = preset_transform("poly10");
  const FilterBank read = filter_bank_from_bytes(to_bytes(t->bank()));
  const Transform1DPtr u = make_pups_transform(read, "pups:poly10");
  EXPECT_EQ(u->spec(), "pups:poly10");
  std::vector<double> a = random_line(101, 9), b = a;
  t->analyze(std::span<double>(a));
  u->analyze(std::span<double>(b));
  EXPECT_EQ(a, b);
}

TEST(PupsTransform, NonReconstructingBankIsRejected) {
  FilterBank bank = preset_transform("chaikin")->bank();
  bank.A.taps[1] += 0.01;
  EXPECT_THROW(make_pups_transform(bank, "pups:broken"), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::pups

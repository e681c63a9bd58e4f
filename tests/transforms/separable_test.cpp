// Separable engine: subband geometry, perfect reconstruction on 1-D/2-D/3-D arrays of odd,
// even and prime sizes, partial inverse for reduced resolution, thread independence.
#include "transforms/separable.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "transforms/cdf.h"

namespace pupwave {
namespace {

std::size_t volume(const Extent& d) { return d[0] * d[1] * d[2]; }

std::vector<Extent> test_dims() {
  return {{1, 1, 1},   {2, 1, 1},   {300, 1, 1}, {1, 37, 1},   {1, 1, 13}, {17, 1, 1},
          {1, 8, 5},   {64, 64, 1}, {31, 7, 1},  {97, 101, 1}, {3, 2, 1},  {128, 1, 9},
          {13, 11, 7}, {16, 9, 4},  {2, 2, 2},   {23, 1, 19},  {5, 33, 17}};
}

template <class T>
std::vector<T> random_array(std::size_t n, unsigned seed, double lo, double hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<T> v(n);
  for (auto& x : v) x = static_cast<T>(std::floor(u(rng)));
  return v;
}

TEST(Separable, LevelExtentAndDefaultLevels) {
  EXPECT_EQ(level_extent({513, 1, 10}, 0), (Extent{513, 1, 10}));
  EXPECT_EQ(level_extent({513, 1, 10}, 1), (Extent{257, 1, 5}));
  EXPECT_EQ(level_extent({513, 1, 10}, 3), (Extent{65, 1, 2}));
  EXPECT_EQ(default_levels({1, 1, 1}), 0);
  EXPECT_EQ(default_levels({2, 1, 1}), 1);
  EXPECT_EQ(default_levels({512, 512, 1}), 6);   // 512 -> 256 -> ... -> 16 -> 8 (< 16)
  EXPECT_EQ(default_levels({4096, 300, 1}), 5);  // shortest axis 300 -> 150 -> ... -> 10
  EXPECT_EQ(default_levels({1 << 20, 1 << 20, 1}), 8);
  EXPECT_THROW(level_extent({4, 4, 4}, -1), std::invalid_argument);
}

TEST(Separable, SubbandsTileTheArrayExactly) {
  for (const Extent& d : test_dims()) {
    for (int levels = 0; levels <= 8; ++levels) {
      const auto bands = subbands(d, levels);
      ASSERT_FALSE(bands.empty());
      EXPECT_EQ(bands[0].orientation, 0u);
      EXPECT_EQ(bands[0].level, levels);
      EXPECT_EQ(bands[0].size, level_extent(d, levels));
      std::vector<int> covered(volume(d), 0);
      int prev_level = levels + 1;
      unsigned prev_orientation = 0;
      for (std::size_t k = 1; k < bands.size(); ++k) {
        const Subband& b = bands[k];
        EXPECT_NE(b.orientation, 0u);
        EXPECT_GT(b.count(), 0u);
        EXPECT_TRUE(b.level < prev_level || (b.level == prev_level && b.orientation > prev_orientation));
        prev_level = b.level, prev_orientation = b.orientation;
      }
      for (const Subband& b : bands)
        for (std::size_t z = 0; z < b.size[2]; ++z)
          for (std::size_t y = 0; y < b.size[1]; ++y)
            for (std::size_t x = 0; x < b.size[0]; ++x)
              ++covered[(b.offset[2] + z) * d[0] * d[1] + (b.offset[1] + y) * d[0] + b.offset[0] + x];
      EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }))
          << d[0] << "x" << d[1] << "x" << d[2] << " levels " << levels;
    }
  }
}

class SeparableRoundTrip : public ::testing::TestWithParam<const char*> {
 protected:
  Transform1DPtr t() const { return GetParam() == std::string("cdf97") ? make_cdf97() : make_cdf53(); }
};

TEST_P(SeparableRoundTrip, DoubleAndFloat) {
  const auto tr = t();
  unsigned seed = 1;
  for (const Extent& d : test_dims()) {
    for (int levels = 1; levels <= 8; ++levels) {
      const auto x = random_array<double>(volume(d), ++seed, -128, 128);
      auto y = x;
      forward(*tr, y.data(), d, levels);
      inverse(*tr, y.data(), d, levels);
      double err = 0;
      for (std::size_t i = 0; i < x.size(); ++i) err = std::max(err, std::abs(x[i] - y[i]));
      EXPECT_LT(err, 1e-9 * 256) << d[0] << "x" << d[1] << "x" << d[2] << " L" << levels;
      std::vector<float> f(x.begin(), x.end());
      forward(*tr, f.data(), d, levels);
      inverse(*tr, f.data(), d, levels);
      for (std::size_t i = 0; i < x.size(); ++i) ASSERT_NEAR(f[i], x[i], 256 * 1e-5);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Cdf, SeparableRoundTrip, ::testing::Values("cdf97", "cdf53"));

TEST(Separable, IntegerCdf53IsBitExact) {
  const auto tr = make_cdf53();
  unsigned seed = 100;
  for (const Extent& d : test_dims()) {
    for (int levels = 1; levels <= 8; ++levels) {
      const auto x = random_array<int32_t>(volume(d), ++seed, -70000, 70000);
      auto y = x;
      forward(*tr, y.data(), d, levels);
      if (volume(d) > 8) {
        EXPECT_NE(x, y);  // something was transformed
      }
      inverse(*tr, y.data(), d, levels);
      ASSERT_EQ(x, y) << d[0] << "x" << d[1] << "x" << d[2] << " L" << levels;
    }
  }
}

// One level of the engine equals 1-D analysis of every row, then of every column, then of
// every line along z (checks the strided gather/scatter against a plain reference).
TEST(Separable, OneLevelIsRowsThenColumnsThenSlices) {
  const Extent d{37, 21, 5};
  const auto x = random_array<double>(volume(d), 5, -10, 10);
  auto y = x, ref = x;
  const auto tr = make_cdf97();
  forward(*tr, y.data(), d, 1);
  const std::size_t strides[3] = {1, d[0], d[0] * d[1]};
  for (std::size_t a = 0; a < 3; ++a) {
    for (std::size_t start = 0; start < ref.size(); ++start) {
      if ((start / strides[a]) % d[a] != 0) continue;  // first sample of a line along a
      std::vector<double> line(d[a]);
      for (std::size_t i = 0; i < d[a]; ++i) line[i] = ref[start + i * strides[a]];
      tr->analyze(std::span<double>(line));
      for (std::size_t i = 0; i < d[a]; ++i) ref[start + i * strides[a]] = line[i];
    }
  }
  for (std::size_t i = 0; i < y.size(); ++i) ASSERT_NEAR(y[i], ref[i], 1e-12);
}

// Partial inverse down to level k equals the coarse band of a k-level forward transform.
TEST(Separable, StopLevelGivesCoarseBandOfFewerLevels) {
  const auto tr = make_cdf53();
  for (const Extent& d : {Extent{61, 45, 1}, Extent{19, 1, 23}, Extent{12, 17, 9}}) {
    const auto x = random_array<int32_t>(volume(d), 9, -1000, 1000);
    for (int levels = 1; levels <= 5; ++levels) {
      for (int k = 1; k <= levels; ++k) {
        auto full = x, fewer = x;
        forward(*tr, full.data(), d, levels);
        inverse(*tr, full.data(), d, levels, k);
        forward(*tr, fewer.data(), d, k);
        const Extent c = level_extent(d, k);
        for (std::size_t z = 0; z < c[2]; ++z)
          for (std::size_t y = 0; y < c[1]; ++y)
            for (std::size_t xx = 0; xx < c[0]; ++xx) {
              const std::size_t i = (z * d[1] + y) * d[0] + xx;
              ASSERT_EQ(full[i], fewer[i]) << "levels " << levels << " stop " << k;
            }
      }
    }
  }
}

// The same for the irreversible 9/7 in double, to rounding.
TEST(Separable, StopLevelMatchesForCdf97) {
  const auto tr = make_cdf97();
  const Extent d{50, 37, 3};
  const auto x = random_array<double>(volume(d), 13, -1000, 1000);
  for (int k = 1; k <= 4; ++k) {
    auto full = x, fewer = x;
    forward(*tr, full.data(), d, 5);
    inverse(*tr, full.data(), d, 5, k);
    forward(*tr, fewer.data(), d, k);
    const Extent c = level_extent(d, k);
    for (std::size_t z = 0; z < c[2]; ++z)
      for (std::size_t y = 0; y < c[1]; ++y)
        for (std::size_t xx = 0; xx < c[0]; ++xx) {
          const std::size_t i = (z * d[1] + y) * d[0] + xx;
          ASSERT_NEAR(full[i], fewer[i], 1e-9 * 2000) << "stop " << k;
        }
  }
}

TEST(Separable, ThreadCountDoesNotChangeResults3d) {
  const Extent d{90, 60, 40};
  const auto x = random_array<double>(volume(d), 22, -100, 100);
  auto one = x, many = x;
  const auto tr = make_cdf53();
  forward(*tr, one.data(), d, 3, serial_executor());
  forward(*tr, many.data(), d, 3, *make_pool_executor(3));
  inverse(*tr, many.data(), d, 3, 0, *make_pool_executor(3));
  inverse(*tr, one.data(), d, 3, 0, default_executor());
  EXPECT_EQ(one, many);
  for (std::size_t i = 0; i < x.size(); ++i) ASSERT_NEAR(one[i], x[i], 1e-9);
}

TEST(Separable, ThreadCountDoesNotChangeResults) {
  const Extent d{700, 400, 1};
  const auto x = random_array<float>(volume(d), 21, -100, 100);
  auto one = x, many = x;
  const auto tr = make_cdf97();
  forward(*tr, one.data(), d, 4, serial_executor());
  forward(*tr, many.data(), d, 4, *make_pool_executor(4));
  EXPECT_EQ(one, many);
  EXPECT_NE(one, x);
}

TEST(Separable, RejectsBadArguments) {
  std::vector<int32_t> v(16, 1);
  std::vector<double> w(16, 1);
  EXPECT_THROW(forward(*make_cdf97(), v.data(), {4, 4, 1}, 1), std::logic_error);
  EXPECT_THROW(forward(*make_cdf97(), w.data(), {4, 4, 1}, -1), std::invalid_argument);
  EXPECT_THROW(forward(*make_cdf97(), w.data(), {4, 0, 1}, 1), std::invalid_argument);
  EXPECT_THROW(inverse(*make_cdf97(), w.data(), {4, 4, 1}, 2, 3), std::invalid_argument);
  EXPECT_THROW(forward<double>(*make_cdf97(), nullptr, {4, 4, 1}, 1), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave

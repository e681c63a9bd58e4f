// Lifting primitives: split/merge, boundary reflection, exact mirror steps.
#include "transforms/lifting.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace pupwave::lifting {
namespace {

TEST(Lifting, SplitMergeRoundTrip) {
  for (std::size_t n = 1; n <= 17; ++n) {
    std::vector<int> line(n), scratch(n / 2);
    for (std::size_t i = 0; i < n; ++i) line[i] = static_cast<int>(i);
    split<int>(line, scratch);
    for (std::size_t j = 0; j < (n + 1) / 2; ++j) EXPECT_EQ(line[j], static_cast<int>(2 * j));
    for (std::size_t j = 0; j < n / 2; ++j) EXPECT_EQ(line[(n + 1) / 2 + j], static_cast<int>(2 * j + 1));
    merge<int>(line, scratch);
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(line[i], static_cast<int>(i));
  }
}

// A scratch of the whole line selects the vectorized split/merge (through a copy of the line):
// it must reorder exactly as the compacting form with half a line of scratch does.
TEST(Lifting, SplitMergeWithWholeLineScratchMatchHalfScratch) {
  for (std::size_t n = 1; n <= 41; ++n) {
    std::vector<float> a(n), b(n), half(n / 2), whole(n);
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] = static_cast<float>(i) * 1.5f - 7.0f;
    split<float>(a, half);
    split<float>(b, whole);
    EXPECT_EQ(a, b) << "split n=" << n;
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] = static_cast<float>(3 * i % 11) - 4.0f;
    merge<float>(a, half);
    merge<float>(b, whole);
    EXPECT_EQ(a, b) << "merge n=" << n;
  }
}

// Reflection by the wire rules must agree with whole-sample symmetric extension of the
// interleaved line, element by element, far beyond the ends.
TEST(Lifting, WireRulesMatchWholeSampleSymmetricLine) {
  for (std::ptrdiff_t n = 2; n <= 9; ++n) {
    auto ws = [n](std::ptrdiff_t i) {  // direct WS extension of x[0..n), period 2(n-1)
      const std::ptrdiff_t p = 2 * (n - 1);
      i = ((i % p) + p) % p;
      return i < n ? i : p - i;
    };
    const auto wires = whole_sample_symmetric_wires(static_cast<std::size_t>(n));
    const auto ne = static_cast<std::size_t>((n + 1) / 2), no = static_cast<std::size_t>(n / 2);
    for (std::ptrdiff_t j = -12; j < 12; ++j) {
      EXPECT_EQ(2 * static_cast<std::ptrdiff_t>(reflect_index(j, ne, wires.even)), ws(2 * j))
          << "n=" << n << " even j=" << j;
      EXPECT_EQ(2 * static_cast<std::ptrdiff_t>(reflect_index(j, no, wires.odd)) + 1, ws(2 * j + 1))
          << "n=" << n << " odd j=" << j;
    }
  }
}

TEST(Lifting, HalfSampleReflection) {
  const Boundary hs{Extension::half_sample, Extension::half_sample};
  EXPECT_EQ(reflect_index(-1, 4, hs), 0u);
  EXPECT_EQ(reflect_index(-2, 4, hs), 1u);
  EXPECT_EQ(reflect_index(4, 4, hs), 3u);
  EXPECT_EQ(reflect_index(5, 4, hs), 2u);
  EXPECT_EQ(reflect_index(9, 4, hs), 1u);  // 9 -> -2 -> 1
  EXPECT_EQ(reflect_index(-7, 1, hs), 0u);
}

TEST(Lifting, MirrorStepsUndoFloatSteps) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const double t5[] = {0.1, -0.3, 0.7, -0.3, 0.1};
  const Taps f{t5, -2};
  for (std::size_t m = 1; m <= 9; ++m) {
    std::vector<double> e(m), o(m > 1 ? m - 1 : 0);
    for (auto& v : e) v = u(rng);
    for (auto& v : o) v = u(rng);
    const auto e0 = e, o0 = o;
    const Boundary b{Extension::half_sample, Extension::whole_sample};
    predict<double>(e, b, o, f);
    update<double>(o, b, e, f);
    scale<double>(e, 1.7);
    undo_scale<double>(e, 1.7);
    undo_update<double>(o, b, e, f);
    undo_predict<double>(e, b, o, f);
    for (std::size_t i = 0; i < e.size(); ++i) EXPECT_NEAR(e[i], e0[i], 1e-14);
    for (std::size_t i = 0; i < o.size(); ++i) EXPECT_NEAR(o[i], o0[i], 1e-14);
  }
}

TEST(Lifting, IntegerStepsAreBitExact) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int32_t> u(-100000, 100000);
  const int32_t w[] = {1, 1};
  const IntegerTaps p{w, 0, 0, 1}, q{w, -1, 2, 2};
  for (std::size_t n = 1; n <= 12; ++n) {
    std::vector<int32_t> e((n + 1) / 2), o(n / 2);
    for (auto& v : e) v = u(rng);
    for (auto& v : o) v = u(rng);
    const auto e0 = e, o0 = o;
    const auto wires = whole_sample_symmetric_wires(n);
    lift_integer(e, wires.even, o, p, Direction::subtract);
    lift_integer(o, wires.odd, e, q, Direction::add);
    lift_integer(o, wires.odd, e, q, Direction::subtract);
    lift_integer(e, wires.even, o, p, Direction::add);
    EXPECT_EQ(e, e0);
    EXPECT_EQ(o, o0);
  }
}

TEST(Lifting, FloorRoundingOfNegativeSums) {
  const int32_t w[] = {1, 1};
  std::vector<int32_t> e{-3, 0}, o{0};
  lift_integer(e, {}, o, IntegerTaps{w, 0, 0, 1}, Direction::subtract);
  EXPECT_EQ(o[0], 2);  // -floor(-3/2) = 2
}

}  // namespace
}  // namespace pupwave::lifting

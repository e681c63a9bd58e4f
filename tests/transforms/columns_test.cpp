// Transform1D::analyze_columns / synthesize_columns: the column-block form the separable
// engine uses gives bit-identically the results of transforming each column as a line, for
// the transforms that override it with row-wise lifting (CDF 9/7 and 5/3, PUPs) and for the
// default (copy each column out) used by the other families (Kobbelt).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "transforms/spec.h"

namespace pupwave {
namespace {

template <class T>
std::vector<T> random_block(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> v(-300, 300);
  std::vector<T> b(count);
  for (auto& x : b) x = std::is_integral_v<T> ? T(v(rng)) : T(v(rng)) / T(7);
  return b;
}

// Column c of a block of rows as a line, transformed by the 1-D form.
template <class T>
std::vector<T> by_lines(const Transform1D& t, std::vector<T> block, std::size_t width, bool analysis) {
  const std::size_t n = block.size() / width;
  std::vector<T> line(n);
  for (std::size_t c = 0; c < width; ++c) {
    for (std::size_t i = 0; i < n; ++i) line[i] = block[i * width + c];
    if (analysis)
      t.analyze(std::span<T>(line));
    else
      t.synthesize(std::span<T>(line));
    for (std::size_t i = 0; i < n; ++i) block[i * width + c] = line[i];
  }
  return block;
}

template <class T>
void expect_columns_match(const std::string& spec) {
  const auto t = make_transform(spec);
  for (std::size_t n = 1; n <= 37; ++n)
    for (std::size_t width : {1u, 3u, 17u, 32u}) {
      const auto input = random_block<T>(n * width, unsigned(n * 100 + width));
      for (bool analysis : {true, false}) {
        auto block = input;
        if (analysis)
          t->analyze_columns(std::span<T>(block), width);
        else
          t->synthesize_columns(std::span<T>(block), width);
        const auto expected = by_lines(*t, input, width, analysis);
        // Bit-identical: memcmp-like comparison, so -0 and +0 or NaNs would differ too.
        ASSERT_EQ(0, std::memcmp(block.data(), expected.data(), block.size() * sizeof(T)))
            << spec << " n=" << n << " width=" << width << (analysis ? " analysis" : " synthesis");
      }
    }
}

TEST(Columns, Cdf97MatchesLines) {
  expect_columns_match<float>("cdf97");
  expect_columns_match<double>("cdf97");
}

TEST(Columns, Cdf53MatchesLinesInEveryType) {
  expect_columns_match<float>("cdf53");
  expect_columns_match<double>("cdf53");
  expect_columns_match<std::int32_t>("cdf53");
}

TEST(Columns, PupsMatchesLines) {
  for (const char* spec :
       {"pups:chaikin", "pups:cinpact-interp-vm4", "pups:poly16-vm4-cg", "pups:cinpact-c3-ext"}) {
    expect_columns_match<float>(spec);
    expect_columns_match<double>(spec);
  }
}

TEST(Columns, DefaultFormMatchesLines) { expect_columns_match<double>("kobbelt:k2"); }

}  // namespace
}  // namespace pupwave

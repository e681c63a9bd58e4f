// Spec strings: every listed spec builds a transform with that canonical spec, which
// reconstructs perfectly on 1-D lines and through the separable engine; unknown specs fail.
#include "transforms/spec.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "transforms/separable.h"

namespace pupwave {
namespace {

TEST(Spec, ListsTheBaselines) {
  const auto specs = transform_specs();
  EXPECT_NE(std::find(specs.begin(), specs.end(), "cdf97"), specs.end());
  EXPECT_NE(std::find(specs.begin(), specs.end(), "cdf53"), specs.end());
}

TEST(Spec, EveryListedSpecRoundTrips) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0, 255);
  for (const auto& name : transform_specs()) {
    const auto t = make_transform(name);
    ASSERT_NE(t, nullptr) << name;
    EXPECT_EQ(t->spec(), name);
    for (std::size_t n : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 16u, 31u, 64u, 97u, 300u, 511u, 512u}) {
      std::vector<double> x(n);
      for (auto& v : x) v = u(rng);
      auto y = x;
      t->analyze(std::span<double>(y));
      t->synthesize(std::span<double>(y));
      double err = 0;
      for (std::size_t i = 0; i < n; ++i) err = std::max(err, std::abs(x[i] - y[i]));
      EXPECT_LT(err, 1e-9 * 255) << name << " n=" << n;
    }
    for (const Extent& d : {Extent{37, 23, 1}, Extent{11, 6, 13}}) {
      std::vector<double> x(d[0] * d[1] * d[2]);
      for (auto& v : x) v = u(rng);
      auto y = x;
      forward(*t, y.data(), d, 3);
      inverse(*t, y.data(), d, 3);
      double err = 0;
      for (std::size_t i = 0; i < x.size(); ++i) err = std::max(err, std::abs(x[i] - y[i]));
      EXPECT_LT(err, 1e-9 * 255) << name << " " << d[0] << "x" << d[1] << "x" << d[2];
    }
  }
}

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

// Chroma from luma in the pc coder (codec/entropy/pc_cfl.h, docs/bitstream.md): the least-squares
// weights and their rounding to sixteenths, the prediction's float expression, and the weights'
// codes round-tripping at the head of a codeword (and refused beyond [-32, 32]).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "codec/entropy/pc_blocks.h"
#include "codec/entropy/pc_cfl.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// y = a x1 + b x2 + noise over random x1, x2: the sums of pc_cfl_fit.
PcCflSums sums_of(double a, double b, double noise, unsigned seed, int n = 4000) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  PcCflSums s;
  for (int k = 0; k < n; ++k) {
    const double x1 = 10.0 * g(rng), x2 = 4.0 * g(rng) + 0.3 * x1;  // Cb goes a little with luma
    s.add(x1, x2, a * x1 + b * x2 + noise * g(rng));
  }
  return s;
}

TEST(PcCfl, CodesAreWeightsInSixteenthsClampedToTwo) {
  EXPECT_EQ(pc_cfl_code(0.5), 8);
  EXPECT_EQ(pc_cfl_code(-0.25), -4);
  EXPECT_EQ(pc_cfl_code(0.03), 0);  // under half a sixteenth
  EXPECT_EQ(pc_cfl_code(0.04), 1);  // over it
  EXPECT_EQ(pc_cfl_code(7.0), 32);  // clamped to 2
  EXPECT_EQ(pc_cfl_code(-7.0), -32);
  EXPECT_EQ(pc_cfl_code(std::numeric_limits<double>::quiet_NaN()), 0);
}

TEST(PcCfl, LeastSquaresFindsTheWeightsOfOneAndTwoRegressors) {
  const PcCfl cb = pc_cfl_fit(sums_of(-0.375, 0.0, 0.5, 1), 1);
  EXPECT_EQ(cb.count, 1);
  EXPECT_EQ(cb.code[0], -6);
  const PcCfl cr = pc_cfl_fit(sums_of(0.125, -1.25, 0.5, 2), 2);
  EXPECT_EQ(cr.count, 2);
  EXPECT_EQ(cr.code[0], 2);
  EXPECT_EQ(cr.code[1], -20);
  // Uncorrelated chroma: no prediction.
  EXPECT_TRUE(pc_cfl_none(pc_cfl_fit(sums_of(0.0, 0.0, 1.0, 3), 2)));
}

TEST(PcCfl, RegressorsThatCarryNothingGiveZeroOrTheOtherOne) {
  EXPECT_TRUE(pc_cfl_none(pc_cfl_fit(PcCflSums{}, 1)));  // luma all zero (a coarse step)
  EXPECT_TRUE(pc_cfl_none(pc_cfl_fit(PcCflSums{}, 2)));
  PcCflSums only_cb;  // luma zero, Cb carries it: Cb's weight alone
  for (int k = -50; k <= 50; ++k) only_cb.add(0.0, double(k), 0.5 * double(k));
  const PcCfl w = pc_cfl_fit(only_cb, 2);
  EXPECT_EQ(w.code[0], 0);
  EXPECT_EQ(w.code[1], 8);
  PcCflSums same;  // Cb = luma (collinear): luma's weight takes it all
  for (int k = -50; k <= 50; ++k) same.add(double(k), double(k), 0.75 * double(k));
  const PcCfl c = pc_cfl_fit(same, 2);
  EXPECT_EQ(c.code[0], 12);
  EXPECT_EQ(c.code[1], 0);
}

TEST(PcCfl, PredictionIsTheFloatExpressionOfTheFormat) {
  PcCfl k;
  k.count = 2;
  k.code[0] = -3;
  k.code[1] = 17;
  const float l = 12.375f, cb = -3.5f;
  const float expect = float(-3) * (1.0f / 16) * l + float(17) * (1.0f / 16) * cb;
  EXPECT_EQ(pc_cfl_predict(k, l, cb), expect);
  k.count = 1;  // Cb's prediction ignores the second weight
  EXPECT_EQ(pc_cfl_predict(k, l, cb), float(-3) * (1.0f / 16) * l);
}

// Every code of [-32, 32] in both places goes through a codeword with the block's indices intact.
TEST(PcCfl, CodesRoundTripAtTheHeadOfTheCodeword) {
  std::mt19937 rng(9);
  const std::size_t w = 9, h = 7;
  for (int a = -32; a <= 32; ++a) {
    std::vector<std::int32_t> q(w * h);
    for (auto& v : q) v = std::int32_t(rng() % 7) - 3;
    q[0] = 5;  // never all zero
    const std::vector<std::int32_t> sent = q;
    PcCfl k;
    k.count = 2;
    k.code[0] = a;
    k.code[1] = -a / 2 + (a & 1);
    const CoefCodeword word = pc_encode_block(q, w, h, LcParent{}, nullptr, {}, &k);
    std::vector<std::int32_t> out(w * h);
    PcCfl got;
    got.count = 2;
    pc_decode_block(word.bytes, word.bits, w, h, LcParent{}, out.data(), w, {}, &got);
    EXPECT_EQ(out, sent) << a;
    EXPECT_EQ(got.code[0], k.code[0]);
    EXPECT_EQ(got.code[1], k.code[1]);
  }
}

TEST(PcCfl, CodesBeyondTheRangeAreRefused) {
  std::vector<std::int32_t> q(16, 1);
  PcCfl k;
  k.count = 1;
  k.code[0] = 33;
  EXPECT_THROW(pc_encode_block(q, 4, 4, LcParent{}, nullptr, {}, &k), std::invalid_argument);
  // A codeword with code 33 written by the unchecked loop: the decoder refuses it.
  auto [bytes, largest] = pc_encode_indices(q, 4, 4, PcContext(4, 4, LcParent{}), nullptr, &k);
  ASSERT_EQ(largest, 1u);
  std::vector<std::int32_t> out(16);
  PcCfl got;
  got.count = 1;
  EXPECT_THROW(pc_decode_block(bytes, 1, 4, 4, LcParent{}, out.data(), 4, {}, &got), DecodeError);
}

}  // namespace
}  // namespace pupwave

// Chroma from luma in the pc coder (codec/entropy/pc_cfl.h, docs/bitstream.md): the least-squares
// weights and their rounding to sixteenths, the prediction's float expression, and the weights'
// codes round-tripping at the head of a codeword (and refused beyond [-32, 32]), and the
// encoder's estimate of whether a block's prediction pays (pc_cfl_pays).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <span>
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

TEST(PcCfl, ProxyCostCountsRoundingErrorEntropyAndNonZeros) {
  const std::vector<float> zeros(64, 0.0f);
  EXPECT_EQ(pc_cfl_proxy_cost(zeros, 0.05, 0.1), 0.0);
  // One index 1 (reconstructed at 1.05): its error, one class (no entropy), a sign bit, a non-zero.
  const std::vector<float> one = {1.0f};
  EXPECT_NEAR(pc_cfl_proxy_cost(one, 0.05, 0.1), 0.0025 + 0.1 * (0.25 * 1.0 + 2.0), 1e-9);
  // Half zeros, half index 1: one bit of class entropy per value on top.
  const std::vector<float> half = {0.0f, 1.05f, 0.0f, -1.05f};
  EXPECT_NEAR(pc_cfl_proxy_cost(half, 0.05, 0.1), 0.1 * (0.25 * (4.0 + 2.0) + 2.0 * 2.0), 1e-9);
}

// A block's values u (index units) and a residual ur: squared index-unit error + lambda x bits
// of each coded for real with RDOQ (the both-ways test the encoder made before pc_cfl_pays).
double coded_cost(std::span<const float> x, std::size_t w, std::size_t h, const PcCfl& k) {
  std::vector<std::int32_t> q(x.size());
  const PcRdoq rdoq{x, 0.1, 0.05};
  const CoefCodeword word = pc_encode_block(q, w, h, LcParent{}, &rdoq, {}, &k);
  double e = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = q[i] == 0 ? 0.0 : (q[i] < 0 ? double(q[i]) - 0.05 : double(q[i]) + 0.05);
    e += (double(x[i]) - r) * (double(x[i]) - r);
  }
  return e + 0.1 * 8.0 * double(word.bytes.size());
}

TEST(PcCfl, PredictionIsChosenWhereItClearlyPaysAndNotWhereItDoesNot) {
  const std::size_t w = 64, h = 64;
  std::mt19937 rng(5);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::vector<float> luma(w * h), noise(w * h), u(w * h), ur(w * h);
  for (auto& l : luma) l = 4.0f * g(rng);
  for (auto& n : noise) n = 0.3f * g(rng);
  PcCfl k;
  k.count = 1;
  k.code[0] = 12;
  // Chroma that follows luma (weight 0.75): the residual is the small noise alone.
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = 0.75f * luma[i] + noise[i], ur[i] = noise[i];
  EXPECT_TRUE(pc_cfl_pays(u, ur, 0.05, 0.1));
  EXPECT_LT(coded_cost(ur, w, h, k), coded_cost(u, w, h, k));  // coding both ways agrees
  // Chroma that barely codes (almost all under half a step) and a weak prediction that spreads
  // luma's values into it: the residual codes more non-zeros than it removes.
  for (std::size_t i = 0; i < u.size(); ++i) u[i] = noise[i], ur[i] = noise[i] - 0.125f * luma[i];
  EXPECT_FALSE(pc_cfl_pays(u, ur, 0.05, 0.1));
  EXPECT_GT(coded_cost(ur, w, h, k), coded_cost(u, w, h, k));
  // No gain at all (the same values): no prediction.
  EXPECT_FALSE(pc_cfl_pays(u, u, 0.05, 0.1));
}

}  // namespace
}  // namespace pupwave

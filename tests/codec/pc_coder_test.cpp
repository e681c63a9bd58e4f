// The parent-context coefficient coder (codec/entropy/pc_blocks.*, entropy coder 4):
// exact round trips with and without a parent and with a block offset inside its band, greedy
// RDOQ (the decoder gets exactly the re-chosen indices, each one of nearest / nearest - 1 / 0),
// the worth of the parent on correlated bands, and bounded decoding of corrupt codewords.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "codec/entropy/bit_model.h"
#include "codec/entropy/block_encoder.h"
#include "codec/entropy/pc_bit.h"
#include "codec/entropy/pc_blocks.h"
#include "codec/error.h"

namespace pupwave {
namespace {

// A parent band of Laplacian-like indices with a smooth envelope (as wavelet bands look).
std::vector<std::int32_t> parent_band(std::size_t w, std::size_t h, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> noise(1.0);
  std::vector<std::int32_t> p(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const double envelope = 1.0 + std::sin(0.4 * double(x)) * std::cos(0.3 * double(y));
      const auto m = std::int32_t(scale * envelope * noise(rng));
      p[y * w + x] = (rng() & 1u) ? -m : m;
    }
  return p;
}

// Child coefficients (index units) whose magnitudes follow the parent's at (x / 2, y / 2).
std::vector<float> child_coefficients(const std::vector<std::int32_t>& parent, std::size_t pw, std::size_t w,
                                      std::size_t h, unsigned seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> noise(1.0);
  std::vector<float> u(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const double scale = 0.1 + 1.5 * std::abs(parent[(y / 2) * pw + x / 2]);
      u[y * w + x] = float(((rng() & 1u) ? -1.0 : 1.0) * scale * noise(rng));
    }
  return u;
}

std::vector<std::int32_t> truncated(const std::vector<float>& u) {
  std::vector<std::int32_t> q(u.size());
  for (std::size_t k = 0; k < u.size(); ++k) q[k] = std::int32_t(u[k]);  // toward zero: dead-zone
  return q;
}

LcParent parent_of(const std::vector<std::int32_t>& p, std::size_t pw, std::size_t ph, std::size_t x0 = 0,
                   std::size_t y0 = 0) {
  return {p.data(), pw, pw, ph, x0, y0};
}

std::vector<std::int32_t> decode(const CoefCodeword& w, std::size_t width, std::size_t height,
                                 const LcParent& parent) {
  std::vector<std::int32_t> out(width * height, 7);
  pc_decode_block(w.bytes, w.bits, width, height, parent, out.data(), width);
  return out;
}

TEST(PcCoder, RoundTripsWithAndWithoutParent) {
  const std::size_t pw = 24, ph = 17, w = 48, h = 34;
  const auto parent = parent_band(pw, ph, 6.0, 1);
  for (bool with_parent : {false, true}) {
    auto q = truncated(child_coefficients(parent, pw, w, h, 2));
    const auto original = q;
    const LcParent lp = with_parent ? parent_of(parent, pw, ph) : LcParent{};
    const CoefCodeword word = pc_encode_block(q, w, h, lp);
    EXPECT_EQ(q, original);  // no RDOQ: the indices are left as they are
    ASSERT_GT(word.bits, 0);
    EXPECT_EQ(decode(word, w, h, lp), original);
  }
}

TEST(PcCoder, RoundTripsABlockInsideItsBand) {
  // A 16 x 8 block at (16, 24) of a band whose parent is 20 x 20: parents (8.., 12..) clamped.
  const std::size_t pw = 20, ph = 20, w = 16, h = 8;
  const auto parent = parent_band(pw, ph, 4.0, 3);
  auto q = truncated(child_coefficients(parent, pw, w, h, 4));
  const auto original = q;
  const LcParent lp = parent_of(parent, pw, ph, 16, 24);
  const CoefCodeword word = pc_encode_block(q, w, h, lp);
  EXPECT_EQ(decode(word, w, h, lp), original);
}

TEST(PcCoder, LargeIndicesUseTheEscapeAndRoundTrip) {
  std::vector<std::int32_t> q{0, 1, -2, (1 << 29) + 12345, -((1 << 20) + 7), 3, 0, -(1 << 29)};
  const auto original = q;
  const CoefCodeword word = pc_encode_block(q, 4, 2, LcParent{});
  EXPECT_EQ(word.bits, 30);
  EXPECT_EQ(decode(word, 4, 2, LcParent{}), original);
  std::vector<std::int32_t> too_large{1 << 30};
  EXPECT_THROW(pc_encode_block(too_large, 1, 1, LcParent{}), IndexRangeError);
}

TEST(PcCoder, AllZeroBlockHasNoCodeword) {
  std::vector<std::int32_t> q(64, 0);
  const CoefCodeword word = pc_encode_block(q, 8, 8, LcParent{});
  EXPECT_EQ(word.bits, 0);
  EXPECT_TRUE(word.bytes.empty());
}

TEST(PcCoder, ParentContextShortensCorrelatedBands) {
  const std::size_t pw = 64, ph = 64, w = 128, h = 128;
  const auto parent = parent_band(pw, ph, 1.5, 5);  // many zero parents, over near-zero children
  const auto u = child_coefficients(parent, pw, w, h, 6);
  auto q1 = truncated(u), q2 = truncated(u);
  const std::size_t without = pc_encode_block(q1, w, h, LcParent{}).bytes.size();
  const std::size_t with = pc_encode_block(q2, w, h, parent_of(parent, pw, ph)).bytes.size();
  // 0.98: these parents are independent noise under a smooth envelope, so the parent's
  // neighbours in the activity (real bands' are correlated) add noise here.
  EXPECT_LT(double(with), 0.98 * double(without)) << with << " vs " << without;
}

TEST(PcCoder, ActivityCountsTheParentsNeighbourOnTheChildsSideOnly) {
  // A silent block over a parent band that is zero but for (2, 1) = -9.
  const std::size_t pw = 4, ph = 4, w = 8, h = 8;
  std::vector<std::int32_t> parent(pw * ph, 0);
  parent[1 * pw + 2] = -9;
  const PcContext ctx(w, h, parent_of(parent, pw, ph));
  // Child (3, 2): parent (1, 1), its neighbour towards the child is column 2: S = 9, s = 3.
  EXPECT_EQ(ctx.at(3, 2).cls, 3);
  // Child (2, 2): parent (1, 1), neighbour column 0: nothing.
  EXPECT_EQ(ctx.at(2, 2).cls, 0);
  // Child (4, 2): parent (2, 1) itself: S = 3 x 9, s = 9, class 2 x 4 - 2 + 0; its sign counts.
  EXPECT_EQ(ctx.at(4, 2).cls, 6);
  EXPECT_EQ(ctx.at(4, 2).sign(), 27 + 9 + 3 + 0u);
  EXPECT_EQ(ctx.at(3, 2).sign(), 27 + 9 + 3 + 1u);  // a neighbour's sign does not
}

TEST(PcCoder, LumaParentJoinsActivityAndSignContext) {
  const std::size_t w = 4, h = 4;
  std::vector<std::int32_t> luma(w * h, 0);
  luma[1 * w + 2] = -5;
  const PcContext ctx(w, h, LcParent{}, PcLuma{luma.data(), w});
  EXPECT_EQ(ctx.at(2, 1).cls, 2 * 3 - 2 + 0);  // s = 5: bit width 3, next bit 0
  EXPECT_EQ(ctx.at(2, 1).sign(), 0 + 9 + 3 + 1u);
  EXPECT_EQ(ctx.at(1, 1).cls, 0);
  EXPECT_EQ(ctx.at(1, 1).sign(), 27 + 9 + 3 + 1u);
}

TEST(PcCoder, CbParentOfCrWeighsEightAndGivesTheSign) {
  const std::size_t w = 4, h = 4;
  std::vector<std::int32_t> luma(w * h, 0), cb(w * h, 0);
  luma[1 * w + 2] = -5;
  cb[1 * w + 2] = 1;
  const PcContext ctx(w, h, LcParent{}, PcLuma{luma.data(), w, cb.data()});
  EXPECT_EQ(ctx.at(2, 1).cls, 2 * 4 - 2 + 1);       // S = 15 + 24, s = 13: bit width 4, next bit 1
  EXPECT_EQ(ctx.at(2, 1).sign(), 54 + 9 + 3 + 1u);  // Cb's sign (+), not luma's
}

TEST(PcCoder, LumaParentRoundTripsAndShortensCorrelatedChroma) {
  const std::size_t w = 96, h = 80;
  const auto luma = parent_band(w, h, 4.0, 12);  // chroma magnitudes follow the luma indices
  std::mt19937 rng(13);
  std::exponential_distribution<double> noise(1.0);
  std::vector<float> u(w * h);
  for (std::size_t k = 0; k < u.size(); ++k)
    u[k] = float(((rng() & 1u) ? -1.0 : 1.0) * (0.1 + 0.8 * std::abs(luma[k])) * noise(rng));
  auto q1 = truncated(u), q2 = truncated(u);
  const auto original = q1;
  const PcLuma guide{luma.data(), w};
  const CoefCodeword with = pc_encode_block(q1, w, h, LcParent{}, nullptr, guide);
  const CoefCodeword without = pc_encode_block(q2, w, h, LcParent{});
  std::vector<std::int32_t> out(w * h, 7);
  pc_decode_block(with.bytes, with.bits, w, h, LcParent{}, out.data(), w, guide);
  EXPECT_EQ(out, original);
  EXPECT_LT(double(with.bytes.size()), 0.95 * double(without.bytes.size()))
      << with.bytes.size() << " vs " << without.bytes.size();
}

TEST(PcCoder, ModelsMatchTheBlockCoderAtRate6AndAdaptFasterAt5) {
  std::mt19937 rng(14);
  BitModel reference;
  PcBit same, fast;
  fast.max_shift = 5;
  for (int k = 0; k < 2000; ++k) {
    const int bit = (rng() % 10) < (k < 1000 ? 1u : 7u) ? 1 : 0;  // P(1) 0.1, then 0.7
    reference.update(bit);
    same.update(bit);
    fast.update(bit);
    ASSERT_EQ(same.p0, reference.p0) << k;
    if (k == 1020) {
      EXPECT_LT(fast.p0, same.p0);  // 20 bits into the change, the fast one is further
    }
  }
}

TEST(PcCoder, RdoqIndicesDecodeExactlyAndStayNearTheCoefficients) {
  const std::size_t pw = 32, ph = 32, w = 64, h = 64;
  const auto parent = parent_band(pw, ph, 5.0, 7);
  const auto u = child_coefficients(parent, pw, w, h, 8);
  const LcParent lp = parent_of(parent, pw, ph);
  const PcRdoq rdoq{u, 0.1, 0.05};
  std::vector<std::int32_t> q(u.size());
  const CoefCodeword word = pc_encode_block(q, w, h, lp, &rdoq);
  EXPECT_EQ(decode(word, w, h, lp), q);  // the decoder sees the re-chosen indices
  std::size_t lowered = 0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    const auto nearest = std::int32_t(std::max(0.0, std::floor(std::fabs(double(u[k])) - 0.05 + 0.5)));
    const std::int32_t a = std::abs(q[k]);
    EXPECT_TRUE(a == nearest || a == nearest - 1 || a == 0) << k;
    if (a != 0) {
      EXPECT_EQ(q[k] < 0, u[k] < 0) << k;
    }
    lowered += a < nearest;
  }
  EXPECT_GT(lowered, 0u);  // lambda 0.1 does drop some
  // Fewer bytes than coding the nearest points themselves (what the RDOQ trades error for).
  std::vector<std::int32_t> nearest_q(u.size());
  for (std::size_t k = 0; k < u.size(); ++k) {
    const auto n = std::int32_t(std::max(0.0, std::floor(std::fabs(double(u[k])) - 0.05 + 0.5)));
    nearest_q[k] = u[k] < 0 ? -n : n;
  }
  EXPECT_LT(word.bytes.size(), pc_encode_block(nearest_q, w, h, lp).bytes.size());
}

TEST(PcCoder, RdoqNeighbourTermChargesIsolationAndCreditsCompany) {
  // 3 x 3 nearest points; the term of the centre (1, 1) looks at E, S (2 each), SW and SE (1).
  const PcRdoq rdoq{};
  std::vector<std::int32_t> q(9, 0);
  EXPECT_DOUBLE_EQ(pc_neighbour_bits(q, 3, 3, 1, 1, 0, rdoq), rdoq.neighbour_bits);  // all zero
  q[5] = 2;                                                                          // E non-zero
  EXPECT_DOUBLE_EQ(pc_neighbour_bits(q, 3, 3, 1, 1, 0, rdoq), rdoq.neighbour_bits / 3.0);
  q[6] = q[7] = -1;
  q[8] = 1;  // all four non-zero
  EXPECT_DOUBLE_EQ(pc_neighbour_bits(q, 3, 3, 1, 1, 0, rdoq), -rdoq.neighbour_bits);
  // Half at class `fade`; the last row and column have only zeros beyond the block.
  EXPECT_DOUBLE_EQ(pc_neighbour_bits(q, 3, 3, 1, 1, int(rdoq.neighbour_fade), rdoq),
                   -rdoq.neighbour_bits / 2);
  EXPECT_DOUBLE_EQ(pc_neighbour_bits(q, 3, 3, 2, 2, 0, rdoq), rdoq.neighbour_bits);
  // With the term switched off RDOQ is the plain greedy choice: an index the term would drop stays.
  PcModels m;
  EXPECT_EQ(pc_rdoq_index(m, PcCtx{}, 1.2f, 1, 0.1, 0.05, 0.0), 1);
  EXPECT_EQ(pc_rdoq_index(m, PcCtx{}, 1.2f, 1, 0.1, 0.05, 20.0), 0);  // 20 bits more for a 1
}

TEST(PcCoder, CorruptCodewordsFailCleanly) {
  const std::size_t pw = 16, ph = 16, w = 32, h = 32;
  const auto parent = parent_band(pw, ph, 5.0, 9);
  auto q = truncated(child_coefficients(parent, pw, w, h, 10));
  const LcParent lp = parent_of(parent, pw, ph);
  const CoefCodeword word = pc_encode_block(q, w, h, lp);
  std::mt19937 rng(11);
  std::vector<std::int32_t> out(w * h);
  int changed = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> bad = word.bytes;
    bad[rng() % bad.size()] ^= std::uint8_t(1u << (rng() % 8));
    try {  // a DecodeError, or indices within the index's bit length
      pc_decode_block(bad, word.bits, w, h, lp, out.data(), w);
      for (std::int32_t v : out) ASSERT_LT(std::abs(std::int64_t(v)), std::int64_t(1) << word.bits);
      changed += out != q;
    } catch (const DecodeError&) {
      ++changed;
    }
  }
  EXPECT_GT(changed, 100);  // the flips do reach the decoder
  EXPECT_THROW(pc_decode_block(word.bytes, 0, w, h, lp, out.data(), w), DecodeError);
  EXPECT_THROW(pc_decode_block({}, word.bits, w, h, lp, out.data(), w), DecodeError);
}

}  // namespace
}  // namespace pupwave

// Round trips of the adaptive binary range coder, including every truncation point.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>
#include <vector>

#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"

namespace pupwave {
namespace {

// Bits drawn with a per-position skew, coded in a few contexts.
struct Source {
  std::vector<int> bits;
  std::vector<int> context;
};

Source make_source(std::size_t n, double p1, unsigned seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution skewed(p1);
  std::uniform_int_distribution<int> ctx(0, 3);
  Source s;
  for (std::size_t i = 0; i < n; ++i) {
    const int c = ctx(rng);
    s.context.push_back(c);
    s.bits.push_back(c == 3 ? int(rng() & 1u) : int(skewed(rng)));
  }
  return s;
}

TEST(RangeCoder, RoundTripsSkewedAndUniformBits) {
  for (double p1 : {0.001, 0.05, 0.3, 0.5, 0.97}) {
    const Source s = make_source(20000, p1, 7);
    RangeEncoder enc;
    std::vector<BitModel> models(4);
    for (std::size_t i = 0; i < s.bits.size(); ++i) {
      if (s.context[i] == 2) {
        enc.encode_equiprobable(s.bits[i]);
      } else {
        enc.encode(s.bits[i], models[std::size_t(s.context[i])]);
      }
    }
    const auto bytes = enc.finish();
    RangeDecoder dec(bytes);
    std::vector<BitModel> dmodels(4);
    for (std::size_t i = 0; i < s.bits.size(); ++i) {
      const int bit =
          s.context[i] == 2 ? dec.decode_equiprobable() : dec.decode(dmodels[std::size_t(s.context[i])]);
      ASSERT_EQ(bit, s.bits[i]) << "p1=" << p1 << " bit " << i;
    }
  }
}

TEST(RangeCoder, CompressesSkewedBitsNearTheirEntropy) {
  RangeEncoder enc;
  BitModel model;
  std::mt19937 rng(3);
  std::bernoulli_distribution skewed(0.05);
  const std::size_t n = 100000;
  for (std::size_t i = 0; i < n; ++i) enc.encode(int(skewed(rng)), model);
  const double entropy_bits = 0.2864 * double(n);  // H(0.05) = 0.2864 bits
  // Adaptation noise costs a few percent on a stationary source; no coder beats entropy.
  const double coded_bits = double(enc.finish().size()) * 8.0;
  EXPECT_LT(coded_bits, entropy_bits * 1.10);
  EXPECT_GT(coded_bits, entropy_bits * 0.97);
}

TEST(RangeCoder, EveryTruncationPointDecodesItsPrefix) {
  const Source s = make_source(3000, 0.2, 11);
  RangeEncoder enc;
  std::vector<BitModel> models(4);
  std::vector<TruncationPoint> points;
  for (std::size_t i = 0; i < s.bits.size(); ++i) {
    enc.encode(s.bits[i], models[std::size_t(s.context[i])]);
    points.push_back(enc.truncation_point());
  }
  const auto stream = enc.finish();
  for (std::size_t k = 0; k < points.size(); k += 7) {
    const auto word = RangeEncoder::codeword(stream, points[k]);
    ASSERT_LE(points[k].size(), stream.size() + 1);
    RangeDecoder dec(word);
    std::vector<BitModel> dmodels(4);
    for (std::size_t i = 0; i <= k; ++i)
      ASSERT_EQ(dec.decode(dmodels[std::size_t(s.context[i])]), s.bits[i]) << "cut " << k << " bit " << i;
  }
}

TEST(RangeCoder, EmptyStreamIsEmpty) {
  RangeEncoder enc;
  EXPECT_TRUE(enc.finish().empty());
  BitModel m;
  enc.encode(0, m);
  EXPECT_LE(enc.finish().size(), 1u);
}

// The settled model adapts without clamping (bit_model.h): every probability the model can
// hold must stay inside [kMinP, one - kMinP] after either bit, and the first updates must
// follow the count-based schedule 1, 2, 2, 3, 3, 3, 3, 4, ... up to kMaxShift.
TEST(BitModel, SettledUpdatesStayInBoundsAndScheduleHolds) {
  for (std::uint32_t p = BitModel::kMinP; p <= kProbabilityOne - BitModel::kMinP; ++p)
    for (int bit : {0, 1}) {
      BitModel m{std::uint16_t(p)};
      for (int i = 0; i < 40; ++i) m.update(1 - bit);  // settle the count (p moves, stays legal)
      m.p0 = std::uint16_t(p);
      m.update(bit);
      const std::uint32_t expect =
          bit ? p - (p >> BitModel::kMaxShift) : p + ((kProbabilityOne - p) >> BitModel::kMaxShift);
      ASSERT_EQ(m.p0, expect) << "p0 " << p << " bit " << bit;
      ASSERT_GE(m.p0, BitModel::kMinP);
      ASSERT_LE(m.p0, kProbabilityOne - BitModel::kMinP);
    }
  BitModel m;
  std::uint32_t p = m.p0;
  for (int n = 0; n < 40; ++n) {
    const int shift = std::min(int(std::bit_width(unsigned(n) + 1u)), BitModel::kMaxShift);
    m.update(0);
    p = std::min<std::uint32_t>(p + ((kProbabilityOne - p) >> shift), kProbabilityOne - BitModel::kMinP);
    ASSERT_EQ(m.p0, p) << "update " << n;
  }
}

}  // namespace
}  // namespace pupwave

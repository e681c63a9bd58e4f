// The non-embedded coefficient coder (codec/entropy/coef_*): exact round trips of indices of
// every size and magnitude up to the coder's limit, its raw-bit range coding, its efficiency on a
// source of known entropy, and bounded decoding of corrupt codewords.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/coef_contexts.h"
#include "codec/entropy/coef_decoder.h"
#include "codec/entropy/coef_encoder.h"
#include "codec/entropy/range_decoder.h"
#include "codec/entropy/range_encoder.h"
#include "codec/error.h"

namespace pupwave {
namespace {

struct Indices {
  std::vector<std::uint32_t> magnitude;
  std::vector<std::uint8_t> negative;
};

std::size_t count(const Extent& s) { return s[0] * s[1] * s[2]; }

// Magnitudes of a smooth envelope times a geometric variable (as wavelet detail bands look),
// scaled by `scale`; random signs.
Indices structured(const Extent& size, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> noise(1.0);
  Indices d;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y)
      for (std::size_t x = 0; x < size[0]; ++x) {
        const double envelope = 1.0 + std::sin(0.3 * double(x)) * std::cos(0.2 * double(y + z));
        d.magnitude.push_back(std::uint32_t(std::min(scale * envelope * noise(rng), 1073741823.0)));
        d.negative.push_back(std::uint8_t(rng() & 1u));
      }
  return d;
}

// Any magnitude below 2^30 (each bit width equally likely), random signs.
Indices wide(const Extent& size, unsigned seed) {
  std::mt19937 rng(seed);
  Indices d;
  for (std::size_t i = 0; i < count(size); ++i) {
    const auto bits = unsigned(rng() % 31u);  // 0..30
    d.magnitude.push_back(bits == 0 ? 0u : std::uint32_t(rng()) & ((1u << bits) - 1u));
    d.negative.push_back(std::uint8_t(rng() & 1u));
  }
  return d;
}

void expect_round_trip(const Indices& d, const Extent& size) {
  const CoefCodeword w = encode_coefficients(d.magnitude, d.negative, size);
  std::uint32_t largest = 0;
  for (std::uint32_t q : d.magnitude) largest = std::max(largest, q);
  ASSERT_EQ(w.bits, int(std::bit_width(largest)));
  if (w.bits == 0) {
    EXPECT_TRUE(w.bytes.empty());
    return;
  }
  std::vector<std::int32_t> out(count(size), 12345);
  decode_coefficients(w.bytes, w.bits, size, out);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto q = std::int32_t(d.magnitude[i]);
    ASSERT_EQ(out[i], d.negative[i] && q != 0 ? -q : q) << "coefficient " << i;
  }
}

TEST(CoefCoder, RoundTripsStructuredIndicesOfEveryBlockShape) {
  for (const Extent& size :
       {Extent{1, 1, 1}, Extent{3, 5, 7}, Extent{17, 1, 4}, Extent{32, 32, 32}, Extent{1, 9, 2}})
    for (double scale : {0.3, 2.0, 40.0, 5000.0, 3e8})
      expect_round_trip(structured(size, scale, unsigned(scale) + 3), size);
}

TEST(CoefCoder, RoundTripsHugeMagnitudesUpToTheLimit) {
  for (const Extent& size : {Extent{1, 1, 1}, Extent{8, 8, 8}, Extent{31, 7, 3}})
    expect_round_trip(wide(size, 11), size);
  // Every magnitude at the limit, and a lone huge one among zeros (the escape after small contexts).
  Indices top{std::vector<std::uint32_t>(64, (1u << kCoefMaxBits) - 1u), std::vector<std::uint8_t>(64, 1)};
  expect_round_trip(top, {4, 4, 4});
  Indices lone{std::vector<std::uint32_t>(27, 0u), std::vector<std::uint8_t>(27, 0)};
  lone.magnitude[13] = (1u << kCoefMaxBits) - 1u;
  expect_round_trip(lone, {3, 3, 3});
}

TEST(CoefCoder, AllZeroBlocksCostNothing) {
  Indices zero{std::vector<std::uint32_t>(1000, 0u), std::vector<std::uint8_t>(1000, 1)};
  const CoefCodeword w = encode_coefficients(zero.magnitude, zero.negative, {10, 10, 10});
  EXPECT_EQ(w.bits, 0);
  EXPECT_TRUE(w.bytes.empty());
}

TEST(CoefCoder, RefusesIndicesBeyondTheLimitAndMismatchedSizes) {
  Indices d{{1u << kCoefMaxBits}, {0}};
  EXPECT_THROW(encode_coefficients(d.magnitude, d.negative, {1, 1, 1}), IndexRangeError);
  EXPECT_THROW(encode_coefficients(d.magnitude, d.negative, {2, 1, 1}), std::invalid_argument);
}

// Within 3% of the zeroth-order entropy of i.i.d. two-sided geometric indices: the coder's
// overhead (raw low bits, model learning) is small, and neighbour contexts cost nothing here.
TEST(CoefCoder, CodesAGeometricSourceNearItsEntropy) {
  const Extent size{32, 32, 32};
  std::mt19937 rng(5);
  std::geometric_distribution<std::uint32_t> geo(0.15);
  Indices d;
  std::map<std::int64_t, double> histogram;
  for (std::size_t i = 0; i < count(size); ++i) {
    d.magnitude.push_back(geo(rng));
    d.negative.push_back(std::uint8_t(rng() & 1u));
    histogram[d.negative.back() && d.magnitude.back() ? -std::int64_t(d.magnitude.back())
                                                      : d.magnitude.back()] += 1;
  }
  double entropy_bits = 0.0;
  for (const auto& [v, n] : histogram) entropy_bits -= n * std::log2(n / double(count(size)));
  const CoefCodeword w = encode_coefficients(d.magnitude, d.negative, size);
  EXPECT_LT(double(w.bytes.size()) * 8.0, 1.03 * entropy_bits);
  EXPECT_GT(double(w.bytes.size()) * 8.0, 0.97 * entropy_bits);
}

TEST(CoefCoder, CorruptCodewordsDecodeToBoundedIndices) {
  std::mt19937 rng(9);
  const Extent size{16, 8, 4};
  std::vector<std::int32_t> out(count(size));
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::uint8_t> bytes(rng() % 300);
    for (auto& b : bytes) b = std::uint8_t(rng());
    const int bits = 1 + int(rng() % kCoefMaxBits);
    decode_coefficients(bytes, bits, size, out);
    for (std::int32_t v : out) ASSERT_LT(std::abs(std::int64_t(v)), std::int64_t(1) << bits);
  }
  // A valid codeword cut short decodes too (zeros read past its end).
  const Indices d = structured(size, 100.0, 4);
  const CoefCodeword w = encode_coefficients(d.magnitude, d.negative, size);
  decode_coefficients(std::span(w.bytes).first(w.bytes.size() / 2), w.bits, size, out);
  EXPECT_THROW(decode_coefficients(w.bytes, 0, size, out), DecodeError);
  EXPECT_THROW(decode_coefficients(w.bytes, kCoefMaxBits + 1, size, out), DecodeError);
  std::vector<std::int32_t> small(3);
  EXPECT_THROW(decode_coefficients(w.bytes, w.bits, size, small), DecodeError);
}

TEST(CoefCoder, RawBitsInterleaveWithModelledBits) {
  std::mt19937 rng(3);
  std::vector<std::pair<std::uint32_t, int>> raw;
  std::vector<int> modelled;
  RangeEncoder enc;
  BitModel model;
  for (int i = 0; i < 5000; ++i) {
    const int n = 1 + int(rng() % 16u);
    raw.emplace_back(std::uint32_t(rng()) & ((1u << n) - 1u), n);
    modelled.push_back(rng() % 10u == 0 ? 1 : 0);
    enc.encode_raw(raw.back().first, n);
    enc.encode(modelled.back(), model);
  }
  const std::vector<std::uint8_t> bytes = enc.finish();
  RangeDecoder dec(bytes);
  BitModel decoded_model;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    ASSERT_EQ(dec.decode_raw(raw[i].second), raw[i].first) << i;
    ASSERT_EQ(dec.decode(decoded_model), modelled[i]) << i;
  }
}

}  // namespace
}  // namespace pupwave

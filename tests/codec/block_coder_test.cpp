// Round trips of the bit-plane block coder on random and structured coefficients, at every
// truncation point, in 2-D and 3-D blocks of odd sizes.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "codec/entropy/block_contexts.h"
#include "codec/entropy/block_decoder.h"
#include "codec/entropy/block_encoder.h"
#include "codec/entropy/block_tally.h"
#include "codec/entropy/ctx_priors.h"

namespace pupwave {
namespace {

struct Coefficients {
  std::vector<float> magnitude;
  std::vector<std::uint8_t> negative;
};

// Laplacian-like coefficients with a spatially varying scale, as in a detail band.
Coefficients make_coefficients(const Extent& size, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::exponential_distribution<double> mag(1.0);
  Coefficients c;
  const std::size_t n = size[0] * size[1] * size[2];
  for (std::size_t i = 0; i < n; ++i) {
    const double local = scale * (1.0 + std::sin(double(i % size[0]) * 0.3));
    const double v = (rng() % 3 == 0) ? 0.0 : mag(rng) * local;
    c.magnitude.push_back(float(v));
    c.negative.push_back(std::uint8_t(rng() & 1u));
  }
  return c;
}

// Checks that decoding n passes agrees with the encoder's model of what n passes convey:
// the decoded magnitude bits are a prefix of the true index bits, and the exact squared
// error of the reconstruction matches the encoder's distortion bookkeeping.
void check_all_truncations(const Coefficients& c, const Extent& size, unsigned orientation) {
  const double delta = 0.375;
  const EncodedBlock enc = encode_block(c.magnitude, c.negative, size, orientation, delta);
  ASSERT_EQ(enc.pass_count(), passes_for_planes(enc.planes));
  double remaining = enc.initial_distortion;
  for (int n = 0; n <= enc.pass_count(); ++n) {
    if (n > 0) remaining -= enc.distortion_drop[std::size_t(n - 1)];
    const auto word = enc.codeword(n);
    ASSERT_EQ(word.size(), enc.size(n));
    const DecodedBlock dec = decode_block(word, enc.planes, n, size, orientation);
    double err = 0.0;
    for (std::size_t i = 0; i < c.magnitude.size(); ++i) {
      const auto q = std::uint32_t(c.magnitude[i]);
      const std::uint32_t known = std::uint32_t(std::abs(dec.known[i]));
      if (dec.low_plane[i] != 255) {
        ASSERT_EQ(known, (q >> dec.low_plane[i]) << dec.low_plane[i]) << "pass " << n << " coef " << i;
        ASSERT_EQ(dec.known[i] < 0, c.negative[i] != 0);
      }
      if (n == enc.pass_count()) {
        ASSERT_EQ(known, q);
      }
      const double r = std::abs(reconstruct(dec, i, delta, false));
      err += (c.magnitude[i] - r) * (c.magnitude[i] - r);
    }
    ASSERT_NEAR(err, remaining, 1e-6 * enc.initial_distortion + 1e-6) << "pass " << n;
  }
}

TEST(BlockCoder, RoundTripsEveryTruncationPoint2D) {
  const Extent size{64, 64, 1};
  for (unsigned orientation : {0u, 1u, 2u, 3u})
    check_all_truncations(make_coefficients(size, 20.0, 5 + orientation), size, orientation);
}

TEST(BlockCoder, RoundTripsOddAndTinyShapes) {
  for (Extent size :
       {Extent{1, 1, 1}, Extent{1, 37, 1}, Extent{37, 1, 1}, Extent{13, 6, 1}, Extent{33, 17, 1}})
    check_all_truncations(make_coefficients(size, 50.0, 3), size, 3);
}

TEST(BlockCoder, RoundTrips3DBlocks) {
  for (Extent size : {Extent{16, 16, 16}, Extent{7, 5, 3}})
    check_all_truncations(make_coefficients(size, 8.0, 9), size, 5);
}

TEST(BlockCoder, AllZeroBlockCostsNothing) {
  const Extent size{32, 32, 1};
  const std::vector<float> zero(32 * 32, 0.4f);  // below one quantization step
  const std::vector<std::uint8_t> sign(32 * 32, 0);
  const EncodedBlock enc = encode_block(zero, sign, size, 0, 0.5);
  EXPECT_EQ(enc.planes, 0);
  EXPECT_EQ(enc.pass_count(), 0);
}

TEST(BlockCoder, LargeIndicesUpToTheLimitRoundTrip) {
  const Extent size{8, 8, 1};
  Coefficients c = make_coefficients(size, 1.0, 1);
  c.magnitude[5] = float((1u << kMaxBitPlanes) - 64);
  check_all_truncations(c, size, 0);
  c.magnitude[6] = float(1u << kMaxBitPlanes);
  EXPECT_THROW(encode_block(c.magnitude, c.negative, size, 0, 0.5), std::invalid_argument);
}

TEST(BlockCoder, StructuredDataCompressesBelowRawSize) {
  const Extent size{64, 64, 1};
  Coefficients c = make_coefficients(size, 4.0, 2);
  for (std::size_t i = 0; i < c.magnitude.size(); i += 2) c.magnitude[i] = 0.0f;  // sparse
  const EncodedBlock enc = encode_block(c.magnitude, c.negative, size, 1, 0.5);
  // Raw: planes bits per coefficient plus a sign bit.
  EXPECT_LT(double(enc.size(enc.pass_count())), 64.0 * 64.0 * (enc.planes + 1) / 8.0 * 0.7);
}

// Detail coefficients of real data: differences along x of the Gray-Scott field
// (testimages/gray_scott64.raw, 64^3 float32) over `size` from its corner, in steps of `step`.
Coefficients gray_scott_details(const Extent& size, double step) {
  std::ifstream in(PUPWAVE_TESTIMAGES_DIR "/gray_scott64.raw", std::ios::binary);
  std::vector<float> field(64 * 64 * 64);
  in.read(reinterpret_cast<char*>(field.data()), std::streamsize(field.size() * sizeof(float)));
  EXPECT_TRUE(in.good());
  Coefficients c;
  for (std::size_t z = 0; z < size[2]; ++z)
    for (std::size_t y = 0; y < size[1]; ++y)
      for (std::size_t x = 0; x < size[0]; ++x) {
        const std::size_t i = x + 64 * (y + 64 * z);
        const double d = (double(field[i + 1]) - double(field[i])) / step;
        c.magnitude.push_back(float(std::abs(d)));
        c.negative.push_back(d < 0 ? 1 : 0);
      }
  return c;
}

// The magnitude-class contexts and priors on real data: every truncation point decodes to
// what the encoder's distortion says, in 2-D and 3-D blocks, and the smooth field codes well
// below its raw size.
TEST(BlockCoder, RealDetailsRoundTripAndCompress) {
  for (const Extent size : {Extent{63, 64, 1}, Extent{31, 16, 16}}) {
    const Coefficients c = gray_scott_details(size, 1e-4);
    check_all_truncations(c, size, 1);
    const EncodedBlock enc = encode_block(c.magnitude, c.negative, size, 1, 0.5);
    const double raw = double(c.magnitude.size()) * (enc.planes + 1) / 8.0;
    EXPECT_LT(double(enc.size(enc.pass_count())), 0.7 * raw) << size[2];
  }
}

// A prior is a starting probability worth `count` bits: at count 7 the first update moves it
// by 1/16 of the way, not half of it; every trained prior is a usable probability.
TEST(BlockCoder, PriorModelsStartAtTheirPriorWithWeight) {
  BitModel m = prior_model(64, 7);  // P(1) = 1/4
  EXPECT_EQ(m.p0, kProbabilityOne * 3 / 4);
  m.update(1);
  EXPECT_EQ(m.p0, kProbabilityOne * 3 / 4 - (kProbabilityOne * 3 / 4 >> 4));
  BitModel fresh = prior_model(64, 0);  // worth nothing: the first bit moves it half way
  fresh.update(1);
  EXPECT_EQ(fresh.p0, kProbabilityOne * 3 / 8);
  for (std::size_t c = 0; c < kContextPriors.size(); ++c)
    for (std::size_t k = 0; k < kContextPriors[c].size(); ++k) {
      const BitModel p = prior_model(kContextPriors[c][k], kContextPriorCounts[c][k]);
      EXPECT_GT(p.p0, BitModel::kMinP);
      EXPECT_LT(p.p0, kProbabilityOne - BitModel::kMinP);
    }
}

// Prior training (tools/train/train_priors.cpp) keeps, per block and context, the first
// kTallyWindow bits coded, in the block's band class, in the tally the caller passes (none by
// default), from the tracked and the whole-codeword encoder alike, without changing the
// codeword: a block of all-ones magnitudes codes one run bit, a 1 (the next columns have
// significant neighbours).
TEST(BlockCoder, TallyKeepsTheFirstBitsOfEachContextOfTheBlocksPassedIt) {
  const Extent size{64, 64, 1};
  const Coefficients c = make_coefficients(size, 6.0, 4);
  ContextTally tally;
  const EncodedBlock plain = encode_block(c.magnitude, c.negative, size, 3, 0.5);         // not kept
  const EncodedBlock kept = encode_block(c.magnitude, c.negative, size, 3, 0.5, &tally);  // class 2
  const WholeBlock whole = encode_block_whole(c.magnitude, c.negative, size, 3, 0.5, &tally);
  EXPECT_EQ(kept.committed, plain.committed);
  EXPECT_EQ(whole.codeword, plain.codeword(plain.pass_count()));
  EXPECT_EQ(tally.blocks, 2u);
  std::size_t contexts_seen = 0;
  for (std::size_t k = 0; k < std::size_t(kBlockContexts); ++k) {
    EXPECT_TRUE(tally.starts[0][k].empty() && tally.starts[1][k].empty());
    for (const auto& [key, blocks] : tally.starts[2][k]) {
      EXPECT_EQ(blocks, 2u);  // the same block twice
      EXPECT_GE(tally_length(key), 1u);
      EXPECT_LE(tally_length(key), unsigned(kTallyWindow));
      EXPECT_EQ(std::uint64_t(tally_bits(key)) >> tally_length(key), 0u);
    }
    contexts_seen += tally.starts[2][k].size();
  }
  EXPECT_GE(contexts_seen, 8u);  // significance, sign and refinement contexts

  ContextTally ones;
  const std::vector<float> one(64 * 64, 1.0f);
  const std::vector<std::uint8_t> positive(64 * 64, 0);
  encode_block(one, positive, size, 0, 0.5, &ones);
  EXPECT_EQ(ones.blocks, 1u);
  ASSERT_EQ(ones.starts[0][kRunContext].size(), 1u);
  EXPECT_EQ(ones.starts[0][kRunContext].begin()->first, tally_key(1, 1));
}

// Blocks coded on several threads at once into one tally are each counted once: the tally of
// 4 x 25 codings of one block holds each of its context starts 100 times.
TEST(BlockCoder, TallyCountsBlocksCodedOnSeveralThreadsAtOnce) {
  const Extent size{64, 64, 1};
  const Coefficients c = make_coefficients(size, 6.0, 7);
  ContextTally once, shared;
  encode_block(c.magnitude, c.negative, size, 1, 0.5, &once);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int n = 0; n < 25; ++n) encode_block(c.magnitude, c.negative, size, 1, 0.5, &shared);
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(shared.blocks, 100u);
  for (std::size_t k = 0; k < std::size_t(kBlockContexts); ++k) {
    ASSERT_EQ(shared.starts[1][k].size(), once.starts[1][k].size());
    for (const auto& [key, blocks] : once.starts[1][k]) EXPECT_EQ(shared.starts[1][k][key], 100 * blocks);
  }
}

TEST(BlockCoder, GarbageCodewordsDecodeWithoutFault) {
  std::mt19937 rng(17);
  const Extent size{64, 64, 1};
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint8_t> junk(std::size_t(rng() % 3000));
    for (auto& b : junk) b = std::uint8_t(rng());
    const int planes = int(rng() % (kMaxBitPlanes + 1));
    const unsigned orientation = rng() % 4;
    const DecodedBlock dec = decode_block(junk, planes, passes_for_planes(planes), size, orientation);
    ASSERT_EQ(dec.known.size(), size[0] * size[1]);
    ASSERT_EQ(dec.low_plane.size(), size[0] * size[1]);
    // Whatever the bytes, the result is a valid partial decode of a block of `planes` planes:
    // magnitudes below 2^planes, insignificant samples zero, last planes in range.
    const std::int64_t limit = std::int64_t(1) << planes;
    for (std::size_t i = 0; i < dec.known.size(); ++i) {
      const std::int64_t v = dec.known[i];
      if (dec.low_plane[i] == 255) {
        ASSERT_EQ(v, 0) << "trial " << trial << " sample " << i;
        continue;
      }
      ASSERT_LT(int(dec.low_plane[i]), planes) << "trial " << trial;
      ASSERT_LT(v < 0 ? -v : v, limit) << "trial " << trial;
      ASSERT_EQ((v < 0 ? -v : v) % (std::int64_t(1) << dec.low_plane[i]), 0) << "bits below the last plane";
      ASSERT_TRUE(std::isfinite(reconstruct(dec, i, 0.375, false)));
    }
    // Decoding is a pure function of the bytes.
    const DecodedBlock again = decode_block(junk, planes, passes_for_planes(planes), size, orientation);
    EXPECT_EQ(again.known, dec.known);
    EXPECT_EQ(again.low_plane, dec.low_plane);
  }
}

}  // namespace
}  // namespace pupwave

// The high-throughput block coder (`--entropy ht`): block round trips over sizes and magnitude
// ranges, hostile codewords, and image encodes at every rate mode, thread counts and levels.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/entropy/block_encoder.h"
#include "codec/entropy/ht_blocks.h"
#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_stream.h"
#include "test_images.h"
#include "thread_independence.h"
#include "transforms/executor.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

using testing::expect_thread_independent;
using testing::synthetic_image;

// Laplacian-like indices of scale `scale` with a share `zeros` of forced zeros.
std::vector<std::int32_t> random_indices(std::mt19937& rng, std::size_t n, double scale, double zeros) {
  std::vector<std::int32_t> q(n);
  std::exponential_distribution<double> magnitude(1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (auto& v : q) {
    const auto m = std::int32_t(std::min(magnitude(rng) * scale, 1e9));
    v = u(rng) < zeros ? 0 : (rng() & 1u) ? -m : m;
  }
  return q;
}

TEST(HtCoder, BlocksRoundTripAtEverySizeAndScale) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3000; ++trial) {
    const std::size_t w = 1 + rng() % 64, h = 1 + rng() % 64;
    const double scale = std::exp2(double(rng() % 300) / 10.0 - 6.0);
    const auto q = random_indices(rng, w * h, scale, double(rng() % 100) / 100.0);
    const HtCodeword c = ht_encode_block(q, w, h);
    std::int32_t largest = 0;
    for (std::int32_t v : q) largest = std::max(largest, std::abs(v));
    ASSERT_EQ(c.planes, int(std::bit_width(std::uint32_t(largest))));
    if (c.planes == 0) {
      EXPECT_TRUE(c.bytes.empty());
      continue;
    }
    std::vector<std::int32_t> out(w * h, 7);
    ht_decode_block(c.bytes, w, h, c.planes, out.data());
    ASSERT_EQ(out, q) << w << "x" << h << " scale " << scale;
  }
}

TEST(HtCoder, ZeroBlocksAreCheapAndLargeIndicesAreRefused) {
  std::vector<std::int32_t> q(64 * 64, 0);
  EXPECT_EQ(ht_encode_block(q, 64, 64).planes, 0);
  q[4000] = -1;  // one nonzero after long runs: a few bytes
  const HtCodeword one = ht_encode_block(q, 64, 64);
  EXPECT_EQ(one.planes, 1);
  EXPECT_LT(one.bytes.size(), 24u);
  q[5] = 1 << 30;
  EXPECT_THROW(ht_encode_block(q, 64, 64), IndexRangeError);
  q[5] = (1 << 30) - 1;  // the largest the coder takes
  const HtCodeword top = ht_encode_block(q, 64, 64);
  std::vector<std::int32_t> out(q.size());
  ht_decode_block(top.bytes, 64, 64, top.planes, out.data());
  EXPECT_EQ(out, q);
}

TEST(HtCoder, CorruptCodewordsAreRejectedNeverOverrun) {
  std::mt19937 rng(12);
  int rejected = 0, flips = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t w = 1 + rng() % 64, h = 1 + rng() % 64;
    const auto q = random_indices(rng, w * h, std::exp2(double(rng() % 80) / 10.0), 0.5);
    const HtCodeword c = ht_encode_block(q, w, h);
    if (c.planes == 0) continue;
    std::vector<std::int32_t> out(w * h);
    // Every truncation, a byte more, and a wrong bit-plane count are errors.
    for (std::size_t cut = 0; cut < c.bytes.size(); cut += 1 + cut / 8) {
      const std::vector<std::uint8_t> head(c.bytes.begin(), c.bytes.begin() + std::ptrdiff_t(cut));
      EXPECT_THROW(ht_decode_block(head, w, h, c.planes, out.data()), DecodeError) << cut;
    }
    auto longer = c.bytes;
    longer.push_back(0);
    EXPECT_THROW(ht_decode_block(longer, w, h, c.planes, out.data()), DecodeError);
    EXPECT_THROW(ht_decode_block(c.bytes, w, h, c.planes + 1, out.data()), DecodeError);
    if (c.planes > 1) {
      EXPECT_THROW(ht_decode_block(c.bytes, w, h, c.planes - 1, out.data()), DecodeError);
    }
    // A flipped bit decodes to other indices or is rejected; it never reads out of bounds.
    auto bad = c.bytes;
    bad[rng() % bad.size()] ^= std::uint8_t(1u << (rng() % 8));
    ++flips;
    try {
      ht_decode_block(bad, w, h, c.planes, out.data());
    } catch (const DecodeError&) {
      ++rejected;
    }
  }
  EXPECT_GT(rejected, flips / 2);  // most corruptions are caught by the length and plane checks
}

EncodeOptions ht_options(RateMode mode, double target, std::string transform = "cdf97") {
  EncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = std::move(transform);
  o.entropy = EntropyCoder::ht;
  return o;
}

double psnr_of(const Image& a, const Image& b) { return compare_images(a, b).overall.psnr; }

TEST(HtCoder, ImagesRoundTripAtEveryRateMode) {
  for (std::size_t channels : {1u, 3u}) {
    const Image img = synthetic_image(203, 150, channels, SampleType::u8, 3);
    const double pixels = double(img.plane_size());
    for (double bpp : {0.25, 1.0, 2.0}) {
      const EncodeResult r = encode_image(img, ht_options(RateMode::bpp, bpp));
      EXPECT_EQ(parse_container(r.bytes).header.entropy, EntropyCoder::ht);
      const double got = double(r.bytes.size()) * 8.0 / pixels;
      EXPECT_LE(got, bpp);
      EXPECT_GE(got, 0.98 * bpp) << "target " << bpp;
      EXPECT_NEAR(psnr_of(img, decode_image(r.bytes)), r.psnr, 1e-9);
    }
    for (double target : {32.0, 40.0}) {
      const EncodeResult r = encode_image(img, ht_options(RateMode::psnr, target));
      const double psnr = psnr_of(img, decode_image(r.bytes));
      EXPECT_GE(psnr, target);
      EXPECT_LE(psnr, target + 0.5);
    }
    const EncodeResult fine = encode_image(img, ht_options(RateMode::step, 0.5));
    const EncodeResult coarse = encode_image(img, ht_options(RateMode::step, 8.0));
    EXPECT_GT(psnr_of(img, decode_image(fine.bytes)), psnr_of(img, decode_image(coarse.bytes)) + 10.0);
    EXPECT_GT(fine.bytes.size(), coarse.bytes.size());
  }
}

TEST(HtCoder, FloatAndSixteenBitImagesRoundTrip) {
  for (SampleType type : {SampleType::u16, SampleType::f32}) {
    const Image img = synthetic_image(120, 90, 3, type, 4);
    const EncodeResult r = encode_image(img, ht_options(RateMode::bpp, 2.0));
    EXPECT_LE(double(r.bytes.size()) * 8.0 / double(img.plane_size()), 2.0);
    const Image out = decode_image(r.bytes);
    ASSERT_EQ(out.type, type);
    ASSERT_EQ(out.samples.size(), img.samples.size());
    // Float images are coded in the log domain (transfer.h): compare with the bit-plane coder.
    EncodeOptions e = ht_options(RateMode::bpp, 2.0);
    e.entropy = EntropyCoder::ebcot;
    const double ebcot = psnr_of(img, decode_image(encode_image(img, e).bytes));
    EXPECT_GT(psnr_of(img, out), ebcot - 3.0) << to_string(type) << " ebcot " << ebcot;
    EXPECT_GT(psnr_of(img, out), 25.0) << to_string(type);
  }
}

TEST(HtCoder, LosslessIsBitExact) {
  for (SampleType type : {SampleType::u8, SampleType::u16})
    for (std::size_t channels : {1u, 3u, 4u})
      for (auto [w, h] : {std::pair<std::size_t, std::size_t>{77, 53}, {1, 17}, {1, 1}, {130, 2}}) {
        const Image img = synthetic_image(w, h, channels, type, 9);
        const auto bytes = encode_image(img, ht_options(RateMode::lossless, 0.0, "cdf53")).bytes;
        ASSERT_EQ(decode_image(bytes).samples, img.samples) << to_string(type) << " " << w << "x" << h;
      }
}

TEST(HtCoder, OutputDoesNotDependOnThreadCount) {
  const Image img = synthetic_image(300, 200, 3, SampleType::u8, 7);
  for (RateMode mode : {RateMode::bpp, RateMode::psnr})
    expect_thread_independent(img, ht_options(mode, mode == RateMode::bpp ? 1.0 : 36.0));
}

// Images of 2048 rows or more are surveyed by stripes before their one streamed coding pass;
// the whole-image path (strip_encode off) searches the step with every component held.
TEST(HtCoder, TallImagesMeetBudgetsFromBelowOnEitherPath) {
  const Image img = synthetic_image(96, 2304, 3, SampleType::u8, 5);
  const double pixels = double(img.plane_size());
  for (double bpp : {0.5, 2.0}) {
    EncodeOptions streamed = ht_options(RateMode::bpp, bpp), held = streamed;
    held.strip_encode = false;
    const EncodeResult a = encode_image(img, streamed), b = encode_image(img, held);
    for (const EncodeResult* r : {&a, &b}) {
      const double got = double(r->bytes.size()) * 8.0 / pixels;
      EXPECT_LE(got, bpp);
      EXPECT_GE(got, 0.98 * bpp) << "target " << bpp << (r == &a ? " streamed" : " held");
      EXPECT_NEAR(psnr_of(img, decode_image(r->bytes)), r->psnr, 1e-9);
    }
    EXPECT_GT(a.psnr, b.psnr - 0.1) << "target " << bpp;  // per-band steps lose nothing
  }
  expect_thread_independent(img, ht_options(RateMode::bpp, 1.0));
}

// The lossless attempt against a budget gives up early only when the stream cannot fit:
// a budget the lossless stream fits still gets it.
TEST(HtCoder, LosslessWinsWhereItFits) {
  const Image img = synthetic_image(96, 2304, 1, SampleType::u8, 5);
  const std::size_t lossless = encode_image(img, ht_options(RateMode::lossless, 0.0, "cdf53")).bytes.size();
  const double bpp = double(lossless) * 8.0 / double(img.plane_size()) * 1.01;
  const EncodeResult r = encode_image(img, ht_options(RateMode::bpp, bpp));
  EXPECT_TRUE(r.switched_to_lossless);
  EXPECT_EQ(decode_image(r.bytes).samples, img.samples);
}

TEST(HtCoder, ReducedLevelsDecodeFromAPrefix) {
  const Image img = synthetic_image(240, 176, 3, SampleType::u8, 6);
  for (RateMode mode : {RateMode::bpp, RateMode::lossless}) {
    const auto bytes =
        encode_image(img, ht_options(mode, 2.0, mode == RateMode::lossless ? "cdf53" : "cdf97")).bytes;
    const ParsedStream s = parse_container(bytes);
    for (int k = 1; k <= 3; ++k) {
      const Image low = decode_image(bytes, k);
      const Extent e = level_extent({img.width, img.height, 1}, k);
      ASSERT_EQ(low.width, e[0]);
      ASSERT_EQ(low.height, e[1]);
      std::size_t needed = bytes.size();
      for (int r = s.header.levels; r > s.header.levels - k; --r)
        needed -= s.resolution_data[std::size_t(r)].size() + 12;
      const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(needed));
      EXPECT_EQ(decode_image(cut, k).samples, low.samples) << "level " << k;
      EXPECT_THROW(decode_image(cut, 0), DecodeError);
      // Lossless streams hold the same coefficients whatever the coder: equal at every level.
      if (mode == RateMode::lossless) {
        EncodeOptions o = ht_options(mode, 0.0, "cdf53");
        o.entropy = EntropyCoder::ebcot;
        EXPECT_EQ(decode_image(encode_image(img, o).bytes, k).samples, low.samples) << "level " << k;
      }
    }
  }
}

}  // namespace
}  // namespace pupwave

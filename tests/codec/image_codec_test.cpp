// Image codec round trips: channel layouts x sample types x rate modes, odd sizes, lossless
// bit-exactness, rate and PSNR targets, reduced-resolution decoding, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_stream.h"
#include "codec/image/transfer.h"
#include "test_images.h"
#include "thread_independence.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

using testing::expect_thread_independent;
using testing::synthetic_image;

double psnr_of(const Image& a, const Image& b) { return compare_images(a, b).overall.psnr; }

EncodeOptions options(RateMode mode, double target, std::string transform = "cdf97") {
  EncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = std::move(transform);
  return o;
}

class LayoutsAndTypes : public ::testing::TestWithParam<std::tuple<std::size_t, SampleType>> {};

TEST_P(LayoutsAndTypes, RoundTripsAtSeveralRates) {
  const auto [channels, type] = GetParam();
  const Image img = synthetic_image(97, 75, channels, type);
  double previous_psnr = 0.0, linear_psnr = 0.0;
  for (double bpp : {0.5, 1.5, 4.0}) {
    const EncodeResult r = encode_image(img, options(RateMode::bpp, bpp));
    const Image out = decode_image(r.bytes);
    ASSERT_EQ(out.width, img.width);
    ASSERT_EQ(out.height, img.height);
    ASSERT_EQ(out.channels, img.channels);
    ASSERT_EQ(out.type, img.type);
    // Float images report log-PSNR (codec/image/transfer.h); equal up to float rounding of the transfer.
    const double psnr = is_integer(type) ? psnr_of(img, out) : transfer_psnr(img, out, Transfer::log2);
    EXPECT_NEAR(psnr, r.psnr,
                is_integer(type) ? 1e-9 : 1e-3);  // the encoder's report is the decoder's result
    EXPECT_LE(double(r.bytes.size()) * 8.0 / double(img.plane_size()), bpp);
    EXPECT_GT(psnr, previous_psnr) << "bpp " << bpp;
    previous_psnr = psnr;
    linear_psnr = psnr_of(img, out);
  }
  EXPECT_GT(linear_psnr, 30.0);
}

INSTANTIATE_TEST_SUITE_P(ImageCodec, LayoutsAndTypes,
                         ::testing::Combine(::testing::Values(1u, 2u, 3u, 4u),
                                            ::testing::Values(SampleType::u8, SampleType::u16,
                                                              SampleType::f16, SampleType::f32)));

TEST(ImageCodec, OddAndDegenerateSizesRoundTrip) {
  for (auto [w, h] : {std::pair<std::size_t, std::size_t>{333, 517}, {1, 1000}, {1000, 1}, {1, 1}, {2, 3}}) {
    const Image img = synthetic_image(w, h, 3, SampleType::u8, 4);
    const EncodeResult r = encode_image(img, options(RateMode::step, 1.0));
    const Image out = decode_image(r.bytes);
    ASSERT_EQ(out.width, w);
    ASSERT_EQ(out.height, h);
    EXPECT_GT(psnr_of(img, out), 40.0) << w << "x" << h;
  }
}

TEST(ImageCodec, LosslessIsBitExact) {
  for (SampleType type : {SampleType::u8, SampleType::u16})
    for (std::size_t channels : {1u, 3u, 4u})
      for (auto [w, h] : {std::pair<std::size_t, std::size_t>{77, 53}, {1, 17}, {1, 1}}) {
        const Image img = synthetic_image(w, h, channels, type, 9);
        const Image out = decode_image(encode_image(img, options(RateMode::lossless, 0.0, "cdf53")).bytes);
        ASSERT_EQ(out.samples, img.samples) << to_string(type) << " c=" << channels << " " << w << "x" << h;
      }
}

// A byte budget the lossless stream fits gets it, on images large enough (2048 blocks and up)
// that the encoder estimates the lossless size from a sample of blocks before its exact trial
// (image_encoder.cpp, lossless_clearly_over): the estimate must not drop a stream that fits,
// also where the sample could mislead (the top half flat, every byte in the lower half).
TEST(ImageCodec, LosslessWinsWhereItFitsOnALargeImage) {
  for (bool half_flat : {false, true}) {
    Image img = synthetic_image(1536, 1536, 1, SampleType::u8, 7);
    if (half_flat)
      for (std::size_t y = 0; y < img.height / 2; ++y)
        for (std::size_t x = 0; x < img.width; ++x) img.at(0, x, y) = 100.0f;
    EncodeOptions o = options(RateMode::lossless, 0.0, "cdf53");
    o.block_size = {32, 32, 1};  // 1536^2 in 32^2 blocks: 2300 blocks, so the estimate runs
    const std::size_t lossless = encode_image(img, o).bytes.size();
    const double pixels = double(img.plane_size());
    o.transform = "cdf97";
    o.mode = RateMode::bpp;
    o.target = (double(lossless) + 0.5) * 8.0 / pixels;  // a budget of exactly the lossless size
    const EncodeResult fits = encode_image(img, o);
    EXPECT_TRUE(fits.switched_to_lossless) << "half flat " << half_flat;
    EXPECT_EQ(fits.bytes.size(), lossless);
    EXPECT_EQ(decode_image(fits.bytes).samples, img.samples);
    for (double fraction : {0.99, 0.5}) {  // just under (exact trial) and far under (the estimate)
      o.target = double(lossless) * fraction * 8.0 / pixels;
      const EncodeResult over = encode_image(img, o);
      EXPECT_FALSE(over.switched_to_lossless) << "half flat " << half_flat << " fraction " << fraction;
      EXPECT_LE(double(over.bytes.size()) * 8.0 / pixels, o.target);
    }
  }
}

TEST(ImageCodec, LosslessRejectsFloatAndIrreversibleTransforms) {
  const Image f = synthetic_image(16, 16, 1, SampleType::f32);
  EXPECT_THROW(encode_image(f, options(RateMode::lossless, 0.0, "cdf53")), std::invalid_argument);
  const Image u = synthetic_image(16, 16, 1, SampleType::u8);
  EXPECT_THROW(encode_image(u, options(RateMode::lossless, 0.0, "cdf97")), std::invalid_argument);
  EXPECT_THROW(encode_image(u, options(RateMode::bpp, 1.0, "no-such-transform")), std::invalid_argument);
  EXPECT_THROW(encode_image(u, options(RateMode::bpp, -1.0)), std::invalid_argument);
}

TEST(ImageCodec, BppTargetIsMetFromBelowWithinOnePercent) {
  const Image img = synthetic_image(256, 192, 3, SampleType::u8, 2);
  for (double bpp : {0.25, 1.0, 2.0}) {
    const EncodeResult r = encode_image(img, options(RateMode::bpp, bpp));
    const double achieved = double(r.bytes.size()) * 8.0 / double(img.plane_size());
    EXPECT_LE(achieved, bpp);
    EXPECT_GE(achieved, 0.99 * bpp) << "target " << bpp;
  }
}

TEST(ImageCodec, PsnrTargetIsMet) {
  const Image img = synthetic_image(200, 150, 3, SampleType::u8, 3);
  for (double target : {30.0, 38.0, 45.0}) {
    const EncodeResult r = encode_image(img, options(RateMode::psnr, target));
    const double psnr = psnr_of(img, decode_image(r.bytes));
    EXPECT_GE(psnr, target - 0.1);
    EXPECT_LE(psnr, target + 1.0);  // not wastefully above it
  }
}

// Mean of each 2^k x 2^k box: what a reduced-resolution image should resemble.
Image box_downsample(const Image& img, int k) {
  const Extent e = level_extent({img.width, img.height, 1}, k);
  Image out(e[0], e[1], img.channels, img.type);
  const std::size_t f = std::size_t(1) << k;
  for (std::size_t c = 0; c < img.channels; ++c)
    for (std::size_t y = 0; y < e[1]; ++y)
      for (std::size_t x = 0; x < e[0]; ++x) {
        double sum = 0.0;
        std::size_t n = 0;
        for (std::size_t j = y * f; j < std::min(img.height, (y + 1) * f); ++j)
          for (std::size_t i = x * f; i < std::min(img.width, (x + 1) * f); ++i, ++n) sum += img.at(c, i, j);
        out.at(c, x, y) = float(std::round(sum / double(n)));
      }
  return out;
}

TEST(ImageCodec, ReducedResolutionDecodingReadsOnlyWhatItNeeds) {
  const Image img = synthetic_image(240, 176, 3, SampleType::u8, 6);
  for (RateMode mode : {RateMode::step, RateMode::lossless}) {
    EncodeOptions o = options(mode, 0.5, mode == RateMode::lossless ? "cdf53" : "cdf97");
    const auto bytes = encode_image(img, o).bytes;
    const ParsedStream s = parse_container(bytes);
    for (int k = 1; k <= 3; ++k) {
      const Image low = decode_image(bytes, k);
      const Extent e = level_extent({img.width, img.height, 1}, k);
      ASSERT_EQ(low.width, e[0]);
      ASSERT_EQ(low.height, e[1]);
      EXPECT_GT(psnr_of(box_downsample(img, k), low), 24.0) << "level " << k;
      // Cutting the file after the DATA chunks this level needs must not change the result.
      std::size_t needed = bytes.size();
      for (int r = s.header.levels; r > s.header.levels - k; --r)
        needed -= s.resolution_data[std::size_t(r)].size() + 12;
      const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(needed));
      EXPECT_EQ(decode_image(cut, k).samples, low.samples);
      EXPECT_THROW(decode_image(cut, 0), DecodeError);
    }
    EXPECT_THROW(decode_image(bytes, s.header.levels + 1), std::invalid_argument);
  }
}

TEST(ImageCodec, OutputDoesNotDependOnThreadCount) {
  const Image img = synthetic_image(300, 200, 3, SampleType::u8, 7);
  expect_thread_independent(img, options(RateMode::bpp, 1.0));
}

TEST(ImageCodec, OtherTransformsRoundTrip) {
  const Image img = synthetic_image(90, 70, 1, SampleType::u8, 8);
  for (const char* spec : {"cdf53", "cdf97"}) {
    const EncodeResult r = encode_image(img, options(RateMode::bpp, 2.0, spec));
    EXPECT_GT(psnr_of(img, decode_image(r.bytes)), 30.0) << spec;
  }
}

}  // namespace
}  // namespace pupwave

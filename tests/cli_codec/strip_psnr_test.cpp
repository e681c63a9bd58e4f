// The encoder's PSNR check decoded by strips (strip_psnr, codec/image/image_strips.h) gives the
// figure of the whole-plane decode (full_planes_psnr) on the test photographs: integer and
// float images, lossy and lossless, the bit-plane and ht coders, images narrower and wider
// than its column tiles; lc and pc streams are left to the whole-plane route.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "cli_codec/photo_crops.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_plan.h"
#include "codec/image/image_strips.h"
#include "codec/image/transfer.h"

namespace pupwave {
namespace {

using test::photo;

// The stream of `image` coded with `entropy` at `mode`/`target`, without the encoder's own check.
std::vector<std::uint8_t> encode(const ImageView& image, EntropyCoder entropy, RateMode mode, double target,
                                 const std::string& transform = "cdf97") {
  EncodeOptions o;
  o.entropy = entropy;
  o.mode = mode;
  o.target = target;
  o.transform = transform;
  o.measure_psnr = false;
  return encode_image(image, o).bytes;
}

// strip_psnr equals full_planes_psnr (to the order of the additions) and measure_psnr takes it.
void expect_strip_psnr_matches(const ImageView& reference, const std::vector<std::uint8_t>& bytes,
                               const std::string& what) {
  const ParsedStream s = parse_container(bytes, 0, DecodeLimits{SIZE_MAX});
  const double full = full_planes_psnr(reference, s, default_executor());
  const auto strips = strip_psnr(reference, s, default_executor());
  ASSERT_TRUE(strips.has_value()) << what;
  if (std::isinf(full))
    EXPECT_EQ(*strips, full) << what;
  else
    EXPECT_NEAR(*strips, full, 1e-9 * std::abs(full)) << what;
  EXPECT_EQ(measure_psnr(reference, bytes, default_executor()), *strips) << what;
  // Serial and parallel strips decode the same samples.
  EXPECT_EQ(*strip_psnr(reference, s, serial_executor()), *strips) << what;
}

TEST(StripPsnr, IntegerPhotographsEveryBlockCoder) {
  for (const char* name : {"astronaut.png", "camera.png", "coffee.png", "chelsea.png"}) {
    const Image image = photo(name);
    const ImageView view = view_of(image);
    for (EntropyCoder coder : {EntropyCoder::ebcot, EntropyCoder::ht}) {
      const std::string what = std::string(name) + " " + to_string(coder);
      const auto bytes = encode(view, coder, RateMode::bpp, 1.0);
      expect_strip_psnr_matches(view, bytes, what + " 1 bpp");
      // The figure is that of the decoded image: decode_image and compare_images agree.
      EXPECT_NEAR(measure_psnr(view, bytes, default_executor()),
                  compare_images(image, decode_image(bytes)).overall.psnr, 1e-9 * 40.0)
          << what;
      expect_strip_psnr_matches(view, encode(view, coder, RateMode::step, 8.0, "cdf53"),
                                what + " cdf53 step 8");
      expect_strip_psnr_matches(view, encode(view, coder, RateMode::lossless, 0.0, "cdf53"),
                                what + " lossless");
    }
  }
}

// Four photographs side by side, the second and fourth mirrored (so no seam is flat), cropped
// to `width` columns: wider than the check's column tiles, so it decodes in several of them.
Image wide_photograph(std::size_t width) {
  const Image a = photo("astronaut.png");
  Image wide(width, a.height, a.channels, a.type);
  for (std::size_t c = 0; c < a.channels; ++c)
    for (std::size_t y = 0; y < a.height; ++y)
      for (std::size_t x = 0; x < width; ++x) {
        const std::size_t tile = x / a.width, u = x % a.width;
        wide.plane(c)[y * width + x] = a.plane(c)[y * a.width + (tile % 2 ? a.width - 1 - u : u)];
      }
  return wide;
}

TEST(StripPsnr, WideImagesInColumnTiles) {
  for (std::size_t width : {std::size_t(1100), std::size_t(2047)}) {
    const Image image = wide_photograph(width);
    const ImageView view = view_of(image);
    const std::string what = std::to_string(width) + " columns";
    for (EntropyCoder coder : {EntropyCoder::ebcot, EntropyCoder::ht}) {
      const auto bytes = encode(view, coder, RateMode::bpp, 0.5);
      expect_strip_psnr_matches(view, bytes, what + " " + to_string(coder));
      EXPECT_NEAR(measure_psnr(view, bytes, default_executor()),
                  compare_images(image, decode_image(bytes)).overall.psnr, 1e-9 * 40.0)
          << what;
    }
    expect_strip_psnr_matches(view, encode(view, EntropyCoder::ebcot, RateMode::step, 8.0, "cdf53"),
                              what + " cdf53 step 8");
    expect_strip_psnr_matches(view, encode(view, EntropyCoder::ebcot, RateMode::lossless, 0.0, "cdf53"),
                              what + " lossless");
  }
}

TEST(StripPsnr, SixteenBitPhotograph) {
  Image image = photo("astronaut.png");
  image.type = SampleType::u16;
  for (float& v : image.samples) v *= 257.0f;  // 0..255 -> 0..65535
  const ImageView view = view_of(image);
  expect_strip_psnr_matches(view, encode(view, EntropyCoder::ebcot, RateMode::bpp, 2.0), "u16 ebcot");
  expect_strip_psnr_matches(view, encode(view, EntropyCoder::ht, RateMode::psnr, 50.0), "u16 ht");
}

// Float images are compared in the coded (transfer) domain, as the encoder compares them.
void expect_float_matches(const Image& image, const std::string& what) {
  const CodedDomainImage coded = to_coded_domain(view_of(image), Transfer::log2, false);
  ImageView view = view_of(coded.image);
  view.peak = 1.0;  // log-PSNR, as encode_image measures it
  for (EntropyCoder coder : {EntropyCoder::ebcot, EntropyCoder::ht}) {
    EncodeOptions o;
    o.entropy = coder;
    o.mode = RateMode::bpp;
    o.target = 2.0;
    const EncodeResult r = encode_image(image, o);
    ASSERT_EQ(parse_container(r.bytes).header.nonnegative, coded.nonnegative) << what;
    expect_strip_psnr_matches(view, r.bytes, what + " " + to_string(coder));
    // The reference is the one the encoder compares with: its own figure is the same.
    EXPECT_EQ(r.psnr, measure_psnr(view, r.bytes, default_executor())) << what << " " << to_string(coder);
  }
}

TEST(StripPsnr, FloatPhotographs) {
  expect_float_matches(photo("forest_hdr.exr"), "forest_hdr.exr (half)");
  Image astronaut = photo("astronaut.png");
  astronaut.type = SampleType::f32;
  for (float& v : astronaut.samples) v /= 255.0f;
  expect_float_matches(astronaut, "astronaut.png as float");
}

TEST(StripPsnr, ParentContextCodersUseWholePlanes) {
  const Image image = photo("astronaut.png");
  const ImageView view = view_of(image);
  for (const auto& [coder, mode] :
       {std::pair{EntropyCoder::pc, RateMode::bpp}, std::pair{EntropyCoder::lc, RateMode::lossless}}) {
    const auto bytes = encode(view, coder, mode, 1.0, mode == RateMode::lossless ? "cdf53" : "cdf97");
    const ParsedStream s = parse_container(bytes, 0, DecodeLimits{SIZE_MAX});
    EXPECT_FALSE(strip_psnr(view, s, default_executor()).has_value()) << to_string(coder);
    EXPECT_EQ(measure_psnr(view, bytes, default_executor()), full_planes_psnr(view, s, default_executor()))
        << to_string(coder);
  }
}

}  // namespace
}  // namespace pupwave

// The encoder reads typed strided views (codec/image/image_view.h): every layout and storage of
// the same image gives the same stream as the owning planar Image, nothing is copied whole, and
// unreadable views are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "test_images.h"

namespace pupwave {
namespace {

EncodeOptions bpp1() {
  EncodeOptions o;
  o.mode = RateMode::bpp;
  o.target = 1.0;
  return o;
}

template <class T>
std::vector<T> interleave(const Image& img, std::size_t pad) {
  const std::size_t pitch = img.width * img.channels + pad;
  std::vector<T> out(pitch * img.height, T(0));
  for (std::size_t y = 0; y < img.height; ++y)
    for (std::size_t x = 0; x < img.width; ++x)
      for (std::size_t c = 0; c < img.channels; ++c)
        out[y * pitch + x * img.channels + c] = T(img.at(c, x, y));
  return out;
}

TEST(ImageView, InterleavedPaddedU8GivesTheSameStreamAsThePlanarImage) {
  const Image img = testing::synthetic_image(97, 61, 3, SampleType::u8, 41);
  const auto expected = encode_image(img, bpp1()).bytes;
  const auto pixels = interleave<std::uint8_t>(img, 5);
  const ImageView v = interleaved_view(pixels.data(), 97, 61, 3, SampleType::u8, 97 * 3 + 5);
  EXPECT_EQ(encode_image(v, bpp1()).bytes, expected);
  EncodeOptions lossless;
  lossless.mode = RateMode::lossless;
  lossless.transform = "cdf53";
  EXPECT_EQ(encode_image(v, lossless).bytes, encode_image(img, lossless).bytes);
}

TEST(ImageView, PlanarU16AndBgrOrderByNegativeChannelStride) {
  const Image img = testing::synthetic_image(40, 33, 3, SampleType::u16, 42);
  const auto expected = encode_image(img, bpp1()).bytes;
  std::vector<std::uint16_t> planar(img.samples.begin(), img.samples.end());
  EXPECT_EQ(encode_image(planar_view(planar.data(), 40, 33, 3, SampleType::u16), bpp1()).bytes, expected);
  // Memory holds B, G, R interleaved; the view starts at R and steps back for G and B.
  auto bgr = interleave<std::uint16_t>(img, 0);
  for (std::size_t p = 0; p < 40 * 33; ++p) std::swap(bgr[3 * p], bgr[3 * p + 2]);
  ImageView v = interleaved_view(bgr.data() + 2, 40, 33, 3, SampleType::u16);
  v.channel_stride = -1;
  EXPECT_EQ(encode_image(v, bpp1()).bytes, expected);
}

TEST(ImageView, HalfStorageIsExact) {
  EXPECT_EQ(half_to_float(0x3C00), 1.0f);
  EXPECT_EQ(half_to_float(0xC000), -2.0f);
  EXPECT_EQ(half_to_float(0x7BFF), 65504.0f);
  EXPECT_EQ(half_to_float(0x0001), std::ldexp(1.0f, -24));  // smallest subnormal
  EXPECT_EQ(half_to_float(0x83FF), -1023.0f * std::ldexp(1.0f, -24));
  EXPECT_TRUE(std::isinf(half_to_float(0x7C00)));
  EXPECT_TRUE(std::isnan(half_to_float(0x7E00)));
  // Every finite half converts to a float that converts back to the same bits.
  for (std::uint32_t h = 0; h < 0x10000; ++h) {
    const float f = half_to_float(std::uint16_t(h));
    if (!std::isfinite(f)) continue;
    const int e = f == 0.0f ? 0 : std::ilogb(f);
    const float ulp = std::ldexp(1.0f, std::max(e, -14) - 10);
    ASSERT_EQ(std::fmod(f, ulp), 0.0f) << h;  // representable in binary16
  }
  // A half image through a half view codes as the same image held as float.
  const Image smooth = testing::synthetic_image(30, 20, 1, SampleType::u16, 43);
  Image img(30, 20, 1, SampleType::f16);
  std::vector<std::uint16_t> bits(img.samples.size());
  for (std::size_t i = 0; i < bits.size(); ++i) {
    bits[i] = std::uint16_t(0x3800 + std::uint32_t(smooth.samples[i]) / 64);  // halves in [0.5, 1)
    img.samples[i] = half_to_float(bits[i]);
  }
  EXPECT_EQ(encode_image(planar_view(bits.data(), 30, 20, 1, SampleType::f16), bpp1()).bytes,
            encode_image(img, bpp1()).bytes);
}

TEST(ImageView, UnreadableViewsAndBadSamplesAreRefused) {
  std::vector<std::uint8_t> px(16 * 16, 7);
  ImageView v = planar_view(px.data(), 16, 16, 1, SampleType::u8);
  v.data = nullptr;
  EXPECT_THROW(encode_image(v, bpp1()), std::invalid_argument);
  v = planar_view(px.data(), 16, 16, 1, SampleType::u16);
  v.storage = StorageType::u8;  // 16-bit samples cannot live in bytes
  EXPECT_THROW(encode_image(v, bpp1()), std::invalid_argument);
  v = planar_view(px.data(), 16, 16, 1, SampleType::u8);
  v.row_stride = 0;
  EXPECT_THROW(encode_image(v, bpp1()), std::invalid_argument);
  std::vector<float> f(16 * 16, 3.5f);  // not an integer, yet called 8-bit
  ImageView fv = planar_view(f.data(), 16, 16, 1, SampleType::f32);
  fv.type = SampleType::u8;
  EXPECT_THROW(encode_image(fv, bpp1()), EncodeError);
  f[5] = std::nanf("");
  fv.type = SampleType::f32;
  EXPECT_THROW(encode_image(fv, bpp1()), EncodeError);
}

}  // namespace
}  // namespace pupwave

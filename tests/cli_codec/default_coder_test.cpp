// The default coder choice (encode_image_default_coder, codec/image/image_encoder_default.cpp):
// rate targets on images of up to kPcDefaultPixels (integer or float) take the pc coder (entropy
// coder 4), larger images the bit-plane coder (its strip encoder keeps memory bounded), lossless
// the lc coder; effort 2 is the bit-plane coder's search and is refused without it.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "codec/image/image_codec.h"
#include "codec/image/image_stream.h"
#include "tests/cli_codec/photo_crops.h"

namespace pupwave::test {
namespace {

EntropyCoder coder_of(const std::vector<std::uint8_t>& bytes) {
  return parse_container(bytes).header.entropy;
}

EncodeOptions rate(RateMode mode, double target) {
  EncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.measure_psnr = false;
  return o;
}

// The size rule itself, on views (no pixels read): up to 2^22 pixels of any sample type.
TEST(DefaultCoder, PcUpToFourMegapixels) {
  ImageView v;
  v.type = SampleType::u8;
  v.channels = 3;
  v.width = 2048, v.height = 2048;
  EXPECT_TRUE(pc_is_default_for(v));
  v.height = 2049;
  EXPECT_FALSE(pc_is_default_for(v));
  v.type = SampleType::u16, v.height = 512;
  EXPECT_TRUE(pc_is_default_for(v));
  v.type = SampleType::f32;
  EXPECT_TRUE(pc_is_default_for(v));
  v.height = 2049;
  EXPECT_FALSE(pc_is_default_for(v));
}

// On the test photographs (8-bit, 16-bit and the HDR one in half floats) every rate mode's default
// stream is the pc coder's, byte for byte.
TEST(DefaultCoder, PhotographsTakeThePcCoder) {
  for (const char* name :
       {"camera.png", "coffee.png", "courtyard16.png", "interior16.png", "forest_hdr.exr"}) {
    const Image image = photo(name);
    for (const auto& [mode, target] :
         {std::pair{RateMode::bpp, 0.5}, {RateMode::psnr, 36.0}, {RateMode::step, 8.0}}) {
      const auto chosen = encode_image_default_coder(view_of(image), rate(mode, target)).bytes;
      EncodeOptions pc = rate(mode, target);
      pc.entropy = EntropyCoder::pc;
      EXPECT_EQ(coder_of(chosen), EntropyCoder::pc) << name;
      EXPECT_TRUE(chosen == encode_image(view_of(image), pc).bytes) << name << " mode " << int(mode);
    }
    if (!is_integer(image.type)) continue;  // float images are lossy only
    // Lossless stays the lc coder's.
    EncodeOptions exact = rate(RateMode::lossless, 0.0);
    exact.transform = "cdf53";
    EXPECT_EQ(coder_of(encode_image_default_coder(view_of(image), exact).bytes), EntropyCoder::lc);
  }
}

// Above the size the bit-plane coder codes (a mosaic of a real photograph, 4.2 Mpixel grey), and
// it meets the budget.
TEST(DefaultCoder, LargerImagesTakeTheBitPlaneCoder) {
  const Image camera = photo("camera.png");  // 512 x 512 grey
  Image mosaic(2048, 2049, 1, camera.type);
  for (std::size_t y = 0; y < mosaic.height; ++y)
    for (std::size_t x = 0; x < mosaic.width; ++x) mosaic.at(0, x, y) = camera.at(0, x % 512, y % 512);
  const auto bytes = encode_image_default_coder(view_of(mosaic), rate(RateMode::bpp, 0.1)).bytes;
  EXPECT_EQ(coder_of(bytes), EntropyCoder::ebcot);
  EXPECT_LE(double(bytes.size()) * 8.0, 0.1 * 2048.0 * 2049.0);
}

// Effort 2 is the bit-plane coder's search: refused with the default coder, which would ignore it.
TEST(DefaultCoder, EffortTwoNeedsTheBitPlaneCoder) {
  const Image image = photo("coffee.png");
  EncodeOptions o = rate(RateMode::bpp, 1.0);
  o.effort = 2;
  EXPECT_THROW(encode_image_default_coder(view_of(image), o), std::invalid_argument);
  o.entropy = EntropyCoder::ebcot;
  EXPECT_EQ(coder_of(encode_image(image, o).bytes), EntropyCoder::ebcot);
}

}  // namespace
}  // namespace pupwave::test

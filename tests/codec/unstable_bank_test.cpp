// Filter banks whose coarse band grows at every level (pups:cinpact-c3) overflow the block
// coder's index range at the default level count; the encoder then uses fewer levels.
#include <gtest/gtest.h>

#include "codec/entropy/block_encoder.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_stream.h"
#include "codec/test_images.h"
#include "transforms/separable.h"

namespace pupwave {
namespace {

TEST(UnstableBank, DefaultLevelsFallBackInsteadOfFailing) {
  // Float samples: an integer image at so fine a step would be coded lossless instead.
  const Image img = testing::synthetic_image(256, 256, 1, SampleType::f32);
  EncodeOptions o;
  o.transform = "pups:cinpact-c3";
  o.mode = RateMode::step;  // a fine step: near-lossless indices overflow after the coarse band grows
  o.target = 0.01 / 255.0;
  const int full = default_levels({256, 256, 1});
  o.levels = full;
  EXPECT_THROW(encode_image(img, o), IndexRangeError);  // the bank really overflows at full depth

  o.levels = -1;
  const EncodeResult r = encode_image(img, o);
  const int used = parse_container(r.bytes).header.levels;
  EXPECT_LT(used, full);
  EXPECT_GE(used, 1);
  const Image back = decode_image(r.bytes);
  EXPECT_EQ(back.width, img.width);
  EXPECT_EQ(back.height, img.height);
  EXPECT_GT(r.psnr, 60.0);
}

}  // namespace
}  // namespace pupwave

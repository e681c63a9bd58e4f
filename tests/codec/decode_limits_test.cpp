// The library's decode limit (DecodeLimits, docs/bitstream.md Decoder bounds): counted at the
// decoded level, refused with DecodeError before any output is allocated.
#include <gtest/gtest.h>

#include "codec/error.h"
#include "codec/image/image_codec.h"
#include "test_images.h"

namespace pupwave {
namespace {

std::vector<std::uint8_t> stream_70x50() {
  EncodeOptions o;
  o.mode = RateMode::lossless;
  o.transform = "cdf53";
  return encode_image(testing::synthetic_image(70, 50, 3, SampleType::u8), o).bytes;
}

TEST(DecodeLimits, FullResolutionCountsWidthTimesHeight) {
  const auto bytes = stream_70x50();
  EXPECT_EQ(decode_image(bytes, 0, serial_executor(), DecodeLimits{3500}).width, 70u);
  try {
    decode_image(bytes, 0, serial_executor(), DecodeLimits{3499});
    FAIL() << "no DecodeError";
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("pixels of 3500 exceeds the decode limit of 3499"),
              std::string::npos);
  }
  EXPECT_EQ(kDefaultMaxDecodePixels, std::size_t(1) << 28);
}

TEST(DecodeLimits, AReducedDecodeCountsItsLevel) {
  const auto bytes = stream_70x50();
  const Image half = decode_image(bytes, 1, serial_executor(), DecodeLimits{35 * 25});
  EXPECT_EQ(half.width, 35u);
  EXPECT_EQ(half.height, 25u);
  EXPECT_THROW(decode_image(bytes, 1, serial_executor(), DecodeLimits{35 * 25 - 1}), DecodeError);
  // The same pixels as the default-limit decode.
  EXPECT_EQ(half.samples, decode_image(bytes, 1).samples);
}

}  // namespace
}  // namespace pupwave

// Each row of the coder traits table (codec/entropy/coder_traits.cpp) says what the coder does on
// a real photograph: it codes lossy and lossless streams exactly when the row says so, a stream's
// blocks decode strip by strip exactly when they decode alone, whole-band coders code each band as
// one block, and the entropy byte and name come back from the stream. A stream naming the retired
// coder byte is refused with its name.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "cli_codec/photo_crops.h"
#include "codec/entropy/coder_traits.h"
#include "codec/error.h"
#include "codec/format/crc32.h"
#include "codec/image/image_strips.h"
#include "transforms/executor.h"

namespace pupwave {
namespace {

using test::crop;
using test::photo;

constexpr EntropyCoder kEvery[] = {EntropyCoder::ebcot, EntropyCoder::ht, EntropyCoder::lc, EntropyCoder::pc};

std::vector<std::uint8_t> encode(const Image& image, EntropyCoder coder, RateMode mode) {
  EncodeOptions o;
  o.entropy = coder;
  o.mode = mode;
  o.target = 1.0;
  o.transform = mode == RateMode::lossless ? "cdf53" : "cdf97";
  o.measure_psnr = false;
  return encode_image(image, o).bytes;
}

TEST(CoderTraits, EachRowIsWhatTheCoderDoes) {
  const Image image = crop(photo("coffee.png"), 200, 136);
  for (EntropyCoder coder : kEvery) {
    const CoderTraits& t = coder_traits(coder);
    EXPECT_EQ(t.coder, coder);
    EXPECT_EQ(coder_from_byte(std::uint32_t(coder)), coder);
    EXPECT_STREQ(to_string(coder), t.name);
    for (RateMode mode : {RateMode::lossless, RateMode::bpp}) {
      const bool codes = mode == RateMode::lossless ? t.lossless : t.lossy;
      if (!codes) {
        EXPECT_THROW(encode(image, coder, mode), std::invalid_argument) << t.name;
        continue;
      }
      const auto bytes = encode(image, coder, mode);
      const ParsedStream s = parse_container(bytes);
      EXPECT_EQ(s.header.entropy, coder) << t.name;
      // Whole-band coders code each band of this image as one block; the others in 64 x 64 blocks.
      EXPECT_EQ(s.header.block_size()[0], t.whole_bands ? 1024u : 64u) << t.name;
      const auto strips = ImageStripDecoder::open(bytes, 0, serial_executor(), DecodeLimits{});
      EXPECT_EQ(strips != nullptr, t.blocks_alone) << t.name;
      if (!strips) continue;
      const Image whole = decode_image(bytes);
      std::size_t y0 = 0, differing = 0;
      for (Image strip = strips->next(16); strip.height > 0; y0 += strip.height, strip = strips->next(16))
        for (std::size_t c = 0; c < strip.channels; ++c)
          for (std::size_t i = 0; i < strip.plane_size(); ++i)
            differing += strip.plane(c)[i] != whole.plane(c)[y0 * whole.width + i];
      EXPECT_EQ(y0, whole.height) << t.name;
      EXPECT_EQ(differing, 0u) << t.name;
    }
  }
  EXPECT_FALSE(coder_from_byte(5).has_value());
}

// `bytes` with the HEAD chunk's entropy byte set to `byte` and the chunk's CRC fixed, so only the
// field check can refuse it. HEAD is the first chunk (after the 5-byte signature): 4-byte tag,
// u32 length, payload, CRC-32 of tag, length and payload; the entropy byte is payload byte 15.
std::vector<std::uint8_t> with_entropy_byte(std::vector<std::uint8_t> bytes, std::uint8_t byte) {
  const std::size_t head = 5, payload = head + 8;
  const std::size_t length = bytes[head + 4] | (bytes[head + 5] << 8);
  bytes[payload + 15] = byte;
  const std::uint32_t crc = crc32(std::span<const std::uint8_t>(bytes).subspan(head, 8 + length));
  for (int i = 0; i < 4; ++i) bytes[payload + length + std::size_t(i)] = std::uint8_t(crc >> (8 * i));
  return bytes;
}

// Entropy byte 1 (zstd) is retired: no coder takes it, and a stream naming it is refused by name.
TEST(CoderTraits, RetiredCoderByteIsRefusedByName) {
  EXPECT_FALSE(coder_from_byte(1).has_value());
  EXPECT_STREQ(retired_coder_name(1), "zstd");
  for (EntropyCoder coder : kEvery) EXPECT_EQ(retired_coder_name(std::uint32_t(coder)), nullptr);
  const auto good = encode(crop(photo("astronaut.png"), 96, 80), EntropyCoder::ebcot, RateMode::bpp);
  ASSERT_NO_THROW(decode_image(with_entropy_byte(good, 0)));  // the edit alone breaks nothing
  try {
    (void)decode_image(with_entropy_byte(good, 1));
    ADD_FAILURE() << "a stream naming entropy coder 1 was decoded";
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("entropy coder 1 (zstd) is not supported"), std::string::npos)
        << e.what();
  }
}

// The container refuses a stream whose coder cannot code its kind of stream, naming the coder.
TEST(CoderTraits, ContainerRefusesACoderInTheWrongKindOfStream) {
  const Image image = crop(photo("camera.png"), 64, 48);
  auto lossless = encode(image, EntropyCoder::lc, RateMode::lossless);
  const ParsedStream s = parse_container(lossless);
  StreamHeader h = s.header;
  h.entropy = EntropyCoder::pc;  // pc codes lossy streams only
  std::vector<std::vector<std::uint8_t>> data;
  for (const auto& d : s.resolution_data) data.emplace_back(d.begin(), d.end());
  const auto bad = write_container(h, s.index, data);
  try {
    (void)parse_container(bad);
    ADD_FAILURE() << "a reversible pc stream was parsed";
  } catch (const DecodeError& e) {
    EXPECT_NE(std::string(e.what()).find("pc coder in a reversible stream"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pupwave

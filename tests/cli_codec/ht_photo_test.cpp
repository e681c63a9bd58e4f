// The high-throughput coder (`--entropy ht`) on the test photographs: lossless exact on all
// four, byte budgets met from below, the CLI option, and the strip decoder on ht streams.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "codec/format/crc32.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_metrics.h"
#include "codec/image/image_stream.h"
#include "photo_crops.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {

using test::photo;

EncodeOptions ht(RateMode mode, double target, const char* transform = "cdf97") {
  EncodeOptions o;
  o.mode = mode;
  o.target = target;
  o.transform = transform;
  o.entropy = EntropyCoder::ht;
  return o;
}

TEST(HtPhotos, LosslessIsExactOnEveryPhotograph) {
  for (const char* name : {"astronaut.png", "camera.png", "chelsea.png", "coffee.png"}) {
    const Image img = photo(name);
    const EncodeResult r = encode_image(img, ht(RateMode::lossless, 0.0, "cdf53"));
    EXPECT_EQ(parse_container(r.bytes).header.entropy, EntropyCoder::ht);
    EXPECT_EQ(decode_image(r.bytes).samples, img.samples) << name;
    // Within 15% of the bit-plane coder's lossless size (a coder with no arithmetic coding).
    EncodeOptions e = ht(RateMode::lossless, 0.0, "cdf53");
    e.entropy = EntropyCoder::ebcot;
    EXPECT_LT(double(r.bytes.size()), 1.15 * double(encode_image(img, e).bytes.size())) << name;
  }
}

TEST(HtPhotos, ByteBudgetsAreMetFromBelow) {
  for (const char* name : {"camera.png", "astronaut.png"}) {
    const Image img = photo(name);
    for (double bpp : {0.25, 1.0, 2.0}) {
      const EncodeResult r = encode_image(img, ht(RateMode::bpp, bpp));
      const double got = double(r.bytes.size()) * 8.0 / double(img.plane_size());
      EXPECT_LE(got, bpp) << name;
      EXPECT_GE(got, 0.99 * bpp) << name << " at " << bpp;
      EXPECT_NEAR(compare_images(img, decode_image(r.bytes)).overall.psnr, r.psnr, 1e-9);
    }
  }
}

TEST(HtPhotos, CliCompressesAndDecompresses) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pupwave_ht_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  std::filesystem::create_directories(dir);
  const std::string src = std::string(PUPWAVE_TESTIMAGES_DIR) + "/coffee.png";
  const std::string pw = (dir / "c.pw").string(), png = (dir / "c.png").string();
  const std::string cmd =
      std::string(PUPWAVE_CLI) + " compress " + src + " " + pw + " --entropy ht --bpp 1 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  ASSERT_EQ(
      std::system((std::string(PUPWAVE_CLI) + " decompress " + pw + " " + png + " --level 1 2>&1").c_str()),
      0);
  const Image half = cli::read_image(png);
  EXPECT_EQ(half.width, (photo("coffee.png").width + 1) / 2);
  std::filesystem::remove_all(dir);
}

// `in` tiled `across` times by `down` times (2048 rows or more: surveyed by stripes).
Image tiled(const Image& in, std::size_t across, std::size_t down) {
  Image out(in.width * across, in.height * down, in.channels, in.type);
  for (std::size_t c = 0; c < in.channels; ++c)
    for (std::size_t y = 0; y < out.height; ++y)
      for (std::size_t x = 0; x < out.width; ++x) out.at(c, x, y) = in.at(c, x % in.width, y % in.height);
  return out;
}

// Streamed byte budgets pinned where the search takes one pass and where it takes two or three:
// a sample over 1 MiB (the 1536 x 2560 tiling's) is freed during a pass and surveyed again for
// the next, a smaller one held. CRC-32 of each stream as an encoder holding every sample
// throughout gives it (stream version 6).
TEST(HtPhotos, StreamedSearchesGiveTheStreamsTheHeldSampleGave) {
  const Image camera = photo("camera.png"), tall = tiled(camera, 1, 5), wide = tiled(camera, 3, 5);
  const struct {
    const Image* image;
    double bpp;
    std::uint32_t crc;
  } cases[] = {
      {&camera, 0.5, 2812409360u},  // two passes, the whole-image survey's sample held
      {&tall, 0.5, 2225815233u},    // one pass
      {&tall, 2.0, 2342506729u},    // three passes, the stripes' sample held
      {&wide, 1.0, 464722974u},     // two passes, the stripes surveyed again
      {&wide, 1.5, 4025601890u},    // three passes, the stripes surveyed again twice
  };
  for (const auto& k : cases)
    EXPECT_EQ(crc32(encode_image(*k.image, ht(RateMode::bpp, k.bpp)).bytes), k.crc)
        << k.image->width << " x " << k.image->height << " at " << k.bpp << " bpp";
  const Image astronaut = photo("astronaut.png");  // RGB, two passes
  EXPECT_EQ(crc32(encode_image(astronaut, ht(RateMode::bpp, 2.0)).bytes), 3944350987u);
}

}  // namespace
}  // namespace pupwave

// Strip-wise decoding (codec/image/image_strips.h, `pupwave decompress` to PGM/PPM) gives the
// pixels of the whole-image decoder exactly, on the test photographs: every transform whose
// synthesis is local, lossy and lossless, the bit-plane and ht coders, every reduced level, odd sizes,
// 8- and 16-bit samples, any strip height and thread count.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_codec/photo_crops.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_strips.h"
#include "tools/image_io.h"
#include "transforms/reach.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;

using test::crop;
using test::photo;

// The whole image reassembled from strips of `rows` rows.
Image decode_by_strips(const std::vector<std::uint8_t>& bytes, int level, std::size_t rows,
                       const Executor& ex) {
  const auto decoder = ImageStripDecoder::open(bytes, level, ex, DecodeLimits{});
  EXPECT_NE(decoder, nullptr);
  if (!decoder) return {};
  Image out(decoder->width(), decoder->height(), decoder->channels(), decoder->type());
  std::size_t y0 = 0;
  for (Image strip = decoder->next(rows); strip.height > 0; strip = decoder->next(rows)) {
    EXPECT_LE(strip.height, rows);
    for (std::size_t c = 0; c < out.channels; ++c)
      std::copy_n(strip.plane(c), strip.plane_size(), out.plane(c) + y0 * out.width);
    y0 += strip.height;
  }
  EXPECT_EQ(y0, out.height);
  return out;
}

// Strips of several heights at levels 0..levels (all the stream has, if fewer) equal
// decode_image's pixels.
void expect_strips_match(const std::vector<std::uint8_t>& bytes, int levels, const std::string& what) {
  for (int level = 0; level <= levels; ++level) {
    Image whole;
    try {
      whole = decode_image(bytes, level);
    } catch (const std::invalid_argument&) {  // beyond the stream's levels
      ASSERT_GT(level, 0) << what;
      return;
    }
    for (std::size_t rows : {std::size_t(5), std::size_t(64)}) {
      const Image strips =
          decode_by_strips(bytes, level, rows, rows == 5 ? serial_executor() : default_executor());
      ASSERT_EQ(strips.width, whole.width) << what;
      ASSERT_EQ(strips.height, whole.height) << what;
      EXPECT_TRUE(strips.samples == whole.samples) << what << " level " << level << " strips of " << rows;
    }
  }
}

EncodeOptions options(const std::string& transform, RateMode mode, double target) {
  EncodeOptions o;
  o.transform = transform;
  o.mode = mode;
  o.target = target;
  o.measure_psnr = false;
  return o;
}

TEST(StripDecode, PhotographsAtOneBppEveryLevel) {
  for (const char* name : {"astronaut.png", "camera.png", "chelsea.png", "coffee.png"}) {
    const Image image = photo(name);
    const auto r = encode_image(image, options("cdf97", RateMode::bpp, 1.0));
    expect_strips_match(r.bytes, 8, name);
  }
}

TEST(StripDecode, LosslessAndHtAndSixteenBit) {
  const Image rgb = crop(photo("chelsea.png"), 301, 217);
  expect_strips_match(encode_image(rgb, options("cdf53", RateMode::lossless, 0)).bytes, 3, "lossless");
  EncodeOptions ht = options("cdf97", RateMode::step, 4.0);
  ht.entropy = EntropyCoder::ht;
  expect_strips_match(encode_image(rgb, ht).bytes, 3, "ht");
  Image wide = crop(photo("camera.png"), 333, 129);
  wide.type = SampleType::u16;
  for (float& v : wide.samples) v *= 257.0f;
  expect_strips_match(encode_image(wide, options("cdf97", RateMode::bpp, 2.0)).bytes, 2, "u16");
  expect_strips_match(encode_image(wide, options("cdf53", RateMode::lossless, 0)).bytes, 2, "u16 lossless");
}

TEST(StripDecode, EveryLocalTransformAndOddSizes) {
  const Image image = crop(photo("coffee.png"), 257, 183);
  std::size_t local = 0;
  for (const std::string& spec : transform_specs()) {
    const auto bytes = encode_image(image, options(spec, RateMode::bpp, 1.5)).bytes;
    if (synthesis_reach(*make_transform(spec)) == 0) {  // decoded whole instead
      EXPECT_EQ(ImageStripDecoder::open(bytes, 0, serial_executor(), DecodeLimits{}), nullptr) << spec;
      continue;
    }
    ++local;
    expect_strips_match(bytes, 2, spec);
  }
  EXPECT_GE(local, 10u);  // cdf97, cdf53 and most PUPs banks
}

TEST(StripDecode, ThinImages) {
  const Image image = photo("astronaut.png");
  for (auto [w, h] : {std::pair<std::size_t, std::size_t>{512, 1}, {1, 300}, {3, 200}, {400, 2}}) {
    const Image thin = crop(image, w, h);
    EncodeOptions o = options("cdf97", RateMode::step, 2.0);
    const auto bytes = encode_image(thin, o).bytes;
    expect_strips_match(bytes, 1, std::to_string(w) + "x" + std::to_string(h));
  }
}

TEST(StripDecode, CliWritesPnmAndPngStripByStripWithTheSamePixels) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_strips_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Image image = photo("coffee.png");
  const auto bytes = encode_image(image, options("cdf97", RateMode::bpp, 1.0)).bytes;
  const fs::path pw = dir / "c.pw";
  {
    std::FILE* f = std::fopen(pw.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fwrite(bytes.data(), 1, bytes.size(), f), bytes.size());
    std::fclose(f);
  }
  for (const char* format : {".ppm", ".png"})
    for (int level : {0, 2}) {
      const fs::path out = dir / ("c" + std::to_string(level) + format);
      const std::string command = std::string(PUPWAVE_CLI) + " decompress -q --level " +
                                  std::to_string(level) + " " + pw.string() + " " + out.string();
      ASSERT_EQ(std::system(command.c_str()), 0);
      EXPECT_TRUE(cli::read_image(out).samples == decode_image(bytes, level).samples) << format << level;
    }
  fs::remove_all(dir);
}

// An 8-bit PPM is encoded from the mapped file (no float copy): the stream is the one the
// library makes from the decoded image.
TEST(StripDecode, CompressFromAMappedPpmGivesTheLibrarysStream) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_mapped_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Image image = photo("chelsea.png");
  cli::write_image(image, dir / "c.ppm");
  const std::string command = std::string(PUPWAVE_CLI) + " compress -q --entropy ebcot --bpp 0.8 " +
                              (dir / "c.ppm").string() + " " + (dir / "c.pw").string();
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir / "c.pw", std::ios::binary);
  const std::vector<std::uint8_t> cli_bytes((std::istreambuf_iterator<char>(in)),
                                            std::istreambuf_iterator<char>());
  EXPECT_TRUE(cli_bytes == encode_image(image, options("cdf97", RateMode::bpp, 0.8)).bytes);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pupwave

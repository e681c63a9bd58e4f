// Strip-wise encoding (codec/image/image_strip_encoder.h): the encoder that transforms each
// component by strips and codes code-blocks as their rows complete writes exactly the bytes of
// the whole-image encoder (EncodeOptions::strip_encode = false), on the test photographs at
// several sizes (odd ones included), for every transform whose analysis is local, in every
// rate mode, at any thread count; and `pupwave compress` from a mapped PPM gives them too.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_codec/photo_crops.h"
#include "codec/entropy/codeblocks.h"
#include "codec/image/image_codec.h"
#include "codec/image/image_plan.h"
#include "codec/image/image_strip_encoder.h"
#include "tools/image_io.h"
#include "transforms/reach.h"
#include "transforms/spec.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;

using test::crop;
using test::photo;

EncodeOptions options(const std::string& transform, RateMode mode, double target) {
  EncodeOptions o;
  o.transform = transform;
  o.mode = mode;
  o.target = target;
  o.measure_psnr = false;
  return o;
}

// The strip-wise and the whole-image encoder's bytes for the same input and options.
void expect_same_stream(const Image& image, EncodeOptions o, const std::string& what) {
  o.strip_encode = true;
  const auto strips = encode_image(image, o).bytes;
  o.strip_encode = false;
  const auto whole = encode_image(image, o).bytes;
  EXPECT_FALSE(strips.empty()) << what;
  EXPECT_TRUE(strips == whole) << what << ": " << strips.size() << " vs " << whole.size() << " bytes";
}

// Every block the strip-wise transform hands on holds the whole-image transform's
// coefficients, bit for bit, and each block comes exactly once.
template <class T>
void expect_blocks_match(const Image& image, const EncodeOptions& o, const std::string& what) {
  ImagePlan plan = plan_image(view_of(image), o);
  ASSERT_GT(plan.strip_reach, 0u) << what;
  std::vector<int> seen(plan.blocks.size(), 0);
  std::vector<std::vector<T>> streamed(plan.blocks.size());
  for (std::size_t c = 0; c < image.channels; ++c)
    stream_component<T>(plan, c, [&](std::size_t i, std::span<const T> v) {
      ++seen[i];
      streamed[i].assign(v.begin(), v.end());
    });
  transform_all_components(plan);
  for (std::size_t i = 0; i < plan.blocks.size(); ++i) {
    const CodeBlock& b = plan.blocks[i];
    std::vector<T> whole(b.count());
    if constexpr (std::is_same_v<T, float>)
      copy_block_out(plan.coef[b.component].data(), plan.header.dims, b, whole.data());
    else
      copy_block_out(plan.icoef[b.component].data(), plan.header.dims, b, whole.data());
    ASSERT_EQ(seen[i], 1) << what << " block " << i;
    ASSERT_TRUE(streamed[i] == whole) << what << " block " << i;
  }
}

TEST(StripEncode, StreamedBlocksHoldTheWholeTransformsCoefficients) {
  const Image image = crop(photo("astronaut.png"), 333, 271);
  expect_blocks_match<float>(image, options("cdf97", RateMode::step, 1.0), "cdf97");
  expect_blocks_match<std::int32_t>(image, options("cdf53", RateMode::lossless, 0.0), "cdf53 lossless");
  EncodeOptions one_level = options("cdf97", RateMode::step, 1.0);
  one_level.levels = 1;
  expect_blocks_match<float>(image, one_level, "one level");
}

TEST(StripEncode, PhotographsAtSeveralSizesAndRates) {
  for (const char* name : {"astronaut.png", "camera.png", "coffee.png"}) {
    const Image image = photo(name);
    for (auto [w, h] :
         {std::pair<std::size_t, std::size_t>{image.width, image.height}, {301, 217}, {129, 67}}) {
      const Image part = crop(image, w, h);
      for (double bpp : {0.25, 1.0, 3.0})
        expect_same_stream(part, options("cdf97", RateMode::bpp, bpp),
                           std::string(name) + " " + std::to_string(w) + "x" + std::to_string(h) + " at " +
                               std::to_string(bpp) + " bpp");
    }
  }
}

TEST(StripEncode, StepLosslessPsnrAndLevels) {
  const Image rgb = crop(photo("chelsea.png"), 283, 199);
  expect_same_stream(rgb, options("cdf97", RateMode::step, 3.0), "step");
  expect_same_stream(rgb, options("cdf53", RateMode::lossless, 0.0), "lossless");
  expect_same_stream(rgb, options("cdf97", RateMode::psnr, 36.0), "psnr");
  for (int levels : {0, 1, 3}) {
    EncodeOptions o = options("cdf97", RateMode::bpp, 1.0);
    o.levels = levels;
    expect_same_stream(rgb, o, "levels " + std::to_string(levels));
  }
  EncodeOptions blocks = options("cdf97", RateMode::bpp, 1.0);
  blocks.block_size = {32, 32, 1};
  expect_same_stream(rgb, blocks, "32x32 blocks");
  Image wide = crop(photo("camera.png"), 190, 155);
  wide.type = SampleType::u16;
  for (float& v : wide.samples) v *= 257.0f;
  expect_same_stream(wide, options("cdf97", RateMode::bpp, 2.0), "u16");
  expect_same_stream(wide, options("cdf53", RateMode::lossless, 0.0), "u16 lossless");
}

TEST(StripEncode, EveryLocalTransformAndOddSizes) {
  const Image image = crop(photo("coffee.png"), 257, 183);
  std::size_t local = 0;
  for (const std::string& spec : transform_specs()) {
    if (analysis_reach(*make_transform(spec)) == 0) continue;  // transformed whole instead
    ++local;
    expect_same_stream(image, options(spec, RateMode::bpp, 1.5), spec);
  }
  EXPECT_GE(local, 20u);  // every spec today (Kobbelt k2/k3/kspl: analysis local, synthesis not)
}

TEST(StripEncode, ThinImages) {
  const Image image = photo("astronaut.png");
  for (auto [w, h] : {std::pair<std::size_t, std::size_t>{512, 1}, {1, 300}, {3, 200}, {400, 2}, {2, 2}}) {
    const Image thin = crop(image, w, h);
    expect_same_stream(thin, options("cdf97", RateMode::step, 2.0),
                       std::to_string(w) + "x" + std::to_string(h));
  }
}

TEST(StripEncode, ThreadCountsGiveTheSameBytes) {
  const Image image = crop(photo("astronaut.png"), 400, 333);
  for (RateMode mode : {RateMode::bpp, RateMode::lossless}) {
    EncodeOptions o = options(mode == RateMode::bpp ? "cdf97" : "cdf53", mode, 1.0);
    o.executor = &serial_executor();
    const auto one = encode_image(image, o).bytes;
    o.executor = &default_executor();
    EXPECT_TRUE(one == encode_image(image, o).bytes);
  }
}

// `pupwave compress` encodes a mapped 8-bit PPM by strips, dropping the rows it has read from
// memory (they come back from the page cache when read again): the library's bytes. (Plain
// --lossless is the lc coder, which holds a component whole: the library's bytes too.)
TEST(StripEncode, CliFromAMappedPpmGivesTheWholeImageStream) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_strip_enc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Image image = photo("coffee.png");
  cli::write_image(image, dir / "c.ppm");
  for (const char* rate : {"--bpp 0.6 --entropy ebcot", "--lossless --entropy ebcot", "--lossless"}) {
    const std::string command = std::string(PUPWAVE_CLI) + " compress -q " + rate + " " +
                                (dir / "c.ppm").string() + " " + (dir / "c.pw").string();
    ASSERT_EQ(std::system(command.c_str()), 0);
    std::ifstream in(dir / "c.pw", std::ios::binary);
    const std::vector<std::uint8_t> cli_bytes((std::istreambuf_iterator<char>(in)),
                                              std::istreambuf_iterator<char>());
    const bool lossy = std::string(rate) == "--bpp 0.6 --entropy ebcot";
    EncodeOptions o =
        lossy ? options("cdf97", RateMode::bpp, 0.6) : options("cdf53", RateMode::lossless, 0.0);
    if (std::string(rate) == "--lossless") o.entropy = EntropyCoder::lc;
    o.strip_encode = false;
    EXPECT_TRUE(cli_bytes == encode_image(image, o).bytes) << rate;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pupwave

// `pupwave decompress` to PGM and to PNG decodes strip by strip: an 8192 x 8192 grey image
// (tiles of the camera photograph) decodes under an address-space limit that the whole-image
// decoder, which holds the image in float (256 MiB here), exceeds; the pixels are decode_image's.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "codec/image/image_codec.h"
#include "hostile/bounded_child.h"
#include "tools/image_io.h"

namespace pupwave {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kEdge = 8192;
// No more than the image in float, which the whole-image decoder holds (it needed a 384 MiB
// limit with --threads 2 here); the strip decoder ran in 144 MiB (most of it libraries).
constexpr rlim_t kLimit = rlim_t(256) << 20;
static_assert(kEdge * kEdge * sizeof(float) >= kLimit);

// The camera photograph tiled to kEdge x kEdge, 8-bit grey, one byte a pixel.
std::vector<std::uint8_t> tiled_camera() {
  const Image camera = cli::read_image(std::string(PUPWAVE_TESTIMAGES_DIR) + "/camera.png");
  std::vector<std::uint8_t> pixels(kEdge * kEdge);
  for (std::size_t y = 0; y < kEdge; ++y)
    for (std::size_t x = 0; x < kEdge; ++x)
      pixels[y * kEdge + x] = std::uint8_t(camera.at(0, x % camera.width, y % camera.height));
  return pixels;
}

TEST(StripDecodeMemory, LargeGreyImageDecodesToPgmAndPngUnderAnAddressSpaceLimit) {
  const fs::path dir = fs::temp_directory_path() / ("pupwave_strip_memory_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<std::uint8_t> bytes;
  {
    const auto pixels = tiled_camera();
    EncodeOptions o;
    o.mode = RateMode::step;  // a coarse fixed step keeps the encode to a few seconds
    o.target = 32.0;
    o.measure_psnr = false;
    bytes = encode_image(interleaved_view(pixels.data(), kEdge, kEdge, 1, SampleType::u8), o).bytes;
  }
  const fs::path pw = dir / "tiled.pw", pgm = dir / "tiled.pgm";
  std::ofstream(pw, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));

  const auto strips = testing::run_cli_bounded({"decompress", "-q", "--threads", "2", pw, pgm}, 60.0, kLimit);
  EXPECT_EQ(strips.exit_code, 0) << strips.output;

  const Image expected = decode_image(bytes);
  std::ifstream in(pgm, std::ios::binary);
  std::string magic, max;
  std::size_t w = 0, h = 0;
  in >> magic >> w >> h >> max;
  in.get();  // the one whitespace byte before the raster
  ASSERT_EQ(magic, "P5");
  ASSERT_EQ(w, kEdge);
  ASSERT_EQ(h, kEdge);
  std::vector<std::uint8_t> raster(kEdge * kEdge);
  in.read(reinterpret_cast<char*>(raster.data()), std::streamsize(raster.size()));
  ASSERT_TRUE(in.good());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < raster.size(); ++i) differing += float(raster[i]) != expected.samples[i];
  EXPECT_EQ(differing, 0u);

  const fs::path png = dir / "tiled.png";
  const auto png_strips =
      testing::run_cli_bounded({"decompress", "-q", "--threads", "2", pw, png}, 60.0, kLimit);
  EXPECT_EQ(png_strips.exit_code, 0) << png_strips.output;
  EXPECT_TRUE(cli::read_image(png).samples == expected.samples);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pupwave

// Image file round trips (OpenImageIO, and tools/pnm_io.cpp and png_io.cpp) for every format,
// sample type and channel count.
#include <gtest/gtest.h>

#include <Imath/half.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <tuple>

#include "io/io_test_files.h"
#include "tools/image_io.h"
#include "tools/pnm_io.h"

namespace pupwave::cli {
namespace {
using namespace pupwave::test;

using Case = std::tuple<std::string, SampleType, std::size_t>;

class LosslessRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(LosslessRoundTrip, SamplesComeBackExactly) {
  const auto [ext, type, channels] = GetParam();
  const Image img = random_image(37, 23, channels, type, unsigned(channels * 7 + int(type)));
  const fs::path path =
      scratch_dir() / ("rt_" + std::to_string(int(type)) + "_" + std::to_string(channels) + ext);
  SampleType stored = SampleType::u8;
  write_image(img, path, &stored);
  EXPECT_EQ(stored, type);
  const Image back = read_image(path);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  ASSERT_EQ(back.channels, img.channels);
  EXPECT_EQ(back.type, img.type);
  EXPECT_EQ(back.samples, img.samples);
  fs::remove(path);
}

std::vector<Case> lossless_cases() {
  std::vector<Case> cases;
  for (std::size_t c = 1; c <= 4; ++c) {
    for (SampleType t : {SampleType::u8, SampleType::u16}) cases.emplace_back(".png", t, c);
    for (SampleType t : {SampleType::u8, SampleType::u16, SampleType::f32}) cases.emplace_back(".tif", t, c);
    for (SampleType t : {SampleType::f16, SampleType::f32}) cases.emplace_back(".exr", t, c);
  }
  for (SampleType t : {SampleType::u8, SampleType::u16}) {  // binary PGM/PPM: tools/pnm_io.cpp
    cases.emplace_back(".pgm", t, 1);
    cases.emplace_back(".ppm", t, 3);
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllFormats, LosslessRoundTrip, ::testing::ValuesIn(lossless_cases()));

// Formats that cannot hold a type store the closest exact one: half in TIFF becomes float.
TEST(ImageIo, HalfInTiffIsStoredExactlyAsFloat) {
  const Image img = random_image(11, 7, 3, SampleType::f16, 5);
  const fs::path path = scratch_dir() / "half.tif";
  SampleType stored = SampleType::u8;
  write_image(img, path, &stored);
  EXPECT_EQ(stored, SampleType::f32);
  const Image back = read_image(path);
  EXPECT_EQ(back.type, SampleType::f32);
  EXPECT_EQ(back.samples, img.samples);
  fs::remove(path);
}

TEST(ImageIo, JpegRoundTripIsCloseAndEightBit) {
  const Image img = read_image(fs::path(PUPWAVE_TESTIMAGES_DIR) / "astronaut.png");
  const fs::path path = scratch_dir() / "astronaut.jpg";
  write_image(img, path);
  const Image back = read_image(path);
  ASSERT_EQ(back.type, SampleType::u8);
  ASSERT_EQ(back.samples.size(), img.samples.size());
  double sq = 0;
  for (std::size_t i = 0; i < img.samples.size(); ++i) sq += std::pow(img.samples[i] - back.samples[i], 2);
  EXPECT_LT(sq / double(img.samples.size()), 10.0);  // quality 95: well above 38 dB
  fs::remove(path);
}

TEST(ImageIo, ReadsTheBundledPhotographs) {
  const fs::path dir(PUPWAVE_TESTIMAGES_DIR);
  const std::tuple<const char*, std::size_t, std::size_t, std::size_t> expected[] = {
      {"camera.png", 512, 512, 1},
      {"astronaut.png", 512, 512, 3},
      {"coffee.png", 600, 400, 3},
      {"chelsea.png", 451, 300, 3}};
  for (const auto& [name, w, h, c] : expected) {
    const Image img = read_image(dir / name);
    EXPECT_EQ(img.width, w) << name;
    EXPECT_EQ(img.height, h) << name;
    EXPECT_EQ(img.channels, c) << name;
    EXPECT_EQ(img.type, SampleType::u8) << name;
    const auto [lo, hi] = std::minmax_element(img.samples.begin(), img.samples.end());
    EXPECT_GE(*lo, 0.0f);
    EXPECT_LE(*hi, 255.0f);
    EXPECT_GT(*hi - *lo, 100.0f) << name << " looks flat";
  }
}

TEST(ImageIo, FloatToPngIsConvertedThroughTheNominalRange) {
  Image img(4, 1, 1, SampleType::f32);
  img.samples = {0.0f, 0.5f, 1.0f, 2.0f};
  const fs::path path = scratch_dir() / "float.png";
  SampleType stored = SampleType::u8;
  write_image(img, path, &stored);
  EXPECT_EQ(stored, SampleType::u16);
  const Image back = read_image(path);
  EXPECT_EQ(back.samples, (std::vector<float>{0.0f, 32768.0f, 65535.0f, 65535.0f}));
  fs::remove(path);
}

TEST(ImageIo, AlphaIsNotPremultiplied) {
  Image img(2, 1, 4, SampleType::u8);
  img.samples = {200, 10, 100, 20, 50, 30, 0, 255};  // planar R,G,B,A; first pixel alpha 0
  const fs::path path = scratch_dir() / "alpha.png";
  write_image(img, path);
  EXPECT_EQ(read_image(path).samples, img.samples);
  fs::remove(path);
}

TEST(ImageIo, ClearErrorsForBadInput) {
  const fs::path dir = scratch_dir();
  EXPECT_THROW(read_image(dir / "missing.png"), std::runtime_error);
  EXPECT_THROW(read_image(dir), std::runtime_error);
  const fs::path junk = dir / "junk.png";
  std::ofstream(junk) << "this is not a png";
  try {
    read_image(junk);
    ADD_FAILURE() << "junk accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("junk.png"), std::string::npos) << e.what();
  }
  const Image img(3, 3, 1, SampleType::u8);
  EXPECT_THROW(write_image(img, dir / "out.unknownext"), std::runtime_error);
  EXPECT_THROW(write_image(img, dir), std::runtime_error);
  EXPECT_THROW(write_image(img, dir / "no_such_folder" / "x.png"), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir / "out.unknownext"));
}

// Binary PPM: the header is plain text, 16-bit samples big-endian; truncated or absurd headers
// are refused before any raster is allocated.
TEST(ImageIo, BinaryPnmLayoutAndBadHeaders) {
  const fs::path dir = scratch_dir();
  Image img(2, 1, 3, SampleType::u16);
  img.at(0, 0, 0) = 258;  // 0x0102
  img.at(2, 1, 0) = 65535;
  write_image(img, dir / "two.ppm");
  std::ifstream in(dir / "two.ppm", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), std::string("P6\n2 1\n65535\n").size() + 12);
  EXPECT_EQ(bytes.substr(0, 13), "P6\n2 1\n65535\n");
  EXPECT_EQ(bytes[13], 1);  // first sample, high byte first
  EXPECT_EQ(bytes[14], 2);
  EXPECT_EQ(std::uint8_t(bytes[23]), 255);  // blue of the second pixel

  std::ofstream(dir / "short.ppm", std::ios::binary) << "P6\n4 4\n255\n" << std::string(40, 'x');
  EXPECT_THROW(read_image(dir / "short.ppm"), std::runtime_error);
  std::ofstream(dir / "huge.pgm", std::ios::binary) << "P5\n4000000000 4000000000\n255\n";
  EXPECT_THROW(read_image(dir / "huge.pgm"), std::runtime_error);
  std::ofstream(dir / "bad.pgm", std::ios::binary) << "P5\n12 x\n255\n";
  EXPECT_THROW(read_image(dir / "bad.pgm"), std::runtime_error);
}

// Strip-by-strip PGM writing (the writer runs on its own thread): strips land in order, a
// strip of the wrong shape, a producer that throws and a full device are errors, not hangs.
TEST(ImageIo, PnmRowsWriterKeepsOrderAndReportsFailures) {
  const fs::path dir = scratch_dir();
  const std::size_t width = 7, height = 50;
  Image whole(width, height, 1, SampleType::u8);
  for (std::size_t i = 0; i < whole.samples.size(); ++i) whole.samples[i] = float((i * 37) % 251);
  auto strips_of = [&](std::size_t rows) {
    return [&whole, rows, y = std::size_t(0)]() mutable {
      const std::size_t n = std::min(rows, whole.height - y);
      Image strip(whole.width, n, 1, SampleType::u8);
      std::copy_n(whole.plane(0) + y * whole.width, n * whole.width, strip.plane(0));
      y += n;
      return strip;
    };
  };
  write_binary_pnm_rows(dir / "rows.pgm", width, height, 1, SampleType::u8, strips_of(3));
  write_image(whole, dir / "whole.pgm");
  auto bytes = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(bytes(dir / "rows.pgm"), bytes(dir / "whole.pgm"));

  EXPECT_THROW(write_binary_pnm_rows(dir / "short.pgm", width, height + 1, 1, SampleType::u8, strips_of(4)),
               std::runtime_error);  // the producer ends early: an empty strip
  int calls = 0;
  EXPECT_THROW(write_binary_pnm_rows(dir / "throws.pgm", width, height, 1, SampleType::u8,
                                     [&]() -> Image {
                                       if (++calls == 3) throw std::logic_error("decoder failed");
                                       return strips_of(2)();
                                     }),
               std::logic_error);
  EXPECT_THROW(write_binary_pnm_rows("/dev/full", 4096, 4096, 1, SampleType::u8,
                                     [] { return Image(4096, 64, 1, SampleType::u8); }),
               std::runtime_error);  // every write fails: the device is full
}

}  // namespace
}  // namespace pupwave::cli

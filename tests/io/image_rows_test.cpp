// Image files read and written a strip of rows at a time (open_image_rows, write_image_rows: the
// path of `pupwave convert`) give what the whole-image read_image and write_image give: the
// same samples, type and metadata, on the test photographs and the HDR image, for scanline and
// tiled files, mapped 8-bit and read-whole 16-bit PGM/PPM.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/io_test_files.h"
#include "tools/image_io.h"

namespace pupwave::cli {
namespace {
using namespace pupwave::test;

fs::path testimage(const std::string& name) { return fs::path(PUPWAVE_TESTIMAGES_DIR) / name; }

// The whole image gathered from strips of `rows` rows.
Image read_by_strips(const fs::path& path, std::size_t rows) {
  const auto reader = open_image_rows(path);
  Image out(reader->width(), reader->height(), reader->channels(), reader->type());
  out.metadata = reader->metadata();
  std::size_t y0 = 0;
  for (Image strip = reader->next(rows); strip.height > 0; strip = reader->next(rows)) {
    EXPECT_LE(strip.height, rows) << path;
    EXPECT_LE(y0 + strip.height, out.height) << path;
    if (y0 + strip.height > out.height) break;
    for (std::size_t c = 0; c < out.channels; ++c)
      std::copy_n(strip.plane(c), strip.plane_size(), out.plane(c) + y0 * out.width);
    y0 += strip.height;
  }
  EXPECT_EQ(y0, out.height) << path;
  return out;
}

class ImageRows : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = scratch_dir();
    // A 16-bit PPM (read whole) and a tiled TIFF (read whole by OpenImageIO's tiles).
    Image astronaut = read_image(testimage("astronaut.png"));
    Image wide = astronaut;
    wide.type = SampleType::u16;
    for (float& v : wide.samples) v = v * 257.0f;
    write_image(wide, dir_ / "astronaut16.ppm");
    OIIO::ImageSpec spec(int(astronaut.width), int(astronaut.height), 3, OIIO::TypeDesc::UINT8);
    spec.tile_width = spec.tile_height = 64;
    std::vector<std::uint8_t> interleaved(astronaut.samples.size());
    for (std::size_t c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < astronaut.plane_size(); ++i)
        interleaved[i * 3 + c] = std::uint8_t(astronaut.plane(c)[i]);
    auto out = OIIO::ImageOutput::create((dir_ / "tiled.tif").string());
    ASSERT_TRUE(out && out->open((dir_ / "tiled.tif").string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, interleaved.data()));
    ASSERT_TRUE(out->close());
    write_image(astronaut, dir_ / "astronaut.ppm");
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path ImageRows::dir_;

TEST_F(ImageRows, StripsGiveReadImage) {
  const fs::path files[] = {testimage("astronaut.png"),  testimage("camera.png"), testimage("coffee.png"),
                            testimage("forest_hdr.exr"), dir_ / "astronaut.ppm",  dir_ / "astronaut16.ppm",
                            dir_ / "tiled.tif"};
  for (const fs::path& file : files)
    for (std::size_t rows : {std::size_t(7), std::size_t(64), std::size_t(100000)})
      expect_same_image(read_by_strips(file, rows), read_image(file),
                        file.string() + " by " + std::to_string(rows));
}

TEST_F(ImageRows, TiledFileIsTiled) {
  auto in = OIIO::ImageInput::open((dir_ / "tiled.tif").string());
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().tile_width, 64);  // the tiled branch of the reader is the one exercised
}

// write_image_rows writes what write_image writes: the same samples, type and metadata read
// back, and the same bytes for PGM/PPM; sample types converted the same way.
TEST_F(ImageRows, RowWriterGivesWriteImage) {
  const std::pair<fs::path, std::string> cases[] = {
      {testimage("astronaut.png"), "ppm"},  {dir_ / "astronaut.ppm", "png"},
      {testimage("camera.png"), "pgm"},     {testimage("forest_hdr.exr"), "png"},
      {testimage("forest_hdr.exr"), "exr"}, {dir_ / "astronaut16.ppm", "jpg"},
      {testimage("coffee.png"), "tif"}};
  for (const auto& [input, extension] : cases) {
    const std::string what = input.filename().string() + " -> " + extension;
    const fs::path whole = dir_ / ("whole." + extension), rows = dir_ / ("rows." + extension);
    SampleType whole_type{}, rows_type{};
    write_image(read_image(input), whole, &whole_type);
    const auto reader = open_image_rows(input);
    rows_type = write_image_rows(*reader, rows);
    EXPECT_EQ(rows_type, whole_type) << what;
    expect_same_image(read_image(rows), read_image(whole), what);
    if (extension == "ppm" || extension == "pgm") EXPECT_EQ(file_bytes(rows), file_bytes(whole)) << what;
  }
}

}  // namespace
}  // namespace pupwave::cli

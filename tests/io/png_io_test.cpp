// PNG read and written with libpng (tools/png_io.h) against OpenImageIO's reading of the same
// files (the module's read): the same samples, type, channels and metadata on the test
// photographs and on files of every colour type and depth; the kinds left to OpenImageIO go
// there; corrupt, truncated and hostile files are clear errors; and the CLI's PNG commands do
// not load the OpenImageIO module.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "cli/run_cli.h"
#include "io/io_test_files.h"
#include "tools/image_io.h"
#include "tools/oiio_module.h"
#include "tools/png_io.h"

namespace pupwave::cli {
namespace {
using namespace pupwave::test;
using namespace std::string_literals;

// --- PNG files built chunk by chunk, for the kinds a libpng writer here never makes ---

std::string be32(std::uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

std::string chunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  const auto crc = std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size())));
  return be32(std::uint32_t(data.size())) + body + be32(crc);
}

// A PNG of this header whose image data is `raw` (filter bytes included), with `extra` chunks
// between IHDR and IDAT.
std::string png_file(std::uint32_t w, std::uint32_t h, int depth, int color, int interlace,
                     const std::string& raw, const std::string& extra = "") {
  uLongf size = compressBound(uLong(raw.size()));
  std::string packed(size, '\0');
  compress(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()),
           uLong(raw.size()));
  packed.resize(size);
  const std::string ihdr = be32(w) + be32(h) + char(depth) + char(color) + '\0' + '\0' + char(interlace);
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + extra + chunk("IDAT", packed) +
         chunk("IEND", "");
}

// `rows` rows of `row_bytes` bytes each, filter type 0, bytes counting up from `seed`.
std::string raw_rows(std::size_t rows, std::size_t row_bytes, unsigned seed) {
  std::string raw;
  for (std::size_t y = 0; y < rows; ++y) {
    raw += '\0';
    for (std::size_t x = 0; x < row_bytes; ++x) raw += char((seed + y * 31 + x * 7) & 0xff);
  }
  return raw;
}

// --- reading ---

TEST(PngIo, PhotographsReadAsOpenImageIoReadsThem) {
  for (const char* name : {"camera.png", "astronaut.png", "coffee.png", "chelsea.png"}) {
    const auto native = read_png(testimage(name));
    ASSERT_TRUE(native.has_value()) << name << " was left to OpenImageIO";
    expect_same_image(*native, oiio_module().read(testimage(name)), name);
    EXPECT_TRUE(native->metadata.empty()) << name;
  }
}

TEST(PngIo, SixteenBitPhotographReadsAsOpenImageIoReadsIt) {
  const fs::path dir = scratch_dir();
  Image wide = read_image(testimage("coffee.png"));
  wide.type = SampleType::u16;
  for (std::size_t i = 0; i < wide.samples.size(); ++i)
    wide.samples[i] = wide.samples[i] * 256.0f + float(i % 7);
  const fs::path path = dir / "coffee16.png";
  oiio_module().write(wide, path, path);  // written by OpenImageIO, read natively
  const auto native = read_png(path);
  ASSERT_TRUE(native.has_value());
  expect_same_image(*native, wide, "coffee16 against what was written");
  expect_same_image(*native, oiio_module().read(path), "coffee16 against OpenImageIO");
  fs::remove(path);
}

TEST(PngIo, RowsInStripsGiveTheWholeImage) {
  const auto rows = open_png_rows(testimage("chelsea.png"));
  ASSERT_TRUE(rows);
  const Image whole = oiio_module().read(testimage("chelsea.png"));
  Image gathered(rows->width(), rows->height(), rows->channels(), rows->type());
  std::size_t y0 = 0;
  for (Image strip = rows->next(7); strip.height > 0; strip = rows->next(7)) {
    ASSERT_LE(y0 + strip.height, gathered.height);
    for (std::size_t c = 0; c < gathered.channels; ++c)
      std::copy_n(strip.plane(c), strip.plane_size(), gathered.plane(c) + y0 * gathered.width);
    y0 += strip.height;
  }
  EXPECT_EQ(y0, whole.height);
  EXPECT_TRUE(gathered.samples == whole.samples);
}

// The data window origin of an oFFs chunk in pixels, as OpenImageIO reads it; one in micrometres
// is no origin for either.
TEST(PngIo, OffsetChunkGivesOpenImageIosOrigin) {
  const fs::path dir = scratch_dir();
  const std::string raw = raw_rows(2, 3 * 3, 11);
  const auto offs = [](std::int32_t x, std::int32_t y, char unit) {
    return chunk("oFFs", be32(std::uint32_t(x)) + be32(std::uint32_t(y)) + unit);
  };
  put_bytes(dir / "pixels.png", png_file(3, 2, 8, 2, 0, raw, offs(5, -7, 0)));
  put_bytes(dir / "microns.png", png_file(3, 2, 8, 2, 0, raw, offs(5, -7, 1)));
  const auto pixels = read_png(dir / "pixels.png");
  ASSERT_TRUE(pixels.has_value());
  EXPECT_EQ(pixels->metadata.x, 5);
  EXPECT_EQ(pixels->metadata.y, -7);
  expect_same_image(*pixels, oiio_module().read(dir / "pixels.png"), "oFFs in pixels");
  const auto microns = read_png(dir / "microns.png");
  ASSERT_TRUE(microns.has_value());
  EXPECT_TRUE(microns->metadata.empty());
  expect_same_image(*microns, oiio_module().read(dir / "microns.png"), "oFFs in micrometres");
}

// Palette, 1-bit, tRNS and interlaced files are OpenImageIO's (it expands them): read_image
// gives what it gives.
TEST(PngIo, OtherKindsAreLeftToOpenImageIo) {
  const fs::path dir = scratch_dir();
  const std::string plte = chunk("PLTE", std::string("\x00\x00\x00\xff\x80\x10\x20\x40\xff", 9));
  const struct {
    const char* name;
    std::string bytes;
  } files[] = {
      {"palette.png", png_file(4, 2, 8, 3, 0, std::string("\0\0\1\2\1\0\2\1\0\2", 10), plte)},
      {"onebit.png", png_file(16, 2, 1, 0, 0, raw_rows(2, 2, 3))},
      {"trns.png",
       png_file(3, 2, 8, 2, 0, raw_rows(2, 9, 5), chunk("tRNS", std::string("\0\x07\0\x0e\0\x15", 6)))},
      // Adam7 of a 1 x 1 image: only the first pass has a pixel.
      {"interlaced.png", png_file(1, 1, 8, 2, 1, std::string("\0\x10\x20\x30", 4))},
  };
  for (const auto& f : files) {
    put_bytes(dir / f.name, f.bytes);
    EXPECT_FALSE(read_png(dir / f.name).has_value()) << f.name;
    EXPECT_FALSE(open_png_rows(dir / f.name)) << f.name;
    expect_same_image(read_image(dir / f.name), oiio_module().read(dir / f.name), f.name);
  }
  EXPECT_FALSE(read_png(testimage("forest_hdr.exr")).has_value());  // not a PNG at all
}

// --- writing ---

class PngRoundTrip : public ::testing::TestWithParam<std::tuple<SampleType, std::size_t>> {};

TEST_P(PngRoundTrip, WrittenNativelyReadsBackIdenticallyBothWays) {
  const auto [type, channels] = GetParam();
  Image img = random_image(29, 17, channels, type, unsigned(channels * 13 + int(type)));
  img.metadata.x = 3;
  img.metadata.y = -2;
  const fs::path path =
      scratch_dir() / ("rt_" + std::to_string(int(type)) + "_" + std::to_string(channels) + ".png");
  ASSERT_TRUE(png_writable(path, channels, type, img.metadata));
  write_png(img, path);
  const auto native = read_png(path);
  ASSERT_TRUE(native.has_value());
  expect_same_image(*native, img, "native read");
  expect_same_image(oiio_module().read(path), img, "OpenImageIO read");
  fs::remove(path);
}

INSTANTIATE_TEST_SUITE_P(GreyToRgba, PngRoundTrip,
                         ::testing::Combine(::testing::Values(SampleType::u8, SampleType::u16),
                                            ::testing::Values(1, 2, 3, 4)));

// The chunks of a PNG file other than its image data, each as its type and contents; a zero oFFs
// (which OpenImageIO writes and the native writer leaves out, read alike) is skipped.
std::vector<std::string> png_chunks_of(const fs::path& path) {
  const std::string bytes = file_bytes(path);
  std::vector<std::string> chunks;
  for (std::size_t at = 8; at + 12 <= bytes.size();) {
    const auto byte = [&](std::size_t i) { return std::uint32_t(std::uint8_t(bytes[at + i])); };
    const std::size_t size = byte(0) << 24 | byte(1) << 16 | byte(2) << 8 | byte(3);
    const std::string type = bytes.substr(at + 4, 4), data = bytes.substr(at + 8, size);
    if (type != "IDAT" && !(type == "oFFs" && data == std::string(9, '\0')))
      chunks.push_back(type + ":" + data);
    at += 12 + size;
  }
  return chunks;
}

// forest_hdr.exr's attributes (as the module reads them) and the usual string ones, as 16-bit.
Image forest_with_text() {
  Image img = convert_sample_type(oiio_module().read(testimage("forest_hdr.exr")), SampleType::u16);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"ImageDescription", "a forest"},
                                   {"Artist", "A. Painter"},
                                   {"Copyright", "(c) nobody"},
                                   {"DocumentName", "forest"},
                                   {"Exif:Comment", "text"}})
    img.metadata.attributes.push_back({name, ImageAttribute::Kind::string, text, 0, 0.0});
  return img;
}

TEST(PngIo, AttributesAreWrittenAsOpenImageIoWritesThem) {
  const Image img = forest_with_text();
  const fs::path dir = scratch_dir();
  ASSERT_TRUE(png_writable(dir / "native.png", 3, SampleType::u16, img.metadata));
  write_png(img, dir / "native.png");
  oiio_module().write(img, dir / "oiio.png", dir / "oiio.png");
  const std::vector<std::string> native = png_chunks_of(dir / "native.png");
  EXPECT_EQ(native, png_chunks_of(dir / "oiio.png"));
  // The comparison can fail: IHDR, pHYs (PixelAspectRatio), tIME (DateTime), seven tEXt, IEND.
  EXPECT_EQ(native.size(), 11u);
  EXPECT_NE(std::find(native.begin(), native.end(), "tIME:\x07\xe2\x08\x11\x0f\x0b\x0f"s), native.end());
  EXPECT_NE(std::find(native.begin(), native.end(), "tEXt:Author\0A. Painter"s), native.end());
  expect_same_image(read_image(dir / "native.png"), oiio_module().read(dir / "oiio.png"), "read back");
}

// The linear colour space (gAMA and text), an unreadable DateTime and numbers (both dropped).
TEST(PngIo, ColourSpaceAndDroppedAttributesAreWrittenAsOpenImageIoWritesThem) {
  Image img = random_image(13, 7, 4, SampleType::u8, 5);
  img.metadata.attributes = {{"oiio:ColorSpace", ImageAttribute::Kind::string, "Linear", 0, 0},
                             {"DateTime", ImageAttribute::Kind::string, "yesterday", 0, 0},
                             {"planarconfig", ImageAttribute::Kind::string, "contig", 0, 0},
                             {"Orientation", ImageAttribute::Kind::integer, "", 1, 0}};
  const fs::path dir = scratch_dir();
  ASSERT_TRUE(png_writable(dir / "native.png", 4, SampleType::u8, img.metadata));
  write_png(img, dir / "native.png");
  oiio_module().write(img, dir / "oiio.png", dir / "oiio.png");
  const std::vector<std::string> native = png_chunks_of(dir / "native.png");
  EXPECT_EQ(native, png_chunks_of(dir / "oiio.png"));
  EXPECT_NE(std::find(native.begin(), native.end(), "gAMA:\0\x01\x86\xa0"s), native.end());
}

// Attributes OpenImageIO stores in ways not written here leave the image to it.
TEST(PngIo, AttributesWrittenOtherwiseAreLeftToOpenImageIo) {
  for (const ImageAttribute& a :
       {ImageAttribute{"XResolution", ImageAttribute::Kind::real, "", 0, 72.0},
        ImageAttribute{"PixelAspectRatio", ImageAttribute::Kind::real, "", 0, 2.0},
        ImageAttribute{"oiio:ColorSpace", ImageAttribute::Kind::string, "sRGB", 0, 0},
        ImageAttribute{"png:compressionLevel", ImageAttribute::Kind::integer, "", 3, 0},
        ImageAttribute{"DateTime", ImageAttribute::Kind::string, "2020:13:01 00:00:00", 0, 0},
        ImageAttribute{" spaced", ImageAttribute::Kind::string, "x", 0, 0}}) {
    ImageMetadata m;
    m.attributes.push_back(a);
    EXPECT_FALSE(png_writable("a.png", 3, SampleType::u8, m)) << a.name;
  }
}

TEST(PngIo, RowWriterWritesWhatTheWholeImageWriterWrites) {
  const fs::path dir = scratch_dir();
  const Image whole = read_image(testimage("astronaut.png"));
  std::size_t y = 0;
  const auto next = [&] {
    const std::size_t n = std::min<std::size_t>(13, whole.height - y);
    Image strip(whole.width, n, whole.channels, whole.type);
    for (std::size_t c = 0; c < whole.channels; ++c)
      std::copy_n(whole.plane(c) + y * whole.width, n * whole.width, strip.plane(c));
    y += n;
    return strip;
  };
  write_png_rows(dir / "rows.png", whole.width, whole.height, whole.channels, whole.type, whole.metadata,
                 next);
  write_png(whole, dir / "whole.png");
  EXPECT_EQ(file_bytes(dir / "rows.png"), file_bytes(dir / "whole.png"));
  expect_same_image(oiio_module().read(dir / "rows.png"), whole, "rows.png");
  y = 0;
  EXPECT_THROW(write_png_rows(dir / "short.png", whole.width, whole.height + 1, whole.channels, whole.type,
                              whole.metadata, next),
               std::runtime_error);  // the strips end early
  EXPECT_THROW(write_png(whole, "/dev/full"), std::runtime_error);
}

// What libpng cannot hold natively (5 channels, float, attributes) is not taken.
TEST(PngIo, WritableOnlyForWhatPngHoldsWithoutOpenImageIo) {
  ImageMetadata none;
  EXPECT_TRUE(png_writable("a.PNG", 4, SampleType::u16, none));
  EXPECT_FALSE(png_writable("a.png", 5, SampleType::u8, none));
  EXPECT_FALSE(png_writable("a.png", 3, SampleType::f32, none));
  EXPECT_FALSE(png_writable("a.tif", 3, SampleType::u8, none));
  ImageMetadata with_text;
  with_text.attributes.push_back(ImageAttribute{});
  EXPECT_FALSE(png_writable("a.png", 3, SampleType::u8, with_text));
}

// --- bad files ---

void expect_read_error(const fs::path& path, const std::string& why) {
  try {
    (void)read_image(path);
    ADD_FAILURE() << path << " was read";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(why), std::string::npos) << message;
  }
}

TEST(PngIo, TruncatedAndCorruptFilesAreErrorsNamingThePath) {
  const fs::path dir = scratch_dir();
  const std::string coffee = file_bytes(testimage("coffee.png"));
  put_bytes(dir / "truncated.png", coffee.substr(0, coffee.size() / 2));
  expect_read_error(dir / "truncated.png", "cannot read");
  std::string corrupt = coffee;
  const std::size_t idat = corrupt.find("IDAT");
  ASSERT_NE(idat, std::string::npos);
  corrupt[idat + 100] = char(corrupt[idat + 100] ^ 0x55);
  put_bytes(dir / "corrupt.png", corrupt);
  expect_read_error(dir / "corrupt.png", "IDAT");  // libpng's zlib or CRC error, whichever comes first
  EXPECT_THROW((void)oiio_module().read(dir / "corrupt.png"), std::runtime_error);  // as before
  put_bytes(dir / "header_only.png", coffee.substr(0, 20));
  expect_read_error(dir / "header_only.png", "cannot read");
}

// A header promising more samples than kMaxImageSamples is refused before the pixels are
// allocated (an allocation of that size would throw std::bad_alloc instead); sides over libpng's
// limit are refused by libpng.
TEST(PngIo, HostileHeadersAreRefused) {
  const fs::path dir = scratch_dir();
  put_bytes(dir / "huge.png", png_file(1000000, 1000000, 16, 6, 0, raw_rows(1, 8, 0)));
  expect_read_error(dir / "huge.png", "too large");
  put_bytes(dir / "wide.png", png_file(0x7fffffff, 1, 8, 0, 0, raw_rows(1, 8, 0)));
  expect_read_error(dir / "wide.png", "wide.png");
  // Within kMaxImageSamples but more than deflate could expand the file to: refused before the
  // 1.6 GB of samples are allocated.
  put_bytes(dir / "claims.png", png_file(20000, 20000, 8, 0, 0, raw_rows(1, 8, 0)));
  expect_read_error(dir / "claims.png", "cannot hold the 20000x20000 image");
}

// --- the CLI ---

// Whether running the CLI with these arguments dlopens the OpenImageIO module (glibc's loader
// names every file it loads under LD_DEBUG=files); the command must succeed.
bool cli_loads_openimageio(const std::string& args) {
  const auto result = test::run_shell_output("LD_DEBUG=files " + test::shell_quote(PUPWAVE_CLI) + " " + args +
                                             " 2>&1 >/dev/null </dev/null");
  EXPECT_EQ(result.exit_code, 0) << args << "\n" << result.output;
  return result.output.find("pupwave_oiio") != std::string::npos;
}

TEST(PngCli, PngCommandsDoNotLoadOpenImageIo) {
  const fs::path dir = scratch_dir();
  const std::string png = test::shell_quote(testimage("astronaut.png").string());
  const auto at = [&](const char* name) { return test::shell_quote((dir / name).string()); };
  EXPECT_FALSE(cli_loads_openimageio("convert -q " + png + " " + at("a.ppm")));
  EXPECT_FALSE(cli_loads_openimageio("convert -q " + at("a.ppm") + " " + at("a.png")));
  EXPECT_FALSE(cli_loads_openimageio("compress -q " + png + " " + at("a.pw")));
  EXPECT_FALSE(cli_loads_openimageio("decompress -q " + at("a.pw") + " " + at("b.png")));
  expect_same_image(read_image(dir / "a.png"), oiio_module().read(testimage("astronaut.png")), "a.png");
  // The check can fail: a BMP still goes through OpenImageIO.
  EXPECT_TRUE(cli_loads_openimageio("convert -q " + at("a.png") + " " + at("a.bmp")));
}

}  // namespace
}  // namespace pupwave::cli

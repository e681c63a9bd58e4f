// OpenEXR, TIFF and JPEG read and written here (tools/exr_io.h, tiff_io.h, jpeg_io.h) against
// OpenImageIO's reading of the same files (the module's read): the same samples, type, channel
// names and kept metadata on files OpenImageIO writes from the test photographs; round trips of
// every sample type; the kinds left to OpenImageIO go there; corrupt and truncated files are
// errors naming the file; and the CLI's commands on these formats do not load the module.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "cli/run_cli.h"
#include "io/io_test_files.h"
#include "tools/exr_io.h"
#include "tools/image_io.h"
#include "tools/jpeg_io.h"
#include "tools/oiio_module.h"
#include "tools/tiff_io.h"

namespace pupwave::cli {
namespace {
using namespace pupwave::test;
using namespace std::string_literals;

Image photograph(const char* name) { return read_image(fs::path(PUPWAVE_TESTIMAGES_DIR) / name); }

// The photograph's samples in another type, through the nominal range (255 <-> 65535 <-> 1.0).
Image photograph_as(const char* name, SampleType type) { return convert_sample_type(photograph(name), type); }

// The first `channels` planes of an image (a grey photograph repeated for more).
Image with_channels(const Image& from, std::size_t channels) {
  Image out(from.width, from.height, channels, from.type);
  for (std::size_t c = 0; c < channels; ++c)
    std::copy_n(from.plane(c % from.channels), from.plane_size(), out.plane(c));
  return out;
}

// Writes `image` to dir/name with OpenImageIO, then reads it with `native` and with OpenImageIO.
template <class Read>
void expect_read_as_openimageio_reads(const Image& image, const std::string& name, Read native) {
  const fs::path path = scratch_dir() / name;
  oiio_module().write(image, path, path);
  const auto read = native(path);
  ASSERT_TRUE(read.has_value()) << name << " was left to OpenImageIO";
  expect_same_image(*read, oiio_module().read(path), name);
}

// A copy of the file cut to `keep` bytes.
fs::path truncated_copy(const fs::path& path, std::size_t keep) {
  const fs::path cut = path.parent_path() / ("cut_" + path.filename().string());
  std::ofstream(cut, std::ios::binary) << file_bytes(path).substr(0, keep);
  return cut;
}

// Reads every row of the file natively; the error's message.
template <class Open>
std::string read_error(const fs::path& path, Open open) {
  try {
    auto rows = open(path);
    if (!rows) return "left to OpenImageIO";
    while (rows->next(16).height > 0) {
    }
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// --- OpenEXR ---

TEST(ExrIo, TestImageReadsAsOpenImageIoReadsIt) {
  const fs::path path = fs::path(PUPWAVE_TESTIMAGES_DIR) / "forest_hdr.exr";
  const auto native = read_exr(path);
  ASSERT_TRUE(native.has_value());
  EXPECT_EQ(native->metadata.attributes.size(), 6u);  // Software, DateTime, Orientation...
  expect_same_image(*native, oiio_module().read(path), "forest_hdr.exr");
}

TEST(ExrIo, FilesOpenImageIoWritesReadAsItReadsThem) {
  const auto read = [](const fs::path& p) { return read_exr(p); };
  expect_read_as_openimageio_reads(photograph_as("chelsea.png", SampleType::f32), "float.exr", read);
  expect_read_as_openimageio_reads(photograph_as("camera.png", SampleType::f16), "grey.exr", read);
  Image rgba = with_channels(photograph_as("astronaut.png", SampleType::f16), 4);
  expect_read_as_openimageio_reads(rgba, "rgba.exr", read);
  // Layers, an X/Y layer, a data window and a display window, attributes of every kept kind.
  Image layered = with_channels(photograph_as("coffee.png", SampleType::f16), 6);
  layered.metadata.channel_names = {"diffuse.R", "diffuse.G", "diffuse.B", "P.X", "P.Y", "P.A"};
  layered.metadata.x = 10;
  layered.metadata.y = -4;
  layered.metadata.full_x = 0;
  layered.metadata.full_y = 0;
  layered.metadata.full_width = 700;
  layered.metadata.full_height = 500;
  layered.metadata.attributes = {{"Software", ImageAttribute::Kind::string, "pupwave test", 0, 0.0},
                                 {"DateTime", ImageAttribute::Kind::string, "2024:01:02 03:04:05", 0, 0.0},
                                 {"frame", ImageAttribute::Kind::integer, {}, 42, 0.0},
                                 {"XResolution", ImageAttribute::Kind::real, {}, 0, 300.0},
                                 {"ExposureTime", ImageAttribute::Kind::real, {}, 0, 0.125}};
  expect_read_as_openimageio_reads(layered, "layered.exr", read);
}

TEST(ExrIo, RoundTripsKeepSamplesNamesWindowsAndAttributes) {
  for (SampleType type : {SampleType::f16, SampleType::f32}) {
    for (std::size_t channels = 1; channels <= 4; ++channels) {
      Image image = with_channels(photograph_as("chelsea.png", type), channels);
      image.metadata.x = 3;
      image.metadata.y = 5;
      image.metadata.attributes = {{"note", ImageAttribute::Kind::string, "kept", 0, 0.0}};
      const fs::path path = scratch_dir() / ("rt" + std::to_string(channels) + to_string(type) + ".exr");
      ASSERT_TRUE(exr_writable(path, type, image.metadata));
      write_exr(image, path);
      const auto back = read_exr(path);
      ASSERT_TRUE(back.has_value());
      EXPECT_EQ(back->type, type);
      EXPECT_TRUE(back->samples == image.samples) << path;
      EXPECT_EQ(back->metadata.x, 3);
      EXPECT_EQ(back->metadata.y, 5);
      EXPECT_TRUE(back->metadata.channel_names.empty()) << "default names are not stored";
      ASSERT_FALSE(back->metadata.attributes.empty());
      EXPECT_EQ(back->metadata.attributes.front().text, "kept");
      expect_same_image(*back, oiio_module().read(path), path.string());
    }
  }
}

TEST(ExrIo, WrittenInStripsAsWholeAndNamedChannelsKept) {
  Image image = with_channels(photograph_as("coffee.png", SampleType::f16), 3);
  image.metadata.channel_names = {"Y", "BY", "RY"};
  const fs::path whole = scratch_dir() / "whole.exr", strips = scratch_dir() / "strips.exr";
  write_exr(image, whole);
  std::size_t y0 = 0;
  write_exr_rows(strips, image.width, image.height, 3, SampleType::f16, image.metadata, [&] {
    const std::size_t rows = std::min<std::size_t>(50, image.height - y0);
    Image strip(image.width, rows, 3, SampleType::f16);
    for (std::size_t c = 0; c < 3; ++c)
      std::copy_n(image.plane(c) + y0 * image.width, rows * image.width, strip.plane(c));
    y0 += rows;
    return strip;
  });
  EXPECT_EQ(file_bytes(whole), file_bytes(strips));
  const auto back = read_exr(strips);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->metadata.channel_names, std::vector<std::string>({"Y", "BY", "RY"}));
  EXPECT_TRUE(back->samples == image.samples);
}

TEST(ExrIo, KindsLeftToOpenImageIoGoThere) {
  // An attribute OpenImageIO reads as a matrix (compress names it as not kept, in its words).
  Image image = photograph_as("camera.png", SampleType::f16);
  const fs::path plain = scratch_dir() / "plain.exr";
  oiio_module().write(image, plain, plain);
  EXPECT_TRUE(read_exr(plain).has_value());
  EXPECT_FALSE(read_exr(fs::path(PUPWAVE_TESTIMAGES_DIR) / "camera.png").has_value());
  // Attributes with names OpenImageIO's writer renames or drops leave writing to it.
  ImageMetadata m;
  m.attributes = {{"ImageDescription", ImageAttribute::Kind::string, "x", 0, 0.0}};
  EXPECT_FALSE(exr_writable("a.exr", SampleType::f16, m));
  m.attributes = {{"oiio:ColorSpace", ImageAttribute::Kind::string, "Linear", 0, 0.0}};
  EXPECT_FALSE(exr_writable("a.exr", SampleType::f16, m));
  EXPECT_FALSE(exr_writable("a.exr", SampleType::u8, {}));
}

TEST(ExrIo, CorruptAndTruncatedFilesAreErrorsNamingTheFile) {
  const fs::path path = scratch_dir() / "whole_forest.exr";
  fs::copy_file(fs::path(PUPWAVE_TESTIMAGES_DIR) / "forest_hdr.exr", path,
                fs::copy_options::overwrite_existing);
  const auto open = [](const fs::path& p) { return open_exr_rows(p); };
  for (std::size_t keep : {std::size_t(12), std::size_t(300), fs::file_size(path) / 2}) {
    const fs::path cut = truncated_copy(path, keep);
    const std::string error = read_error(cut, open);
    EXPECT_NE(error.find(cut.string()), std::string::npos) << keep << ": " << error;
  }
}

// --- TIFF ---

TEST(TiffIo, FilesOpenImageIoWritesReadAsItReadsThem) {
  const auto read = [](const fs::path& p) { return read_tiff(p); };
  for (SampleType type : {SampleType::u8, SampleType::u16, SampleType::f32})
    for (std::size_t channels = 1; channels <= 4; ++channels)
      expect_read_as_openimageio_reads(with_channels(photograph_as("astronaut.png", type), channels),
                                       "oiio" + std::to_string(channels) + to_string(type) + ".tif", read);
}

TEST(TiffIo, RoundTripsKeepSamplesAndType) {
  for (SampleType type : {SampleType::u8, SampleType::u16, SampleType::f32}) {
    for (std::size_t channels = 1; channels <= 4; ++channels) {
      const Image image = with_channels(photograph_as("coffee.png", type), channels);
      const fs::path path = scratch_dir() / ("rt" + std::to_string(channels) + to_string(type) + ".tiff");
      ASSERT_TRUE(tiff_writable(path, channels, type, image.metadata));
      write_tiff(image, path);
      const auto back = read_tiff(path);
      ASSERT_TRUE(back.has_value());
      expect_same_image(*back, image, path.string());
      expect_same_image(*back, oiio_module().read(path), path.string() + " against OpenImageIO");
    }
  }
}

// The tags of a little-endian TIFF's first directory, each as its number, type, count and value
// (strip offsets and byte counts, which depend on where the writer puts things, left out).
std::vector<std::string> tiff_tags_of(const fs::path& path) {
  const std::string bytes = file_bytes(path);
  const auto u = [&](std::size_t at, int n) {
    std::uint32_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = v << 8 | std::uint8_t(bytes.at(at + std::size_t(i)));
    return std::size_t(v);
  };
  EXPECT_EQ(bytes.substr(0, 2), "II") << path;
  const std::size_t ifd = u(4, 4);
  std::vector<std::string> tags;
  for (std::size_t i = 0, n = u(ifd, 2); i < n; ++i) {
    const std::size_t at = ifd + 2 + 12 * i, tag = u(at, 2), type = u(at + 2, 2), count = u(at + 4, 4);
    if (tag == 273 || tag == 279) continue;
    const std::size_t size = count * (type == 3 ? 2 : type == 4 || type == 11 ? 4 : type == 12 ? 8 : 1);
    const std::string value = size <= 4 ? bytes.substr(at + 8, size) : bytes.substr(u(at + 8, 4), size);
    tags.push_back(std::to_string(tag) + " " + std::to_string(type) + " " + std::to_string(count) + " " +
                   value);
  }
  return tags;
}

TEST(TiffIo, AttributesAreWrittenAsOpenImageIoWritesThem) {
  Image img = convert_sample_type(oiio_module().read(testimage("forest_hdr.exr")), SampleType::f32);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"ImageDescription", "a forest"},
                                   {"Artist", "A. Painter"},
                                   {"Copyright", "(c) nobody"},
                                   {"DocumentName", "forest"}})
    img.metadata.attributes.push_back({name, ImageAttribute::Kind::string, text, 0, 0.0});
  const fs::path dir = scratch_dir();
  ASSERT_TRUE(tiff_writable(dir / "native.tif", 3, SampleType::f32, img.metadata));
  write_tiff(img, dir / "native.tif");
  oiio_module().write(img, dir / "oiio.tif", dir / "oiio.tif");
  const std::vector<std::string> native = tiff_tags_of(dir / "native.tif");
  EXPECT_EQ(native, tiff_tags_of(dir / "oiio.tif"));
  // The comparison can fail: the six ASCII tags are there.
  EXPECT_NE(std::find(native.begin(), native.end(), "315 2 11 A. Painter\0"s), native.end());
  EXPECT_NE(std::find(native.begin(), native.end(), "306 2 20 2018:08:17 15:11:15\0"s), native.end());
  expect_same_image(*read_tiff(dir / "native.tif"), oiio_module().read(dir / "oiio.tif"), "read back");
}

TEST(TiffIo, KindsLeftToOpenImageIoGoThere) {
  for (const ImageAttribute& a :
       {ImageAttribute{"HostComputer", ImageAttribute::Kind::string, "h", 0, 0},
        ImageAttribute{"Orientation", ImageAttribute::Kind::integer, "", 3, 0},
        ImageAttribute{"PixelAspectRatio", ImageAttribute::Kind::real, "", 0, 2.0},
        ImageAttribute{"Exif:ExposureTime", ImageAttribute::Kind::real, "", 0, 0.5}}) {
    ImageMetadata m;
    m.attributes.push_back(a);
    EXPECT_FALSE(tiff_writable("a.tif", 3, SampleType::u8, m)) << a.name;
  }
  EXPECT_FALSE(tiff_writable("a.tif", 3, SampleType::f16, {}));
  EXPECT_FALSE(tiff_writable("a.tif", 5, SampleType::u8, {}));
  ImageMetadata moved;
  moved.x = 4;
  EXPECT_FALSE(tiff_writable("a.tif", 3, SampleType::u8, moved));
  EXPECT_FALSE(read_tiff(fs::path(PUPWAVE_TESTIMAGES_DIR) / "camera.png").has_value());
}

TEST(TiffIo, CorruptAndTruncatedFilesAreErrorsNamingTheFile) {
  const fs::path path = scratch_dir() / "whole.tif";
  write_tiff(photograph("chelsea.png"), path);
  const auto open = [](const fs::path& p) { return open_tiff_rows(p); };
  for (std::size_t keep : {std::size_t(8), std::size_t(200), fs::file_size(path) / 2}) {
    const fs::path cut = truncated_copy(path, keep);
    const std::string error = read_error(cut, open);
    EXPECT_NE(error.find(cut.string()), std::string::npos) << keep << ": " << error;
  }
}

// --- JPEG ---

TEST(JpegIo, FilesOpenImageIoWritesReadAsItReadsThem) {
  const auto read = [](const fs::path& p) { return read_jpeg(p); };
  expect_read_as_openimageio_reads(photograph("chelsea.png"), "rgb.jpg", read);
  expect_read_as_openimageio_reads(photograph("camera.png"), "grey.jpeg", read);
}

TEST(JpegIo, WrittenFilesReadBackCloseToTheImage) {
  for (const char* name : {"astronaut.png", "camera.png"}) {
    const Image image = photograph(name);
    const fs::path path = scratch_dir() / (std::string(name) + ".jpg");
    ASSERT_TRUE(jpeg_writable(path, image.channels, image.type, image.metadata));
    write_jpeg(image, path);
    const auto back = read_jpeg(path);
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->channels, image.channels);
    EXPECT_EQ(back->type, SampleType::u8);
    double squared = 0.0;
    for (std::size_t i = 0; i < image.samples.size(); ++i)
      squared += std::pow(double(back->samples[i]) - double(image.samples[i]), 2.0);
    const double psnr = 10.0 * std::log10(255.0 * 255.0 * double(image.samples.size()) / squared);
    EXPECT_GT(psnr, 36.0) << name << " at quality 95";
    expect_same_image(*back, oiio_module().read(path), path.string());
  }
}

// The JFIF segment (APP0, the file's first after its start marker) of a JPEG file.
std::string jfif_segment(const fs::path& path) {
  const std::string bytes = file_bytes(path);
  EXPECT_EQ(bytes.substr(2, 2), "\xff\xe0") << path;
  return bytes.substr(2, 18);
}

// The attributes OpenImageIO's reader gives for a file, each as "name type = value", sorted
// (the order follows the file's layout, which libexif's differs from).
std::vector<std::string> openimageio_attributes(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << path;
  if (!in) return {};
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<std::string> attributes;
  for (const OIIO::ParamValue& p : spec.extra_attribs)
    attributes.push_back(p.name().string() + " " + p.type().c_str() + " = " + spec.metadata_val(p));
  std::sort(attributes.begin(), attributes.end());
  return attributes;
}

// The header segments of a JPEG but its EXIF block, whose layout libexif's and OpenImageIO's
// differ in (the attributes read from it are compared instead).
std::vector<std::string> segments_but_exif(const fs::path& path) {
  std::vector<std::string> segments = jpeg_header_segments(path);
  std::erase_if(segments, [](const std::string& s) { return s.substr(0, 2) == "\xff\xe1"; });
  return segments;
}

// Writes `image` natively and through OpenImageIO into dir/<name>_native.jpg and _oiio.jpg;
// both read back as the same attributes, segments other than EXIF and image. The attributes.
std::vector<std::string> expect_written_as_openimageio_writes(const Image& image, const std::string& name) {
  const fs::path dir = scratch_dir(), native = dir / (name + "_native.jpg"),
                 oiio = dir / (name + "_oiio.jpg");
  EXPECT_TRUE(jpeg_writable(native, image.channels, image.type, image.metadata)) << name;
  write_jpeg(image, native);
  oiio_module().write(image, oiio, oiio);
  const std::vector<std::string> attributes = openimageio_attributes(native);
  EXPECT_EQ(attributes, openimageio_attributes(oiio)) << name;
  EXPECT_EQ(segments_but_exif(native), segments_but_exif(oiio)) << name;
  EXPECT_EQ(jpeg_header_segments(native).size(), jpeg_header_segments(oiio).size()) << name;
  expect_same_image(*read_jpeg(native), oiio_module().read(oiio), name + " read back");
  return attributes;
}

ImageAttribute text_attribute(const std::string& name, const std::string& text) {
  return {name, ImageAttribute::Kind::string, text, 0, 0.0};
}

ImageAttribute real_attribute(const std::string& name, double value) {
  return {name, ImageAttribute::Kind::real, "", 0, value};
}

bool has(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// An EXR's own attributes (screenWindowWidth, PixelAspectRatio 1) as OpenImageIO writes them.
TEST(JpegIo, ExrAttributesAreWrittenAsOpenImageIoWritesThem) {
  Image img = photograph("astronaut.png");
  img.metadata.attributes = {real_attribute("PixelAspectRatio", 1.0),
                             real_attribute("screenWindowWidth", 1.0)};
  expect_written_as_openimageio_writes(img, "exr_own");
  // The comparison can fail: a density of 72 x 72, not libjpeg's default of 1 x 1.
  EXPECT_EQ(jfif_segment(scratch_dir() / "exr_own_native.jpg").substr(12, 4), "\0\x48\0\x48"s);
}

// forest_hdr.exr's attributes (DateTime, Software, Orientation, Exif:ImageHistory...) and the
// text and resolution ones photographs carry: the EXIF, IPTC, comment and JFIF OpenImageIO writes.
TEST(JpegIo, TextAndResolutionAttributesAreWrittenAsOpenImageIoWritesThem) {
  Image img = convert_sample_type(oiio_module().read(testimage("forest_hdr.exr")), SampleType::u8);
  ASSERT_EQ(img.metadata.attributes.size(), 6u);
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"ImageDescription", "a forest"},
                                   {"Artist", "A. Painter"},
                                   {"Copyright", "(c) nobody"},
                                   {"Make", "Canon"},
                                   {"Model", "EOS 5D"}})
    img.metadata.attributes.push_back(text_attribute(name, text));
  img.metadata.attributes.push_back(real_attribute("XResolution", 300.0));
  img.metadata.attributes.push_back(real_attribute("YResolution", 300.0));
  img.metadata.attributes.push_back(text_attribute("ResolutionUnit", "in"));
  const std::vector<std::string> attributes = expect_written_as_openimageio_writes(img, "forest");
  // The comparison can fail: the EXIF, IPTC and JFIF values are there.
  EXPECT_TRUE(has(attributes, "DateTime string = \"2018:08:17 15:11:15\""))
      << ::testing::PrintToString(attributes);
  EXPECT_TRUE(has(attributes, "Exif:FlashPixVersion string = \"0100\""));
  EXPECT_TRUE(has(attributes, "IPTC:Creator string = \"A. Painter\""));
  EXPECT_TRUE(has(attributes, "Model string = \"EOS 5D\""));
  EXPECT_TRUE(has(attributes, "Orientation uint16 = 1"));
  EXPECT_TRUE(has(attributes, "ResolutionUnit string = \"in\""));
  EXPECT_TRUE(has(attributes, "XResolution float = 300"));
  const auto history = std::find_if(attributes.begin(), attributes.end(),
                                    [](const std::string& a) { return a.starts_with("Exif:ImageHistory "); });
  EXPECT_NE(history, attributes.end());
  // A grey image gets the same EXIF sub-directory.
  Image grey = photograph("camera.png");
  grey.metadata.attributes = {text_attribute("Exif:ImageHistory", "made"), text_attribute("Software", "odd")};
  EXPECT_TRUE(has(expect_written_as_openimageio_writes(grey, "grey"), "Exif:ImageHistory string = \"made\""));
}

// The JFIF density OpenImageIO derives from pixel aspect ratios, resolutions and their unit.
TEST(JpegIo, DensitiesAreWrittenAsOpenImageIoWritesThem) {
  const Image plain = photograph("camera.png");
  const std::vector<std::vector<ImageAttribute>> cases = {
      {},
      {real_attribute("PixelAspectRatio", 2.0)},
      {real_attribute("PixelAspectRatio", 0.75)},
      {real_attribute("PixelAspectRatio", 1.01)},
      {real_attribute("PixelAspectRatio", 0.7), real_attribute("XResolution", 300.0)},
      {real_attribute("PixelAspectRatio", 1.0), real_attribute("XResolution", 300.0),
       real_attribute("YResolution", 150.0)},
      {real_attribute("XResolution", 200.0), text_attribute("ResolutionUnit", "CM")},
      {real_attribute("YResolution", 96.0), text_attribute("ResolutionUnit", "inch")},
      {real_attribute("Orientation", 0.0)}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    Image img = plain;
    img.metadata.attributes = cases[i];
    if (i + 1 == cases.size()) {  // the last is one left to OpenImageIO
      EXPECT_FALSE(jpeg_writable("a.jpg", 1, SampleType::u8, img.metadata));
      continue;
    }
    expect_written_as_openimageio_writes(img, "density" + std::to_string(i));
  }
  // The comparison can fail: 72 x 144 for a ratio of 2, 300 x 429 for 0.7 with a resolution of 300.
  EXPECT_EQ(jfif_segment(scratch_dir() / "density1_native.jpg").substr(12, 4), "\0\x48\0\x90"s);
  EXPECT_EQ(jfif_segment(scratch_dir() / "density4_native.jpg").substr(12, 4), "\x01\x2c\x01\xad"s);
}

TEST(JpegIo, AttributesStoredOtherwiseAreLeftToOpenImageIo) {
  for (const ImageAttribute& a :
       {text_attribute("HostComputer", "h"), text_attribute("Software", ""),
        ImageAttribute{"Orientation", ImageAttribute::Kind::integer, "", 9, 0},
        ImageAttribute{"ResolutionUnit", ImageAttribute::Kind::integer, "", 2, 0},
        real_attribute("XResolution", 72.5), real_attribute("PixelAspectRatio", 0.0),
        real_attribute("Exif:ExposureTime", 0.5), text_attribute("Software", std::string(70000, 's'))}) {
    ImageMetadata m;
    m.attributes.push_back(a);
    EXPECT_FALSE(jpeg_writable("a.jpg", 3, SampleType::u8, m)) << a.name;
  }
  ImageMetadata twice;
  twice.attributes = {text_attribute("Software", "a"), text_attribute("Software", "b")};
  EXPECT_FALSE(jpeg_writable("a.jpg", 3, SampleType::u8, twice));
  ImageMetadata aspect_from_y;
  aspect_from_y.attributes = {real_attribute("PixelAspectRatio", 2.0), real_attribute("YResolution", 100.0)};
  EXPECT_FALSE(jpeg_writable("a.jpg", 3, SampleType::u8, aspect_from_y));
}

TEST(JpegIo, CorruptAndTruncatedFilesAreErrorsNamingTheFile) {
  const fs::path path = scratch_dir() / "whole.jpg";
  write_jpeg(photograph("chelsea.png"), path);
  const auto open = [](const fs::path& p) { return open_jpeg_rows(p); };
  for (std::size_t keep : {std::size_t(4), std::size_t(300), fs::file_size(path) / 2}) {
    const fs::path cut = truncated_copy(path, keep);
    const std::string error = read_error(cut, open);
    EXPECT_NE(error.find(cut.string()), std::string::npos) << keep << ": " << error;
  }
}

// --- the CLI ---

bool loads_openimageio(const std::string& args) {
  const auto result = test::run_shell_output("LD_DEBUG=files " + test::shell_quote(PUPWAVE_CLI) + " " + args +
                                             " 2>&1 >/dev/null </dev/null");
  EXPECT_EQ(result.exit_code, 0) << args << "\n" << result.output;
  return result.output.find("pupwave_oiio") != std::string::npos;
}

TEST(NativeFormatsCli, ConvertInfoCompressAndDecompressDoNotLoadOpenImageIo) {
  const fs::path dir = scratch_dir();
  const auto at = [&](const std::string& name) { return test::shell_quote((dir / name).string()); };
  const std::string png = test::shell_quote((fs::path(PUPWAVE_TESTIMAGES_DIR) / "astronaut.png").string());
  const std::string exr = test::shell_quote((fs::path(PUPWAVE_TESTIMAGES_DIR) / "forest_hdr.exr").string());
  EXPECT_FALSE(loads_openimageio("convert -q " + exr + " " + at("f.exr")));
  EXPECT_FALSE(loads_openimageio("convert -q " + at("f.exr") + " " + at("g.exr")));
  // An EXR's attributes (PixelAspectRatio, screenWindowWidth, ...) keep no PNG or TIFF from the
  // native writers.
  EXPECT_FALSE(loads_openimageio("convert -q " + exr + " " + at("f.png")));
  EXPECT_FALSE(loads_openimageio("convert -q " + exr + " " + at("f.tif")));
  // forest_hdr.exr's DateTime, Software and Exif:ImageHistory go into the EXIF block written here.
  EXPECT_FALSE(loads_openimageio("convert -q " + exr + " " + at("f.jpg")));
  EXPECT_FALSE(loads_openimageio("convert -q " + png + " " + at("p.exr")));
  EXPECT_FALSE(loads_openimageio("convert -q " + at("p.exr") + " " + at("p.jpg")));
  EXPECT_FALSE(loads_openimageio("compress -q --bpp 2 " + exr + " " + at("f.pw")));
  EXPECT_FALSE(loads_openimageio("decompress -q " + at("f.pw") + " " + at("f.png")));
  for (const char* ext : {".exr", ".tif", ".jpg"}) {
    EXPECT_FALSE(loads_openimageio("convert -q " + png + " " + at(std::string("a") + ext))) << ext;
    EXPECT_FALSE(loads_openimageio("info " + at(std::string("a") + ext))) << ext;
    EXPECT_FALSE(loads_openimageio("compress -q --bpp 1 " + at(std::string("a") + ext) + " " + at("a.pw")))
        << ext;
    EXPECT_FALSE(loads_openimageio("decompress -q " + at("a.pw") + " " + at(std::string("b") + ext))) << ext;
    EXPECT_FALSE(loads_openimageio("convert -q " + at(std::string("a") + ext) + " " + at("back.ppm"))) << ext;
  }
  expect_same_image(read_image(dir / "a.tif"), photograph("astronaut.png"), "a.tif");
  // The check can fail: a BMP still goes through OpenImageIO.
  EXPECT_TRUE(loads_openimageio("convert -q " + png + " " + at("a.bmp")));
}

}  // namespace
}  // namespace pupwave::cli

#include "tools/jpeg_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>
// jpeglib.h needs FILE and size_t declared first.
#include <jerror.h>
#include <jpeglib.h>
#include <libexif/exif-data.h>

#include "codec/image/image_view.h"
#include "tools/atomic_file.h"
#include "tools/strip_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// The quality the CLI asks OpenImageIO to write JPEG at (tools/oiio/oiio_module.cpp).
constexpr int kJpegQuality = 95;

// What libjpeg's callbacks share with the code calling into libjpeg: plain C data, so that the
// longjmp out of an error skips no destructor.
struct JpegCall {
  jpeg_error_mgr errors{};
  std::jmp_buf jump{};
  char message[JMSG_LENGTH_MAX] = "";
  bool truncated = false;  // libjpeg reached the end of the file before the last scanline
  std::FILE* file = nullptr;
};

// Keeps libjpeg's message and returns to the setjmp of the jpeg_step_* function that called it.
[[noreturn]] void on_jpeg_error(j_common_ptr info) {
  auto* call = static_cast<JpegCall*>(info->client_data);
  (*info->err->format_message)(info, call->message);
  std::longjmp(call->jump, 1);
}

// Warnings are dropped, as OpenImageIO drops them, but for the end of the file coming early.
void on_jpeg_message(j_common_ptr info, int level) {
  auto* call = static_cast<JpegCall*>(info->client_data);
  if (level < 0 && info->err->msg_code == JWRN_JPEG_EOF) {
    call->truncated = true;
    (*info->err->format_message)(info, call->message);
  }
}

// Points libjpeg's errors at `call`.
void route_jpeg_errors(jpeg_common_struct& info, JpegCall& call) {
  info.err = jpeg_std_error(&call.errors);
  call.errors.error_exit = on_jpeg_error;
  call.errors.emit_message = on_jpeg_message;
  info.client_data = &call;
}

// The only functions that call setjmp: each runs one libjpeg step and returns false, with
// call.message set, when libjpeg reports an error. They hold no C++ object with a destructor.
bool jpeg_step_open(JpegCall& call, jpeg_decompress_struct& info) {
  if (setjmp(call.jump)) return false;
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, call.file);
  jpeg_read_header(&info, TRUE);
  return true;
}

bool jpeg_step_start(JpegCall& call, jpeg_decompress_struct& info) {
  if (setjmp(call.jump)) return false;
  jpeg_start_decompress(&info);
  return true;
}

bool jpeg_step_read_row(JpegCall& call, jpeg_decompress_struct& info, JSAMPROW row) {
  if (setjmp(call.jump)) return false;
  return jpeg_read_scanlines(&info, &row, 1) == 1 && !call.truncated;
}

// The JFIF density fields (libjpeg's density_unit, X_density, Y_density).
struct JfifDensity {
  std::uint8_t unit = 0;
  std::uint16_t x = 1, y = 1;  // libjpeg's default
};

// A marker written after the JFIF one: its code (JPEG_COM, JPEG_APP0 + n) and contents.
struct JpegMarker {
  int code = 0;
  std::string bytes;
};

bool jpeg_step_write_header(JpegCall& call, jpeg_compress_struct& info, JDIMENSION width, JDIMENSION height,
                            int components, const JfifDensity& density,
                            const std::vector<JpegMarker>& markers) {
  if (setjmp(call.jump)) return false;
  jpeg_create_compress(&info);
  jpeg_stdio_dest(&info, call.file);
  info.image_width = width;
  info.image_height = height;
  info.input_components = components;
  info.in_color_space = components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, kJpegQuality, TRUE);
  info.density_unit = density.unit;
  info.X_density = density.x;
  info.Y_density = density.y;
  jpeg_start_compress(&info, TRUE);
  for (const JpegMarker& m : markers)
    jpeg_write_marker(&info, m.code, reinterpret_cast<const JOCTET*>(m.bytes.data()),
                      static_cast<unsigned>(m.bytes.size()));
  return true;
}

bool jpeg_step_write_row(JpegCall& call, jpeg_compress_struct& info, JSAMPROW row) {
  if (setjmp(call.jump)) return false;
  return jpeg_write_scanlines(&info, &row, 1) == 1;
}

bool jpeg_step_finish(JpegCall& call, jpeg_compress_struct& info) {
  if (setjmp(call.jump)) return false;
  jpeg_finish_compress(&info);
  return true;
}

// Whether the file starts with a JPEG start-of-image marker.
bool has_jpeg_magic(std::FILE* file) {
  unsigned char magic[3] = {};
  const bool jpeg = std::fread(magic, 1, sizeof magic, file) == sizeof magic && magic[0] == 0xFF &&
                    magic[1] == 0xD8 && magic[2] == 0xFF;
  std::rewind(file);
  return jpeg;
}

// The rows of a JPEG file read with jpeg_read_scanlines, a strip at a time.
class JpegRows final : public StripReader {
 public:
  // Null when the file is not a JPEG of the kinds read here; throws for a corrupt one.
  static std::unique_ptr<JpegRows> open(const fs::path& path) {
    if (!is_readable_file(path)) return nullptr;
    std::unique_ptr<JpegRows> rows(new JpegRows(path));
    JpegCall& call = rows->call_;
    call.file = std::fopen(path.c_str(), "rb");
    if (!call.file || !has_jpeg_magic(call.file)) return nullptr;
    route_jpeg_errors(*reinterpret_cast<jpeg_common_struct*>(&rows->info_), call);
    rows->created_ = true;
    if (!jpeg_step_open(call, rows->info_)) rows->fail();
    return rows->take_header() ? std::move(rows) : nullptr;
  }
  ~JpegRows() override {
    if (created_) jpeg_destroy_decompress(&info_);
    if (call_.file) std::fclose(call_.file);
  }
  JpegRows(const JpegRows&) = delete;
  JpegRows& operator=(const JpegRows&) = delete;

 protected:
  void read_strip(std::size_t, Image& strip) override {
    for (std::size_t y = 0; y < strip.height; ++y) {
      if (!jpeg_step_read_row(call_, info_, row_.data())) fail();
      const ImageView row = interleaved_view(row_.data(), width_, 1, channels_, SampleType::u8);
      for (std::size_t c = 0; c < channels_; ++c) row.read_row(c, 0, strip.plane(c) + y * width_);
    }
  }

 private:
  explicit JpegRows(const fs::path& path) : path_(path) {}

  // Takes the header read by jpeg_step_open; false for a colour space left to OpenImageIO.
  bool take_header() {
    const J_COLOR_SPACE space = info_.jpeg_color_space;
    const bool grey = space == JCS_GRAYSCALE && info_.num_components == 1;
    const bool rgb = (space == JCS_YCbCr || space == JCS_RGB) && info_.num_components == 3;
    if (!grey && !rgb) return false;
    info_.out_color_space = grey ? JCS_GRAYSCALE : JCS_RGB;
    width_ = info_.image_width;
    height_ = info_.image_height;
    channels_ = std::size_t(info_.num_components);
    check_image_samples(path_, width_, height_, channels_);
    if (!jpeg_step_start(call_, info_)) fail();
    row_.resize(width_ * channels_);
    return true;
  }

  [[noreturn]] void fail() const {
    throw_read_error(path_, call_.message[0] ? call_.message : "corrupt JPEG data");
  }

  fs::path path_;
  JpegCall call_;
  jpeg_decompress_struct info_{};
  bool created_ = false;           // whether info_ holds libjpeg's state to destroy
  std::vector<std::uint8_t> row_;  // one scanline as libjpeg gives it
};

// What OpenImageIO 2.4's JPEG writer does with an image's attributes, found by writing files
// through it: text attributes go into its EXIF block (APP1), some also into a Photoshop IPTC block
// (APP13) and ImageDescription into a comment (COM); Orientation and whole X/YResolution into
// EXIF; resolution and pixel aspect ratio set the JFIF density; screenWindowWidth is dropped.
// An image with any other attribute, or one of these in another form, is left to OpenImageIO.

// A text attribute, its EXIF directory and tag, and its IPTC dataset (record 2; 0: none).
struct TextTag {
  const char* name;
  ExifIfd ifd;
  ExifTag tag;
  std::uint8_t iptc;
};
// TIFF/EP's ImageHistory, which libexif's tag list lacks.
constexpr ExifTag kImageHistoryTag = ExifTag(0x9213);
constexpr TextTag kTextTags[] = {
    {"ImageDescription", EXIF_IFD_0, EXIF_TAG_IMAGE_DESCRIPTION, 120},
    {"Make", EXIF_IFD_0, EXIF_TAG_MAKE, 0},
    {"Model", EXIF_IFD_0, EXIF_TAG_MODEL, 0},
    {"Software", EXIF_IFD_0, EXIF_TAG_SOFTWARE, 65},
    {"DateTime", EXIF_IFD_0, EXIF_TAG_DATE_TIME, 0},
    {"Artist", EXIF_IFD_0, EXIF_TAG_ARTIST, 80},
    {"Copyright", EXIF_IFD_0, EXIF_TAG_COPYRIGHT, 116},
    {"Exif:ImageHistory", EXIF_IFD_EXIF, kImageHistoryTag, 0},
};

// All text together stays under this, so that each block fits its marker's 65533 bytes.
constexpr std::size_t kMaxJpegText = 60000;

const TextTag* text_tag(const std::string& name) {
  for (const TextTag& t : kTextTags)
    if (name == t.name) return &t;
  return nullptr;
}

const ImageAttribute* find_attribute(const ImageMetadata& metadata, std::string_view name) {
  for (const ImageAttribute& a : metadata.attributes)
    if (a.name == name) return &a;
  return nullptr;
}

// A resolution OpenImageIO stores as the EXIF rational v/1 and a JFIF density of v.
bool whole_density(double v) { return v >= 1.0 && v <= 65535.0 && v == std::floor(v); }

// Whether this one attribute is stored as OpenImageIO stores it (see above).
bool jpeg_attribute_held(const ImageAttribute& a) {
  using Kind = ImageAttribute::Kind;
  if (text_tag(a.name))
    return a.kind == Kind::string && !a.text.empty() && a.text.find('\0') == std::string::npos;
  if (a.name == "XResolution" || a.name == "YResolution")
    return a.kind == Kind::real && whole_density(a.real);
  if (a.name == "PixelAspectRatio") return a.kind == Kind::real && a.real > 0.0;
  if (a.name == "Orientation") return a.kind == Kind::integer && a.integer >= 1 && a.integer <= 8;
  if (a.name == "ResolutionUnit") return a.kind == Kind::string;  // names only the JFIF unit
  return a.name == "screenWindowWidth" && a.kind == Kind::real;
}

// Whether every attribute is held, once (OpenImageIO keeps the last of a repeated name), their
// text fits the blocks, and the density is one whose rule was seen: a pixel aspect ratio with a
// YResolution but no XResolution was not.
bool jpeg_attributes_held(const ImageMetadata& metadata) {
  std::size_t text = 0;
  for (const ImageAttribute& a : metadata.attributes) {
    if (!jpeg_attribute_held(a) || find_attribute(metadata, a.name) != &a) return false;
    text += a.text.size();
  }
  const bool aspect_from_y = find_attribute(metadata, "PixelAspectRatio") &&
                             find_attribute(metadata, "YResolution") &&
                             !find_attribute(metadata, "XResolution");
  return text <= kMaxJpegText && !aspect_from_y;
}

// OpenImageIO's rounding of a density: to nearest, within 1..65535 (clamped as a float, so that
// the extreme ratios' values never overflow the conversion).
std::uint16_t density_of(float v) { return std::uint16_t(std::clamp(v + 0.5f, 1.0f, 65535.0f)); }

// The JFIF density OpenImageIO 2.4 writes: the unit named by ResolutionUnit ("in", "cm", else
// none); with a pixel aspect ratio, XResolution by XResolution / ratio, or 72 and 72 x ratio
// (the larger side 72's); without, the resolutions given (one standing for both); else 1 x 1.
JfifDensity jfif_density(const ImageMetadata& metadata) {
  JfifDensity d;
  if (const ImageAttribute* unit = find_attribute(metadata, "ResolutionUnit")) {
    const auto is = [&](std::string_view name) {
      return unit->text.size() == name.size() &&
             std::equal(name.begin(), name.end(), unit->text.begin(),
                        [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
    };
    d.unit = is("in") ? 1 : is("cm") ? 2 : 0;
  }
  const ImageAttribute* xres = find_attribute(metadata, "XResolution");
  const ImageAttribute* yres = find_attribute(metadata, "YResolution");
  const ImageAttribute* aspect = find_attribute(metadata, "PixelAspectRatio");
  // OpenImageIO receives the attributes as float (tools/oiio/oiio_module.cpp) and computes in float.
  if (aspect) {
    const float ratio = float(aspect->real);
    if (xres) {
      d.x = density_of(float(xres->real));
      d.y = density_of(float(xres->real) / ratio);
    } else {
      d.x = density_of(ratio >= 1.0f ? 72.0f : 72.0f * ratio);
      d.y = density_of(ratio >= 1.0f ? 72.0f * ratio : 72.0f);
    }
  } else if (xres || yres) {
    d.x = density_of(float((xres ? xres : yres)->real));
    d.y = density_of(float((yres ? yres : xres)->real));
  }
  return d;
}

// Adds an entry of `size` bytes to the directory; its bytes are to be filled in.
ExifEntry* add_exif_entry(ExifData& exif, ExifMem* mem, ExifIfd ifd, ExifTag tag, ExifFormat format,
                          unsigned long components, unsigned size) {
  ExifEntry* e = exif_entry_new_mem(mem);
  if (!e) throw std::bad_alloc();
  e->data = static_cast<unsigned char*>(exif_mem_alloc(mem, size));
  if (!e->data) {
    exif_entry_unref(e);
    throw std::bad_alloc();
  }
  e->tag = tag;
  e->format = format;
  e->components = components;
  e->size = size;
  exif_content_add_entry(exif.ifd[ifd], e);
  exif_entry_unref(e);  // the directory holds it
  return e;
}

void add_exif_bytes(ExifData& exif, ExifMem* mem, ExifIfd ifd, ExifTag tag, ExifFormat format,
                    std::string_view bytes) {
  ExifEntry* e = add_exif_entry(exif, mem, ifd, tag, format, bytes.size(), unsigned(bytes.size()));
  std::memcpy(e->data, bytes.data(), bytes.size());
}

// Adds the attributes OpenImageIO writes into EXIF, in its forms: text as ASCII with its NUL,
// Orientation as SHORT, X/YResolution as RATIONAL v/1; an EXIF sub-directory gets the
// ExifVersion, ComponentsConfiguration and FlashpixVersion OpenImageIO adds to it.
void add_exif_attributes(ExifData& exif, ExifMem* mem, const ImageMetadata& metadata) {
  const ExifByteOrder order = exif_data_get_byte_order(&exif);
  for (const ImageAttribute& a : metadata.attributes) {
    if (const TextTag* t = text_tag(a.name)) {
      add_exif_bytes(exif, mem, t->ifd, t->tag, EXIF_FORMAT_ASCII,
                     std::string_view(a.text.c_str(), a.text.size() + 1));
    } else if (a.name == "Orientation") {
      ExifEntry* e = add_exif_entry(exif, mem, EXIF_IFD_0, EXIF_TAG_ORIENTATION, EXIF_FORMAT_SHORT, 1, 2);
      exif_set_short(e->data, order, ExifShort(a.integer));
    } else if (a.name == "XResolution" || a.name == "YResolution") {
      const ExifTag tag = a.name == "XResolution" ? EXIF_TAG_X_RESOLUTION : EXIF_TAG_Y_RESOLUTION;
      ExifEntry* e = add_exif_entry(exif, mem, EXIF_IFD_0, tag, EXIF_FORMAT_RATIONAL, 1, 8);
      exif_set_rational(e->data, order, ExifRational{ExifLong(a.real), 1});
    }
  }
  if (exif.ifd[EXIF_IFD_EXIF]->count == 0) return;
  add_exif_bytes(exif, mem, EXIF_IFD_EXIF, EXIF_TAG_EXIF_VERSION, EXIF_FORMAT_UNDEFINED, "0230");
  add_exif_bytes(exif, mem, EXIF_IFD_EXIF, EXIF_TAG_COMPONENTS_CONFIGURATION, EXIF_FORMAT_UNDEFINED,
                 std::string_view("\1\2\3\0", 4));
  add_exif_bytes(exif, mem, EXIF_IFD_EXIF, EXIF_TAG_FLASH_PIX_VERSION, EXIF_FORMAT_UNDEFINED, "0100");
}

// The EXIF block ("Exif\0\0" and a little-endian TIFF structure) OpenImageIO writes into every
// JPEG, with no entries when no attribute goes there.
std::string exif_block(const ImageMetadata& metadata) {
  // libexif's reference counts, released however this returns.
  const auto unref_mem = [](ExifMem* m) { exif_mem_unref(m); };
  const auto unref_data = [](ExifData* d) { exif_data_unref(d); };
  const std::unique_ptr<ExifMem, decltype(unref_mem)> mem(exif_mem_new_default(), unref_mem);
  if (!mem) throw std::bad_alloc();
  const std::unique_ptr<ExifData, decltype(unref_data)> exif(exif_data_new_mem(mem.get()), unref_data);
  if (!exif) throw std::bad_alloc();
  exif_data_set_byte_order(exif.get(), EXIF_BYTE_ORDER_INTEL);
  add_exif_attributes(*exif, mem.get(), metadata);
  unsigned char* bytes = nullptr;
  unsigned int size = 0;
  exif_data_save_data(exif.get(), &bytes, &size);
  if (!bytes) throw std::bad_alloc();
  std::string block(reinterpret_cast<const char*>(bytes), size);
  exif_mem_free(mem.get(), bytes);
  return block;
}

// OpenImageIO's Photoshop IPTC block: "Photoshop 3.0", one 8BIM resource 0x0404 holding a
// record-2 dataset per attribute that has one, in dataset order; empty when none does.
std::string iptc_block(const ImageMetadata& metadata) {
  std::vector<std::pair<std::uint8_t, const std::string*>> sets;
  for (const ImageAttribute& a : metadata.attributes)
    if (const TextTag* t = text_tag(a.name); t && t->iptc) sets.emplace_back(t->iptc, &a.text);
  if (sets.empty()) return {};
  std::sort(sets.begin(), sets.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto be16 = [](std::size_t v) { return std::string{char(v >> 8 & 0xFF), char(v & 0xFF)}; };
  std::string data;
  for (const auto& [dataset, text] : sets)
    data += "\x1C\x02" + std::string(1, char(dataset)) + be16(text->size()) + *text;
  return std::string(
             "Photoshop 3.0\0"
             "8BIM\x04\x04\0\0\0\0",
             24) +
         be16(data.size()) + data;
}

// The markers OpenImageIO writes after the JFIF one: ImageDescription as a comment with its NUL,
// the EXIF block, the IPTC block when there is one.
std::vector<JpegMarker> jpeg_markers(const ImageMetadata& metadata) {
  std::vector<JpegMarker> markers;
  if (const ImageAttribute* d = find_attribute(metadata, "ImageDescription"))
    markers.push_back({JPEG_COM, std::string(d->text.c_str(), d->text.size() + 1)});
  markers.push_back({JPEG_APP0 + 1, exif_block(metadata)});
  if (std::string iptc = iptc_block(metadata); !iptc.empty())
    markers.push_back({JPEG_APP0 + 13, std::move(iptc)});
  return markers;
}

// 8-bit grey or RGB, default channel names, no windows, attributes jpeg_attributes_held takes.
bool jpeg_holds(std::size_t channels, SampleType type, const ImageMetadata& metadata) {
  ImageMetadata rest = metadata;
  rest.attributes.clear();
  return (channels == 1 || channels == 3) && type == SampleType::u8 && rest.empty() &&
         jpeg_attributes_held(metadata);
}

// A JPEG being written a scanline at a time.
class JpegWriter {
 public:
  JpegWriter(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
             const ImageMetadata& metadata)
      : file_(file), row_(width * channels) {
    call_.file = std::fopen(file.c_str(), "wb");
    if (!call_.file) throw_write_error(file);
    route_jpeg_errors(*reinterpret_cast<jpeg_common_struct*>(&info_), call_);
    created_ = true;
    const std::vector<JpegMarker> markers = jpeg_markers(metadata);
    errno = 0;
    if (!jpeg_step_write_header(call_, info_, JDIMENSION(width), JDIMENSION(height), int(channels),
                                jfif_density(metadata), markers))
      fail();
  }
  ~JpegWriter() {
    if (created_) jpeg_destroy_compress(&info_);
    if (call_.file) std::fclose(call_.file);
  }
  JpegWriter(const JpegWriter&) = delete;
  JpegWriter& operator=(const JpegWriter&) = delete;

  // Appends the rows of `strip`, rounded and clamped to 0..255.
  void put(const Image& strip) {
    for (std::size_t y = 0; y < strip.height; ++y) {
      interleave_row(strip, y, row_.data());
      errno = 0;
      if (!jpeg_step_write_row(call_, info_, row_.data())) fail();
    }
  }

  // Ends the file; throws if any of it could not be written.
  void finish() {
    errno = 0;
    if (!jpeg_step_finish(call_, info_)) fail();
    close_written_file(call_.file, file_);
  }

 private:
  [[noreturn]] void fail() const { throw_write_failure(file_, call_.message); }

  fs::path file_;
  JpegCall call_;
  jpeg_compress_struct info_{};
  bool created_ = false;
  std::vector<std::uint8_t> row_;  // one interleaved row
};

}  // namespace

bool has_jpeg_extension(const fs::path& path) { return has_extension(path, {".jpg", ".jpeg", ".jpe"}); }

std::unique_ptr<ImageRowReader> open_jpeg_rows(const fs::path& path) { return JpegRows::open(path); }

std::optional<Image> read_jpeg(const fs::path& path) { return read_whole(JpegRows::open(path)); }

bool jpeg_writable(const fs::path& path, std::size_t channels, SampleType type,
                   const ImageMetadata& metadata) {
  return has_jpeg_extension(path) && jpeg_holds(channels, type, metadata);
}

void write_jpeg(const Image& image, const fs::path& file) {
  if (!jpeg_holds(image.channels, image.type, image.metadata))
    throw std::invalid_argument("write_jpeg: needs 1 or 3 channels of 8-bit samples and metadata JPEG holds");
  JpegWriter writer(file, image.width, image.height, image.channels, image.metadata);
  writer.put(image);
  writer.finish();
}

void write_jpeg_rows(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
                     const ImageMetadata& metadata, const std::function<Image()>& next_strip) {
  if (!jpeg_holds(channels, SampleType::u8, metadata))
    throw std::invalid_argument("write_jpeg_rows: needs 1 or 3 channels and metadata JPEG holds");
  JpegWriter writer(file, width, height, channels, metadata);
  write_strips(writer, width, height, channels, SampleType::u8, next_strip, "write_jpeg_rows");
}

}  // namespace pupwave::cli

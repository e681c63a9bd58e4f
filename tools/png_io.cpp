#include "tools/png_io.h"

#include <png.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "codec/image/image_view.h"
#include "tools/atomic_file.h"
#include "tools/strip_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// libpng's default limit on each side, under which OpenImageIO reads PNGs: the same files are
// refused by both paths.
constexpr png_uint_32 kPngMaxSide = 1000000;
// Largest ratio of a deflate stream's output to its input (zlib's documentation: 1032:1).
constexpr std::size_t kDeflateMaxRatio = 1032;

// What libpng's callbacks share with the code calling into libpng: plain C data, so that the
// longjmp out of an error skips no destructor.
struct PngCall {
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::FILE* file = nullptr;
  char message[256] = "";
};

// Keeps libpng's message and returns to the setjmp of the png_step_* function that called libpng.
[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* call = static_cast<PngCall*>(png_get_error_ptr(png));
  std::snprintf(call->message, sizeof call->message, "%s", message);
  png_longjmp(png, 1);
}

// Warnings (a bad CRC in an ancillary chunk, which libpng then skips) are dropped, as OpenImageIO
// drops them.
void on_png_warning(png_structp, png_const_charp) {}

// The only functions that call setjmp: each runs one libpng step and returns false, with
// call.message set, when libpng reports an error. They hold no C++ object with a destructor, so
// the longjmp back into them skips none.
bool png_step_read_info(PngCall& call) {
  if (setjmp(png_jmpbuf(call.png))) return false;
  png_read_info(call.png, call.info);
  // 16-bit samples are big-endian in the file; the rows come out in host order.
  if constexpr (std::endian::native == std::endian::little) png_set_swap(call.png);
  png_read_update_info(call.png, call.info);
  return true;
}

bool png_step_read_row(PngCall& call, png_bytep row) {
  if (setjmp(png_jmpbuf(call.png))) return false;
  png_read_row(call.png, row, nullptr);
  return true;
}

// The chunks OpenImageIO 2.4's PNG writer makes of an image's attributes (found by writing
// files through it): each string a tEXt chunk, a few under PNG's own keywords; DateTime in EXIF's
// form a tIME chunk; a pixel aspect ratio of 1 a 100x100 pHYs chunk without unit; the colour
// space "Linear" a gAMA of 1 besides its text. It drops every other number.
struct PngChunks {
  std::vector<std::string> keywords, texts;
  std::optional<png_time> time;
  bool linear = false;
  bool square_pixels = false;
};

bool same_name(const std::string& a, const char* b) {
  return std::equal(a.begin(), a.end(), b, b + std::char_traits<char>::length(b), [](char x, char y) {
    return std::tolower((unsigned char)x) == std::tolower((unsigned char)y);
  });
}

// The keyword OpenImageIO gives a string attribute.
std::string png_keyword(const std::string& name) {
  if (same_name(name, "Artist")) return "Author";
  if (same_name(name, "name") || same_name(name, "DocumentName")) return "Title";
  if (same_name(name, "ImageDescription") || same_name(name, "description")) return "Description";
  return name;
}

// A keyword libpng writes unchanged (it rewrites or refuses others): 1 to 79 printable ASCII
// characters, no space at either end or twice in a row.
bool plain_keyword(const std::string& k) {
  if (k.empty() || k.size() > 79 || k.front() == ' ' || k.back() == ' ' || k.find("  ") != std::string::npos)
    return false;
  return std::all_of(k.begin(), k.end(), [](char c) { return c >= 32 && c <= 126; });
}

// OpenImageIO's reading of "YYYY:MM:DD HH:MM:SS"; nullopt if it does not parse (then dropped).
std::optional<png_time> exif_time(const std::string& text) {
  int year, month, day, hour, minute, second;
  if (std::sscanf(text.c_str(), "%4d:%02d:%02d %2d:%02d:%02d", &year, &month, &day, &hour, &minute,
                  &second) != 6)
    return std::nullopt;
  png_time t{};
  t.year = png_uint_16(year);
  t.month = png_byte(month);
  t.day = png_byte(day);
  t.hour = png_byte(hour);
  t.minute = png_byte(minute);
  t.second = png_byte(second);
  return t;
}

// libpng's own check of a time it is given (it drops, with a warning, any other).
bool valid_time(const png_time& t) {
  return t.month >= 1 && t.month <= 12 && t.day >= 1 && t.day <= 31 && t.hour <= 23 && t.minute <= 59 &&
         t.second <= 60;
}

// Adds one attribute's chunks; false when only OpenImageIO writes it as OpenImageIO does
// (encoding settings, resolutions, other colour spaces, odd keywords or times).
bool add_png_chunks(const ImageAttribute& a, PngChunks& chunks) {
  using Kind = ImageAttribute::Kind;
  if (same_name(a.name, "planarconfig")) return true;  // ignored by OpenImageIO's PNG writer
  if (same_name(a.name, "compression") || same_name(a.name, "XResolution") ||
      same_name(a.name, "YResolution") || same_name(a.name, "ResolutionUnit") ||
      same_name(a.name.substr(0, 4), "png:"))
    return false;
  if (same_name(a.name, "oiio:ColorSpace")) {
    if (a.kind != Kind::string || a.text != "Linear") return false;
    chunks.linear = true;
  } else if (same_name(a.name.substr(0, 5), "oiio:")) {
    return false;
  }
  if (same_name(a.name, "PixelAspectRatio")) {
    chunks.square_pixels = a.kind == Kind::real && a.real == 1.0;
    return chunks.square_pixels;
  }
  if (a.kind != Kind::string) return true;  // other numbers: dropped
  if (same_name(a.name, "DateTime")) {
    const std::optional<png_time> t = exif_time(a.text);
    if (t && !valid_time(*t)) return false;
    if (t) chunks.time = t;
    return true;
  }
  const std::string keyword = png_keyword(a.name);
  if (!plain_keyword(keyword)) return false;
  chunks.keywords.push_back(keyword);
  chunks.texts.push_back(a.text);
  return true;
}

// The chunks for `attributes`; nullopt when one of them is left to OpenImageIO.
std::optional<PngChunks> png_chunks(const std::vector<ImageAttribute>& attributes) {
  PngChunks chunks;
  for (const ImageAttribute& a : attributes)
    if (!add_png_chunks(a, chunks)) return std::nullopt;
  return chunks;
}

bool png_step_write_header(PngCall& call, png_uint_32 width, png_uint_32 height, int depth, int color_type,
                           const ImageMetadata& metadata, const PngChunks& chunks, png_text* texts) {
  if (setjmp(png_jmpbuf(call.png))) return false;
  png_set_IHDR(call.png, call.info, width, height, depth, color_type, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The data window origin, where OpenImageIO writes and reads it.
  if (metadata.x != 0 || metadata.y != 0)
    png_set_oFFs(call.png, call.info, metadata.x, metadata.y, PNG_OFFSET_PIXEL);
  if (chunks.linear) png_set_gAMA_fixed(call.png, call.info, PNG_FP_1);
  if (chunks.square_pixels) png_set_pHYs(call.png, call.info, 100, 100, PNG_RESOLUTION_UNKNOWN);
  if (chunks.time) png_set_tIME(call.png, call.info, &*chunks.time);
  if (!chunks.texts.empty()) png_set_text(call.png, call.info, texts, int(chunks.texts.size()));
  png_write_info(call.png, call.info);
  if constexpr (std::endian::native == std::endian::little) png_set_swap(call.png);
  return true;
}

bool png_step_write_row(PngCall& call, png_const_bytep row) {
  if (setjmp(png_jmpbuf(call.png))) return false;
  png_write_row(call.png, row);
  return true;
}

bool png_step_write_end(PngCall& call) {
  if (setjmp(png_jmpbuf(call.png))) return false;
  png_write_end(call.png, nullptr);
  return true;
}

// Channels of a PNG colour type read here (no palette); 0 for the others.
std::size_t png_channels(int color_type) {
  switch (color_type) {
    case PNG_COLOR_TYPE_GRAY: return 1;
    case PNG_COLOR_TYPE_GRAY_ALPHA: return 2;
    case PNG_COLOR_TYPE_RGB: return 3;
    case PNG_COLOR_TYPE_RGB_ALPHA: return 4;
    default: return 0;
  }
}

int png_color_type(std::size_t channels) {
  static const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                              PNG_COLOR_TYPE_RGB_ALPHA};
  return types[channels - 1];
}

// Grey, grey+alpha, RGB or RGBA of 8- or 16-bit samples, with attributes stored as OpenImageIO
// stores them (png_chunks).
bool png_holds(std::size_t channels, SampleType type, const ImageMetadata& metadata) {
  return channels >= 1 && channels <= 4 && is_integer(type) && png_chunks(metadata.attributes).has_value();
}

std::size_t png_sample_bytes(SampleType type) { return type == SampleType::u16 ? 2 : 1; }

// A buffer for one row of interleaved samples, held as 16-bit words (so 16-bit samples are read
// and written as what they are) and handed to libpng as bytes.
std::vector<std::uint16_t> png_row_buffer(std::size_t width, std::size_t channels, SampleType type) {
  return std::vector<std::uint16_t>((width * channels * png_sample_bytes(type) + 1) / 2);
}

png_bytep png_bytes_of(std::vector<std::uint16_t>& row) { return reinterpret_cast<png_bytep>(row.data()); }

// The rows of a PNG file read with png_read_row, a strip at a time.
class PngRows final : public StripReader {
 public:
  // Null when the file is not a PNG of the kinds read here; throws for a corrupt one.
  static std::unique_ptr<PngRows> open(const fs::path& path);
  ~PngRows() override {
    png_destroy_read_struct(&call_.png, &call_.info, nullptr);
    if (call_.file) std::fclose(call_.file);
  }
  PngRows(const PngRows&) = delete;
  PngRows& operator=(const PngRows&) = delete;

 protected:
  void read_strip(std::size_t, Image& strip) override {
    for (std::size_t y = 0; y < strip.height; ++y) {
      if (!png_step_read_row(call_, png_bytes_of(row_))) fail();
      const ImageView row = interleaved_view(row_.data(), width_, 1, channels_, type_);
      for (std::size_t c = 0; c < channels_; ++c) row.read_row(c, 0, strip.plane(c) + y * width_);
    }
  }

 private:
  explicit PngRows(const fs::path& path) : path_(path) {}

  // Takes the header read by png_step_read_info; false for a kind of PNG left to OpenImageIO.
  bool take_header() {
    const int depth = png_get_bit_depth(call_.png, call_.info);
    channels_ = png_channels(png_get_color_type(call_.png, call_.info));
    // Palette, 1/2/4-bit, tRNS and interlaced files need expanding or reordering: OpenImageIO's.
    if (channels_ == 0 || (depth != 8 && depth != 16) ||
        png_get_interlace_type(call_.png, call_.info) != PNG_INTERLACE_NONE ||
        png_get_valid(call_.png, call_.info, PNG_INFO_tRNS) != 0)
      return false;
    width_ = png_get_image_width(call_.png, call_.info);
    height_ = png_get_image_height(call_.png, call_.info);
    type_ = depth == 16 ? SampleType::u16 : SampleType::u8;
    check_image_samples(path_, width_, height_, channels_);
    // Deflate expands at most 1032:1 (zlib's limit), so a file far too small for the size its
    // header claims is refused before the caller allocates the image for it.
    std::error_code ec;
    const std::uintmax_t file_bytes = fs::file_size(path_, ec);
    const std::size_t filtered = height_ * (1 + width_ * channels_ * (depth / 8));
    if (!ec && filtered / kDeflateMaxRatio > file_bytes)
      throw_read_error(path_, "its " + std::to_string(file_bytes) + " bytes cannot hold the " +
                                  std::to_string(width_) + "x" + std::to_string(height_) +
                                  " image its header claims (truncated or corrupt)");
    // OpenImageIO's data window origin for a PNG; its channel names are the defaults (not kept).
    metadata_.x = png_get_x_offset_pixels(call_.png, call_.info);
    metadata_.y = png_get_y_offset_pixels(call_.png, call_.info);
    row_ = png_row_buffer(width_, channels_, type_);
    return true;
  }

  [[noreturn]] void fail() const { throw_read_error(path_, call_.message); }

  fs::path path_;
  PngCall call_;
  std::vector<std::uint16_t> row_;  // one row as libpng gives it
};

std::unique_ptr<PngRows> PngRows::open(const fs::path& path) {
  if (!is_readable_file(path)) return nullptr;  // OpenImageIO's path reports why
  std::unique_ptr<PngRows> rows(new PngRows(path));
  PngCall& call = rows->call_;
  call.file = std::fopen(path.c_str(), "rb");
  png_byte signature[8] = {};
  if (!call.file || std::fread(signature, 1, sizeof signature, call.file) != sizeof signature ||
      png_sig_cmp(signature, 0, sizeof signature) != 0)
    return nullptr;
  call.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &call, on_png_error, on_png_warning);
  if (call.png) call.info = png_create_info_struct(call.png);
  if (!call.info) throw std::bad_alloc();
  png_init_io(call.png, call.file);
  png_set_sig_bytes(call.png, sizeof signature);
  png_set_user_limits(call.png, kPngMaxSide, kPngMaxSide);
  if (!png_step_read_info(call)) rows->fail();
  if (!rows->take_header()) return nullptr;
  return rows;
}

// A PNG being written: libpng's structures and the file, released together.
class PngWriter {
 public:
  PngWriter(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
            SampleType type, const ImageMetadata& metadata)
      : file_(file), type_(type), row_(png_row_buffer(width, channels, type)) {
    call_.file = std::fopen(file.c_str(), "wb");
    if (!call_.file) throw_write_error(file);
    call_.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &call_, on_png_error, on_png_warning);
    if (call_.png) call_.info = png_create_info_struct(call_.png);
    if (!call_.info) throw std::bad_alloc();
    png_init_io(call_.png, call_.file);
    const PngChunks chunks = png_chunks(metadata.attributes).value();
    std::vector<png_text> texts(chunks.texts.size());
    for (std::size_t i = 0; i < texts.size(); ++i) {
      texts[i].compression = PNG_TEXT_COMPRESSION_NONE;
      texts[i].key = const_cast<char*>(chunks.keywords[i].c_str());
      texts[i].text = const_cast<char*>(chunks.texts[i].c_str());
      texts[i].text_length = chunks.texts[i].size();
    }
    errno = 0;
    if (!png_step_write_header(call_, png_uint_32(width), png_uint_32(height),
                               int(8 * png_sample_bytes(type)), png_color_type(channels), metadata, chunks,
                               texts.data()))
      fail();
  }
  ~PngWriter() {
    png_destroy_write_struct(&call_.png, &call_.info);
    if (call_.file) std::fclose(call_.file);
  }
  PngWriter(const PngWriter&) = delete;
  PngWriter& operator=(const PngWriter&) = delete;

  // Appends the rows of `strip`, rounded and clamped to the sample type's range.
  void put(const Image& strip) {
    for (std::size_t y = 0; y < strip.height; ++y) {
      if (type_ == SampleType::u16)
        interleave_row(strip, y, row_.data());
      else
        interleave_row(strip, y, png_bytes_of(row_));
      errno = 0;
      if (!png_step_write_row(call_, png_bytes_of(row_))) fail();
    }
  }

  // Ends the file; throws if any of it could not be written.
  void finish() {
    errno = 0;
    if (!png_step_write_end(call_)) fail();
    close_written_file(call_.file, file_);
  }

 private:
  [[noreturn]] void fail() const { throw_write_failure(file_, call_.message); }

  fs::path file_;
  SampleType type_;
  PngCall call_;
  std::vector<std::uint16_t> row_;  // one row as libpng takes it (16-bit samples in host order)
};

}  // namespace

bool has_png_extension(const fs::path& path) { return has_extension(path, {".png"}); }

std::unique_ptr<ImageRowReader> open_png_rows(const fs::path& path) { return PngRows::open(path); }

std::optional<Image> read_png(const fs::path& path) { return read_whole(PngRows::open(path)); }

bool png_writable(const fs::path& path, std::size_t channels, SampleType type,
                  const ImageMetadata& metadata) {
  return has_png_extension(path) && png_holds(channels, type, metadata);
}

void write_png(const Image& image, const fs::path& file) {
  if (!png_holds(image.channels, image.type, image.metadata))
    throw std::invalid_argument(
        "write_png: needs 1 to 4 channels of 8- or 16-bit samples and attributes PNG holds");
  PngWriter writer(file, image.width, image.height, image.channels, image.type, image.metadata);
  writer.put(image);
  writer.finish();
}

void write_png_rows(const fs::path& file, std::size_t width, std::size_t height, std::size_t channels,
                    SampleType type, const ImageMetadata& metadata,
                    const std::function<Image()>& next_strip) {
  if (!png_holds(channels, type, metadata))
    throw std::invalid_argument(
        "write_png_rows: needs 1 to 4 channels of 8- or 16-bit samples and attributes PNG holds");
  PngWriter writer(file, width, height, channels, type, metadata);
  write_strips(writer, width, height, channels, type, next_strip, "write_png_rows");
}

}  // namespace pupwave::cli

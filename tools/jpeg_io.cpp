#include "tools/jpeg_io.h"

#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>
// jpeglib.h needs FILE and size_t declared first.
#include <jerror.h>
#include <jpeglib.h>

#include "codec/image/image_view.h"
#include "tools/atomic_file.h"
#include "tools/jpeg_metadata.h"
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

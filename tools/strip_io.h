#pragma once
// What the native image readers and writers (png_io.h, exr_io.h, tiff_io.h, jpeg_io.h) share: the
// extension test, errors naming the user's file, the size check made before anything is
// allocated for the pixels, and the strip plumbing of a row reader and a row writer.

#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "codec/image/image.h"
#include "tools/image_io.h"

namespace pupwave::cli {

// Whether the name ends in one of `extensions` (given in lower case with the dot), in any case.
bool has_extension(const std::filesystem::path& path, std::initializer_list<std::string_view> extensions);

// Whether `path` names a regular file: the native readers leave anything else to OpenImageIO,
// whose path says why it cannot be read.
bool is_readable_file(const std::filesystem::path& path);

// std::runtime_error "cannot read PATH: WHY".
[[noreturn]] void throw_read_error(const std::filesystem::path& path, const std::string& why);

// std::runtime_error "cannot write PATH: WHY", for a library's refusal (stdio failures: atomic_file.h's
// throw_write_error, which reads errno).
[[noreturn]] void throw_write_refusal(const std::filesystem::path& path, const std::string& why);

// A failed write through a C library: errno (cleared before the library call) says why when a
// system call failed, else the library's message.
[[noreturn]] void throw_write_failure(const std::filesystem::path& path, const char* library_message);

// Closes a stdio file being written (nulling the pointer first, so it is closed once); throws
// naming `path` if its data could not be written.
void close_written_file(std::FILE*& file, const std::filesystem::path& path);

// Attributes that describe a file's encoding or OpenImageIO's reading of it, not the image: not
// kept in Image::metadata.
bool is_encoding_attribute(const std::string& name);

// Throws "cannot read PATH: image too large" when width x height x channels exceeds
// kMaxImageSamples (or the product overflows); called before the pixels are allocated.
void check_image_samples(const std::filesystem::path& path, std::size_t width, std::size_t height,
                         std::size_t channels);

// Channel names a file of this many channels gets when none are given (Y, YA, RGB, RGBA, then
// channelN), as OpenImageIO names them; such names are not stored in Image::metadata.
std::vector<std::string> default_channel_names(std::size_t channels);

// The channel names to store for a file's names: none when they are the defaults.
std::vector<std::string> kept_channel_names(std::vector<std::string> names);

// The index of the alpha channel where OpenImageIO's readers put it: the first channel named A or
// Alpha (after any layer prefix, in any case); -1 when there is none.
int alpha_channel_of(const std::vector<std::string>& channel_names);

// The description `pupwave info` prints for an image file: format (OpenImageIO's name), size,
// channel names, sample type, depth (above 1), alpha channel (if >= 0), then what compress keeps
// besides the pixels (windows, attributes).
std::string describe_image(const std::filesystem::path& path, const std::string& format, std::size_t width,
                           std::size_t height, const std::vector<std::string>& channel_names,
                           const std::string& type, int alpha_channel, const ImageMetadata& kept,
                           int depth = 1);

// A row reader whose subclass decodes rows [y0, y0 + strip.height) into a strip's planes; the
// shape, metadata and the position in the file are kept here.
class StripReader : public ImageRowReader {
 public:
  std::size_t width() const override { return width_; }
  std::size_t height() const override { return height_; }
  std::size_t channels() const override { return channels_; }
  SampleType type() const override { return type_; }
  const ImageMetadata& metadata() const override { return metadata_; }
  Image next(std::size_t rows) override;

 protected:
  // Fills every plane of `strip` (width() columns, strip.height rows starting at row y0).
  virtual void read_strip(std::size_t y0, Image& strip) = 0;

  std::size_t width_ = 0, height_ = 0, channels_ = 0;
  SampleType type_ = SampleType::u8;
  ImageMetadata metadata_;

 private:
  std::size_t next_row_ = 0;
};

// The whole image of a row reader (one strip, read into place), with its metadata; nullopt for
// none (a native reader leaving the file to OpenImageIO).
std::optional<Image> read_whole(std::unique_ptr<ImageRowReader> rows);

// Passes the strips of next_strip to `put` until `height` rows have come; throws
// std::runtime_error ("<who>: a strip does not fit the image") for a strip of another shape.
void for_each_strip(std::size_t width, std::size_t height, std::size_t channels, SampleType type,
                    const std::function<Image()>& next_strip, const std::function<void(const Image&)>& put,
                    const char* who);

// Writes the strips of next_strip through a format's writer (put(strip), then finish()), checking
// each as for_each_strip does.
template <class Writer>
void write_strips(Writer& writer, std::size_t width, std::size_t height, std::size_t channels,
                  SampleType type, const std::function<Image()>& next_strip, const char* who) {
  for_each_strip(
      width, height, channels, type, next_strip, [&](const Image& strip) { writer.put(strip); }, who);
  writer.finish();
}

// Interleaves row y of a strip's planes into `out` as samples of type T, rounded and clamped to
// [0, T's maximum] for integer T, copied for float T.
template <class T>
void interleave_row(const Image& strip, std::size_t y, T* out);

}  // namespace pupwave::cli

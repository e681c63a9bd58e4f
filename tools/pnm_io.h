#pragma once
// Binary PGM/PPM (P5/P6, maxval 255 or 65535), read and written here rather than through
// OpenImageIO: its 2.4 PNM writer makes a stdio call per sample (about a quarter of a 4096^2
// decode) and writes 8 bits only. Every other PNM variant (ASCII, PAM, other maxvals) goes
// through OpenImageIO, as do the formats tools/image_io.cpp does not read natively.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "codec/image/image.h"
#include "codec/image/image_view.h"
#include "tools/mapped_file.h"

namespace pupwave::cli {

// The image in a binary PGM/PPM file with maxval 255 or 65535 (u8 / u16), or nullopt when the
// file is some other kind (the caller then uses OpenImageIO). Throws std::runtime_error for a
// header with absurd dimensions or a raster shorter than the header says; nothing is
// allocated for the raster before its length is checked against the file size.
std::optional<Image> read_binary_pnm(const std::filesystem::path& path);

// Whether the name ends in .pgm, .ppm or .pnm (any case).
bool has_pnm_extension(const std::filesystem::path& path);

// Whether write_binary_pnm handles this image at this path: a .pgm/.ppm/.pnm name, 1 or 3
// channels (grey: P5, RGB: P6), 8- or 16-bit samples.
bool binary_pnm_writable(const std::filesystem::path& path, const Image& image);

// Writes the image as binary PGM/PPM to `file` (16-bit samples big-endian, maxval 65535).
void write_binary_pnm(const Image& image, const std::filesystem::path& file);

}  // namespace pupwave::cli

namespace pupwave::cli {

// Whether write_binary_pnm_rows handles an image of these channels and type at this path.
bool binary_pnm_writable(const std::filesystem::path& path, std::size_t channels, SampleType type);

// Writes a binary PGM/PPM of width x height pixels to `file` whose rows come from successive
// calls of next_strip (images of `width` columns and `channels` planes, top to bottom), so the
// image is never whole in memory. Throws std::runtime_error when a strip does not fit the
// shape or the rows end early.
void write_binary_pnm_rows(const std::filesystem::path& file, std::size_t width, std::size_t height,
                           std::size_t channels, SampleType type, const std::function<Image()>& next_strip);

}  // namespace pupwave::cli

namespace pupwave::cli {

// A binary PGM/PPM with maxval 255, mapped read-only and viewed in place (one byte a sample),
// so the encoder reads its rows from the file instead of a float copy of the image (4 bytes a
// sample). 16-bit files are big-endian and are read with read_binary_pnm instead.
class MappedPnm {
 public:
  // Null when the file is not such a PNM; throws read_binary_pnm's errors for a bad one.
  static std::unique_ptr<MappedPnm> open(const std::filesystem::path& path);
  const ImageView& view() const { return view_; }

 private:
  explicit MappedPnm(const std::filesystem::path& path) : file_(path) {}
  MappedFile file_;
  ImageView view_;
};

}  // namespace pupwave::cli

#pragma once
// Binary PGM/PPM (P5/P6, maxval 255 or 65535), read and written here rather than through
// OpenImageIO: its 2.4 PNM writer makes a stdio call per sample (about a quarter of a 4096^2
// decode) and writes 8 bits only. Every other PNM variant (ASCII, PAM, other maxvals) and
// every other format still goes through OpenImageIO (tools/image_io.cpp).

#include <filesystem>
#include <optional>

#include "codec/image/image.h"

namespace pupwave::cli {

// The image in a binary PGM/PPM file with maxval 255 or 65535 (u8 / u16), or nullopt when the
// file is some other kind (the caller then uses OpenImageIO). Throws std::runtime_error for a
// header with absurd dimensions or a raster shorter than the header says; nothing is
// allocated for the raster before its length is checked against the file size.
std::optional<Image> read_binary_pnm(const std::filesystem::path& path);

// Whether write_binary_pnm handles this image at this path: a .pgm/.ppm/.pnm name, 1 or 3
// channels (grey: P5, RGB: P6), 8- or 16-bit samples.
bool binary_pnm_writable(const std::filesystem::path& path, const Image& image);

// Writes the image as binary PGM/PPM to `file` (16-bit samples big-endian, maxval 65535).
void write_binary_pnm(const Image& image, const std::filesystem::path& file);

}  // namespace pupwave::cli

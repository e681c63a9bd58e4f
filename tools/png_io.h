#pragma once
// PNG files read and written with libpng here rather than through OpenImageIO, whose module costs
// 130 MiB resident and 260 shared libraries to load (tools/oiio_module.h). Reading takes the PNGs
// whose samples are stored as they are held (grey, grey+alpha, RGB, RGBA at 8 or 16 bits,
// non-interlaced, no tRNS chunk) and gives the Image OpenImageIO gives for them; palette,
// 1/2/4-bit, tRNS and interlaced files go to OpenImageIO (tools/image_io.cpp). Writing takes 1 to
// 4 channels of 8- or 16-bit samples whose attributes are stored as OpenImageIO stores them (text,
// tIME, pHYs and gAMA chunks); an image with others (resolutions, colour spaces other than
// "Linear", encoding settings) goes to OpenImageIO.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "codec/image/image.h"
#include "tools/image_io.h"

namespace pupwave::cli {

// Whether the name ends in .png (any case).
bool has_png_extension(const std::filesystem::path& path);

// The image in a PNG file of the kinds above (samples, type and the oFFs origin as OpenImageIO
// reads them), or nullopt when the file is not one (the caller then uses OpenImageIO). Throws
// std::runtime_error naming the file for a corrupt or truncated one, and for dimensions over
// kMaxImageSamples before anything is allocated for the pixels.
std::optional<Image> read_png(const std::filesystem::path& path);

// The rows of such a PNG, read a strip at a time with png_read_row; null when the file is not
// one. Throws read_png's errors.
std::unique_ptr<ImageRowReader> open_png_rows(const std::filesystem::path& path);

// Whether write_png handles an image of these channels, type and metadata at this path: a .png
// name, 1 to 4 channels (grey, grey+alpha, RGB, RGBA), 8- or 16-bit samples, attributes stored
// as OpenImageIO stores them.
bool png_writable(const std::filesystem::path& path, std::size_t channels, SampleType type,
                  const ImageMetadata& metadata);

// Writes the image as PNG to `file` (libpng's default zlib level; the data window origin, if
// any, in an oFFs chunk as OpenImageIO writes it).
void write_png(const Image& image, const std::filesystem::path& file);

// Writes a PNG of width x height pixels to `file` whose rows come from successive calls of
// next_strip (images of `width` columns and `channels` planes, top to bottom), so the image is
// never whole in memory. Throws std::runtime_error when a strip does not fit the shape.
void write_png_rows(const std::filesystem::path& file, std::size_t width, std::size_t height,
                    std::size_t channels, SampleType type, const ImageMetadata& metadata,
                    const std::function<Image()>& next_strip);

}  // namespace pupwave::cli

#pragma once
// JPEG files read and written with libjpeg(-turbo) here rather than through OpenImageIO (whose
// module costs 130 MiB resident, tools/oiio_module.h). Reading takes 8-bit greyscale and
// YCbCr/RGB files, decoded a scanline at a time with libjpeg's default (islow) transform and
// upsampling, as OpenImageIO decodes them, and gives the same Image (EXIF orientation is not
// applied by either); CMYK/YCCK and other colour spaces go to OpenImageIO (tools/image_io.cpp),
// which refuses CMYK. A file that ends before its last scanline is an error here (OpenImageIO
// fills the rest with grey). Writing takes 8-bit grey or RGB images whose attributes are those
// jpeg_writable names, at quality 95 with libjpeg's defaults (JFIF, 4:2:0 chroma), the quality
// the CLI asks OpenImageIO for, with the JFIF density, comment, EXIF block (libexif) and
// Photoshop IPTC block OpenImageIO 2.4 writes for those attributes. Reading gives no attributes,
// as the module's reading of a JPEG does.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "codec/image/image.h"
#include "tools/image_io.h"

namespace pupwave::cli {

// Whether the name ends in .jpg, .jpeg or .jpe (any case).
bool has_jpeg_extension(const std::filesystem::path& path);

// The rows of a JPEG of the kinds above, read a scanline at a time; null when the file is not
// one (the caller then uses OpenImageIO). Throws std::runtime_error naming the file for a corrupt
// or truncated one, and for dimensions over kMaxImageSamples before the pixels are allocated.
std::unique_ptr<ImageRowReader> open_jpeg_rows(const std::filesystem::path& path);

// The whole image of such a file; nullopt when it is not one.
std::optional<Image> read_jpeg(const std::filesystem::path& path);

// Whether write_jpeg_rows handles an image of these channels, type and metadata at this path: a
// JPEG name, 1 or 3 channels of 8-bit samples, default channel names, no windows, and attributes
// stored as OpenImageIO stores them: the text ones (ImageDescription, Make, Model, Software,
// DateTime, Artist, Copyright, Exif:ImageHistory; not empty), Orientation 1-8, whole X/YResolution
// of 1-65535, ResolutionUnit as text, a positive PixelAspectRatio (not with a YResolution alone),
// and screenWindowWidth (dropped). Others leave the image to OpenImageIO.
bool jpeg_writable(const std::filesystem::path& path, std::size_t channels, SampleType type,
                   const ImageMetadata& metadata);

// Writes the image as JPEG to `file` (see write_jpeg_rows).
void write_jpeg(const Image& image, const std::filesystem::path& file);

// Writes a JPEG of width x height pixels to `file` whose rows come from successive calls of
// next_strip (8-bit images of `width` columns and `channels` planes, top to bottom).
void write_jpeg_rows(const std::filesystem::path& file, std::size_t width, std::size_t height,
                     std::size_t channels, const ImageMetadata& metadata,
                     const std::function<Image()>& next_strip);

}  // namespace pupwave::cli

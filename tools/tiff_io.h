#pragma once
// TIFF files read and written with libtiff here rather than through OpenImageIO (whose module
// costs 130 MiB resident, tools/oiio_module.h). Reading takes the TIFFs whose samples are stored
// as they are held: 1 to 4 channels of 8/16-bit unsigned or 32-bit float samples, grey
// (min-is-black) or RGB, contiguous strips under any compression libtiff decodes but JPEG, no
// position or display-size tags; it gives the Image OpenImageIO gives for them (its channel names
// from ExtraSamples). Tiled, planar-separate, palette, 1-bit, YCbCr, JPEG-compressed, CMYK and
// other TIFFs go to OpenImageIO (tools/image_io.cpp). Writing takes 1 to 4 channels of 8/16-bit
// or float samples with the default channel names, no windows and only attributes it stores as
// OpenImageIO does (tiff_writable), written as
// OpenImageIO writes them by default: deflate (level 6) with a predictor, 32 rows a strip, alpha
// (the second of two channels, the fourth of four) marked unassociated.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "codec/image/image.h"
#include "tools/image_io.h"

namespace pupwave::cli {

// Whether the name ends in .tif or .tiff (any case).
bool has_tiff_extension(const std::filesystem::path& path);

// The rows of a TIFF of the kinds above, read a scanline at a time; null when the file is not
// one (the caller then uses OpenImageIO). Throws std::runtime_error naming the file for a corrupt
// or truncated one, and for dimensions over kMaxImageSamples before the pixels are allocated.
std::unique_ptr<ImageRowReader> open_tiff_rows(const std::filesystem::path& path);

// The whole image of such a file; nullopt when it is not one.
std::optional<Image> read_tiff(const std::filesystem::path& path);

// Whether write_tiff_rows handles an image of these channels, type and metadata at this path: a
// .tif/.tiff name, 1 to 4 channels, 8/16-bit or float samples, default channel names, no windows,
// and only attributes stored as OpenImageIO stores them (Artist, Copyright, DateTime,
// DocumentName, ImageDescription and Software as ASCII tags; those it drops).
bool tiff_writable(const std::filesystem::path& path, std::size_t channels, SampleType type,
                   const ImageMetadata& metadata);

// Writes the image as TIFF to `file` (see write_tiff_rows).
void write_tiff(const Image& image, const std::filesystem::path& file);

// Writes a TIFF of width x height pixels to `file` whose rows come from successive calls of
// next_strip (images of `width` columns, `channels` planes and `type`, top to bottom).
void write_tiff_rows(const std::filesystem::path& file, std::size_t width, std::size_t height,
                     std::size_t channels, SampleType type, const ImageMetadata& metadata,
                     const std::function<Image()>& next_strip);

}  // namespace pupwave::cli

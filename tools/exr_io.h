#pragma once
// OpenEXR files read and written with the OpenEXR library here rather than through OpenImageIO
// (whose module costs 130 MiB resident, tools/oiio_module.h). Reading takes single-part
// scanline files and single-level tiled files of half and float channels, and gives exactly the
// Image OpenImageIO gives: its channel order (R, G, B, A first within each layer), its names for
// the header's string, int, float and double attributes, its windows. Files with channels of
// another kind (uint, subsampled, deep), several parts, mipmaps, environment maps or attributes of
// other types (vectors, matrices, chromaticities, timecodes...) go to OpenImageIO
// (tools/image_io.cpp), so what compress keeps of them does not depend on the path. Writing takes
// half or float images whose attributes are strings, integers and floats that OpenImageIO would
// store under their own names (or as capDate, pixelAspectRatio, screenWindowWidth), as scanline
// files with ZIP compression at level 4, what OpenImageIO writes by default (less the capture
// date it adds when the image has none); other attributes go through OpenImageIO.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>

#include "codec/image/image.h"
#include "tools/image_io.h"

namespace pupwave::cli {

// Whether the name ends in .exr (any case).
bool has_exr_extension(const std::filesystem::path& path);

// The rows of an OpenEXR file of the kinds above, read a strip at a time (a tiled file through
// the library's own row of tiles); null when the file is not one (the caller then uses
// OpenImageIO). Throws std::runtime_error naming the file for a corrupt or truncated one, and
// for dimensions over kMaxImageSamples before anything is allocated for the pixels.
std::unique_ptr<ImageRowReader> open_exr_rows(const std::filesystem::path& path);

// The whole image of such a file; nullopt when it is not one.
std::optional<Image> read_exr(const std::filesystem::path& path);

// Whether write_exr_rows handles an image of this type and metadata at this path: a .exr name,
// half or float samples, attributes of the kinds above.
bool exr_writable(const std::filesystem::path& path, SampleType type, const ImageMetadata& metadata);

// Writes the image as a scanline OpenEXR file to `file` (see write_exr_rows).
void write_exr(const Image& image, const std::filesystem::path& file);

// Writes a scanline OpenEXR file of width x height pixels to `file` whose rows come from
// successive calls of next_strip (images of `width` columns, `channels` planes and `type`, top to
// bottom), with the metadata's channel names and windows.
void write_exr_rows(const std::filesystem::path& file, std::size_t width, std::size_t height,
                    std::size_t channels, SampleType type, const ImageMetadata& metadata,
                    const std::function<Image()>& next_strip);

}  // namespace pupwave::cli

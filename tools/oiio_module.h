#pragma once
// The OpenImageIO half of image file I/O lives in a plugin (tools/oiio/, built as a shared
// module next to the `pupwave` binary) that is loaded on first use. Linking OpenImageIO pulls
// in about 260 shared libraries: 0.19 s and 130 MiB resident at every start of the CLI, more
// than a whole 4096^2 decode's budget. Commands whose image files are of the kinds read and
// written natively (tools/image_io.h: PGM/PPM, PNG, EXR, TIFF, JPEG), .pw files and volumes never
// load it.

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "codec/image/image.h"
#include "tools/image_io.h"

namespace pupwave::cli {

// Size, channels and sample type of an image written by rows.
struct ImageShape {
  std::size_t width = 0, height = 0, channels = 0;
  SampleType type = SampleType::u8;
};

// The operations the module provides. Each throws std::runtime_error with the reason.
struct OiioModule {
  // First subimage of an image file, exactly (see read_image).
  Image (*read)(const std::filesystem::path& path);
  // One line describing an image file (see describe_image_file).
  std::string (*describe)(const std::filesystem::path& path);
  // OpenImageIO's format name for writing a file at this path ("png", "tiff", "pnm"...).
  std::string (*format_name)(const std::filesystem::path& path);
  // Writes `image` (already of a type the format stores) to `file`, choosing the format from
  // `target`'s extension (file is the temporary name the atomic write renames onto target).
  void (*write)(const Image& image, const std::filesystem::path& target, const std::filesystem::path& file);
  // The rows of an image file, a strip at a time (see open_image_rows).
  std::unique_ptr<ImageRowReader> (*open_rows)(const std::filesystem::path& path);
  // `write` of an image of `shape` and `metadata` whose rows come from successive calls of
  // next_strip (images of shape's width, channels and type, top to bottom).
  void (*write_rows)(const ImageShape& shape, const ImageMetadata& metadata,
                     const std::filesystem::path& target, const std::filesystem::path& file,
                     const std::function<Image()>& next_strip);
};

// The module, loaded on first call (next to the running executable, else where the build put
// it). Throws std::runtime_error if it cannot be loaded.
const OiioModule& oiio_module();

}  // namespace pupwave::cli

// The module's one exported symbol.
extern "C" const pupwave::cli::OiioModule* pupwave_oiio_module();

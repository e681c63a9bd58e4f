#pragma once
// The OpenImageIO half of image file I/O lives in a plugin (tools/oiio/, built as a shared
// module next to the `pupwave` binary) that is loaded on first use. Linking OpenImageIO pulls
// in about 260 shared libraries: 0.19 s and 130 MiB resident at every start of the CLI, more
// than a whole 4096^2 decode's budget. Commands that touch no PNG/TIFF/EXR/JPEG file (binary
// PGM/PPM, .pw, volumes) never load it.

#include <filesystem>
#include <string>

#include "codec/image/image.h"

namespace pupwave::cli {

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
};

// The module, loaded on first call (next to the running executable, else where the build put
// it). Throws std::runtime_error if it cannot be loaded.
const OiioModule& oiio_module();

}  // namespace pupwave::cli

// The module's one exported symbol.
extern "C" const pupwave::cli::OiioModule* pupwave_oiio_module();

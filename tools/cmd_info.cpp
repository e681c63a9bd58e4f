// `pupwave info FILE`: describe a compressed pupwave image or volume stream, an OpenVDB file or an
// image file.
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "codec/image/image_stream.h"
#include "codec/volume/volume_codec.h"
#include "tools/atomic_file.h"
#include "tools/cli_errors.h"
#include "tools/cli_stdio.h"
#include "tools/commands.h"
#include "tools/image_io.h"
#include "tools/volume_io.h"

namespace pupwave::cli {
namespace {

// The signature a file starts with ("PUPW" images, "PUPV" volumes: docs/bitstream.md).
std::string signature(const std::string& path) {
  char sig[4] = {};
  std::ifstream in(path, std::ios::binary);
  return in.read(sig, 4) ? std::string(sig, 4) : std::string();
}

void run_info(const std::string& input) {
  const InputPath in(input);
  const std::string& path = in.path;
  const std::string sig = signature(path);
  if (sig == "PUPW") {
    const std::string text = naming_stream(input, [&] { return describe_stream(read_file_bytes(path)); });
    std::cout << path << ": " << text << '\n';
  } else if (sig == "PUPV") {
    const std::string text =
        naming_stream(input, [&] { return describe_volume_stream(read_file_bytes(path)); });
    std::cout << path << ": " << text;
  } else if (is_vdb_path(path)) {
    std::cout << describe_vdb_file(path);
  } else {
    std::cout << describe_image_file(path) << '\n';
  }
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand(
      "info",
      "Describe a compressed .pw file (header fields, transform, levels, chunk sizes; every\n"
      "checksum verified; for volumes every grid with its active voxels, tiles, bounding box,\n"
      "voxel size and share of the file), an OpenVDB file (every grid: class, value type,\n"
      "active voxels, bounding box, voxel size) or an image file (format, size, channels, type)");
  cmd->add_option("FILE", *path, "file to describe, or - for stdin")
      ->required()
      ->check(existing_file_or_stdin());
  add_report_verbosity_flags(*cmd);  // -q: the checksums are still verified
  cmd->callback([path] { run_info(*path); });
}

}  // namespace pupwave::cli

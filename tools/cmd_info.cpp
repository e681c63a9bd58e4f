// `pupwave info FILE`: describe an image file or a compressed pupwave file.
#include <iostream>
#include <memory>
#include <string>

#include "tools/commands.h"
#include "tools/image_io.h"

namespace pupwave::cli {

void add_info_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand("info", "Describe an image file (format, size, channels, sample type)");
  cmd->add_option("FILE", *path, "file to describe")->required()->check(CLI::ExistingFile);
  cmd->callback([path] { std::cout << describe_image_file(*path) << '\n'; });
}

}  // namespace pupwave::cli

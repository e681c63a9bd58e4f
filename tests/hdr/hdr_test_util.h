#pragma once
// Shared by the HDR / image-structure tests: temporary files, running the CLI and oiiotool.

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/run_cli.h"

namespace pupwave::test {

inline std::filesystem::path hdr_temp_dir() {
  auto dir = std::filesystem::temp_directory_path() / ("pupwave_hdr_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string testimage(const std::string& name) {
  return std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name;
}

// Runs a shell command (oiiotool, to make test inputs from the real photographs); its exit code.
inline int run_shell(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace pupwave::test

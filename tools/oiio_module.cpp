#include "tools/oiio_module.h"

#include <dlfcn.h>

#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// Where to look: beside the running executable (the CLI), then where the build wrote it
// (test and benchmark programs live in other folders of the build tree).
std::vector<fs::path> candidates() {
  std::vector<fs::path> paths;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back(exe.parent_path() / PUPWAVE_OIIO_MODULE_NAME);
  paths.emplace_back(PUPWAVE_OIIO_MODULE_PATH);
  return paths;
}

const OiioModule* load() {
  std::string why;
  for (const fs::path& p : candidates()) {
    std::error_code ec;
    if (!fs::exists(p, ec)) continue;
    void* handle = dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept open for the process
    if (!handle) {
      why = dlerror();
      continue;
    }
    using Entry = const OiioModule* (*)();
    if (auto entry = reinterpret_cast<Entry>(dlsym(handle, "pupwave_oiio_module"))) return entry();
    why = p.string() + " has no pupwave_oiio_module";
  }
  throw std::runtime_error("cannot load the OpenImageIO module " + std::string(PUPWAVE_OIIO_MODULE_NAME) +
                           " (needed for PNG, JPEG, TIFF, EXR and other non-PNM images; it belongs next to "
                           "the pupwave binary)" +
                           (why.empty() ? "" : ": " + why));
}

}  // namespace

const OiioModule& oiio_module() {
  static const OiioModule* module = load();  // a failed load throws and is retried next call
  return *module;
}

}  // namespace pupwave::cli

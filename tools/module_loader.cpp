#include "tools/module_loader.h"

#include <dlfcn.h>

#include <filesystem>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace pupwave::cli {
namespace fs = std::filesystem;

const void* load_module(const char* name, const char* build_path, const char* entry, const std::string& what,
                        const std::string& needed_for) {
  std::vector<fs::path> candidates;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path() / name);
  candidates.emplace_back(build_path);
  std::string why;
  for (const fs::path& p : candidates) {
    if (!fs::exists(p, ec)) continue;
    void* handle = dlopen(p.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept open for the process
    if (!handle) {
      why = dlerror();
      continue;
    }
    using Entry = const void* (*)();
    if (auto f = reinterpret_cast<Entry>(dlsym(handle, entry))) return f();
    why = p.string() + " has no " + entry;
  }
  throw std::runtime_error("cannot load the " + what + " module " + name + " (" + needed_for +
                           "; it belongs next to the pupwave binary)" + (why.empty() ? "" : ": " + why));
}

}  // namespace pupwave::cli

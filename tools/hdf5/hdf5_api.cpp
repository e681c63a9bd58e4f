#include "tools/hdf5/hdf5_api.h"

#include <dlfcn.h>
#include <link.h>

#include <cstring>
#include <mutex>
#include <string_view>

namespace pupwave::h5 {
namespace {

// True for libhdf5.so*, libhdf5_serial.so*, libhdf5_openmpi.so*, libhdf5_mpich.so*, not _hl/_cpp.
bool is_hdf5_core(std::string_view path) {
  const std::size_t slash = path.rfind('/');
  std::string_view name = slash == std::string_view::npos ? path : path.substr(slash + 1);
  if (!name.starts_with("libhdf5")) return false;
  name.remove_prefix(7);
  for (std::string_view flavour : {"_serial", "_openmpi", "_mpich"})
    if (name.starts_with(flavour)) name.remove_prefix(flavour.size());
  return name.starts_with(".so");
}

int find_hdf5(dl_phdr_info* info, std::size_t, void* data) {
  if (info->dlpi_name == nullptr || !is_hdf5_core(info->dlpi_name)) return 0;
  *static_cast<std::string*>(data) = info->dlpi_name;
  return 1;
}

template <typename F>
bool bind(void* lib, const char* name, F& out) {
  out = reinterpret_cast<F>(dlsym(lib, name));
  return out != nullptr;
}

// The loaded library is found by walking the process's objects, because Python loads h5py (and
// with it libhdf5) RTLD_LOCAL, so its symbols are not in the global scope the plugin sees.
bool load(Hdf5Api& api) {
  std::string path;
  dl_iterate_phdr(find_hdf5, &path);
  void* lib = path.empty() ? RTLD_DEFAULT : dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (lib == nullptr) return false;
  // Each dlopen above adds a reference; the library stays loaded while the host uses it anyway.
  return bind(lib, "H5Tget_class", api.Tget_class) && bind(lib, "H5Tget_size", api.Tget_size) &&
         bind(lib, "H5Tget_sign", api.Tget_sign) && bind(lib, "H5Tget_order", api.Tget_order) &&
         bind(lib, "H5Pget_chunk", api.Pget_chunk) &&
         bind(lib, "H5Pget_filter_by_id2", api.Pget_filter_by_id2) &&
         bind(lib, "H5Pmodify_filter", api.Pmodify_filter) && bind(lib, "H5Epush2", api.Epush2) &&
         bind(lib, "H5allocate_memory", api.allocate_memory) && bind(lib, "H5free_memory", api.free_memory) &&
         bind(lib, "H5E_ERR_CLS_g", api.ERR_CLS) && bind(lib, "H5E_PLINE_g", api.PLINE) &&
         bind(lib, "H5E_CANAPPLY_g", api.CANAPPLY) && bind(lib, "H5E_SETLOCAL_g", api.SETLOCAL) &&
         bind(lib, "H5E_CANTFILTER_g", api.CANTFILTER);
}

}  // namespace

const Hdf5Api* hdf5_api() {
  static Hdf5Api api{};
  static bool found = false;
  static std::once_flag once;
  std::call_once(once, [] { found = load(api); });
  return found ? &api : nullptr;
}

void push_error(const Hdf5Api* api, const hid_t* minor, const char* function, const std::string& message) {
  if (api == nullptr) return;
  const std::string text = "pupwave filter: " + message;
  api->Epush2(H5E_DEFAULT, __FILE__, function, __LINE__, *api->ERR_CLS, *api->PLINE, *minor, "%s",
              text.c_str());
}

}  // namespace pupwave::h5

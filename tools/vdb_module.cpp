#include "tools/vdb_module.h"

#include "tools/module_loader.h"

#include <stdexcept>

namespace pupwave::cli {

const VdbModule& vdb_module() {
#ifndef PUPWAVE_VDB_MODULE_NAME
  throw std::runtime_error(
      "this pupwave was built without OpenVDB (PUPWAVE_BUILD_VDB=OFF): .vdb files are not supported");
#else
  // A failed load throws and is retried next call.
  static const auto* module =
      static_cast<const VdbModule*>(load_module(PUPWAVE_VDB_MODULE_NAME, PUPWAVE_VDB_MODULE_PATH,
                                                "pupwave_vdb_module", "OpenVDB", "needed for .vdb files"));
  return *module;
#endif
}

}  // namespace pupwave::cli

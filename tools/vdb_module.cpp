#include "tools/vdb_module.h"

#include "tools/module_loader.h"

namespace pupwave::cli {

const VdbModule& vdb_module() {
  // A failed load throws and is retried next call.
  static const auto* module =
      static_cast<const VdbModule*>(load_module(PUPWAVE_VDB_MODULE_NAME, PUPWAVE_VDB_MODULE_PATH,
                                                "pupwave_vdb_module", "OpenVDB", "needed for .vdb files"));
  return *module;
}

}  // namespace pupwave::cli

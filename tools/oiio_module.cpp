#include "tools/oiio_module.h"

#include "tools/module_loader.h"

namespace pupwave::cli {

const OiioModule& oiio_module() {
  // A failed load throws and is retried next call.
  static const auto* module = static_cast<const OiioModule*>(
      load_module(PUPWAVE_OIIO_MODULE_NAME, PUPWAVE_OIIO_MODULE_PATH, "pupwave_oiio_module", "OpenImageIO",
                  "needed for image formats and kinds of file not read natively (tools/image_io.h)"));
  return *module;
}

}  // namespace pupwave::cli

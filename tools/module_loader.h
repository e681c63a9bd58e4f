#pragma once
// Loading the CLI's optional modules (tools/oiio_module.h, tools/vdb_module.h): shared objects
// built next to the `pupwave` binary that hold the code linking heavy libraries, so that commands
// not needing them never pay for loading those libraries.

#include <string>

namespace pupwave::cli {

// dlopens module file `name` (beside the running executable, else at `build_path`, where the
// build wrote it: test and benchmark programs live in other folders of the build tree) and returns
// what its entry function `entry` returns. Throws std::runtime_error "cannot load the <what>
// module <name> (<needed_for>; it belongs next to the pupwave binary): <reason>".
const void* load_module(const char* name, const char* build_path, const char* entry, const std::string& what,
                        const std::string& needed_for);

}  // namespace pupwave::cli

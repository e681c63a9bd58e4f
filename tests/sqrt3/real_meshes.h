#pragma once
// The real meshes of testimages/ (provenance in testimages/README.md), read with pupwave's reader.

#include <string>

#include "tools/mesh_io.h"

namespace pupwave::sqrt3::test {

inline TriMesh real_mesh(const std::string& name) {
  return cli::read_mesh(std::string(PUPWAVE_TESTIMAGES_DIR) + "/" + name);
}

inline const char* const kClosedMeshes[] = {"dragknob.off", "u.off", "eight.off"};
inline const char* const kOpenMeshes[] = {"nefertiti.off", "pig.off"};

}  // namespace pupwave::sqrt3::test

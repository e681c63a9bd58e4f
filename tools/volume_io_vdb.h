#pragma once
// OpenVDB files as OpenVDB grids, for tools that work on the trees themselves (`pupwave lod`):
// the same error handling as read_vdb / write_vdb in tools/volume_io.h, file metadata included.

#include <openvdb/openvdb.h>

#include <filesystem>

namespace pupwave::cli {

struct VdbFile {
  openvdb::GridPtrVec grids;
  openvdb::MetaMap metadata;  // file-level metadata, every type
};

// Every grid of the file with its trees, and the file metadata. Throws std::runtime_error naming
// the file for missing, unreadable, corrupt or empty files.
VdbFile read_vdb_file(const std::filesystem::path& path);

// Writes grids and file metadata atomically (nothing is left at path on failure).
void write_vdb_file(const openvdb::GridPtrVec& grids, const openvdb::MetaMap& metadata,
                    const std::filesystem::path& path);

}  // namespace pupwave::cli

#pragma once
// OpenVDB files as OpenVDB grids, for tools that work on the trees themselves (`pupwave lod`):
// the same error handling as read_vdb / write_vdb in tools/volume_io.h, file metadata included.
// Only the VDB module (tools/vdb/, see tools/vdb_module.h) and tests link this code.

#include <openvdb/openvdb.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "codec/volume/volume.h"

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

// The implementations behind read_vdb, describe_vdb_file and write_vdb of tools/volume_io.h
// (same contracts), which reach them through the module's function table.
std::vector<VolumeGrid> read_vdb_grids(const std::filesystem::path& path, std::string_view grid_name,
                                       std::vector<std::string>* skipped);
std::string describe_vdb_grids(const std::filesystem::path& path);
void write_vdb_grids(const std::vector<VolumeGrid>& grids, const std::filesystem::path& path);

}  // namespace pupwave::cli

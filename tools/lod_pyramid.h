#pragma once
// Sparse level-of-detail pyramids on OpenVDB trees (`pupwave lod`): every level is made from the
// previous one, coarse leaf by coarse leaf, so time and memory follow the active voxels and tiles
// of the grid, not its bounding box. See tools/cmd_lod.cpp for the conventions of the output.

#include <openvdb/openvdb.h>

#include <cstddef>
#include <vector>

#include "tools/lod_low_pass.h"

namespace pupwave::cli {

// Most coarse leaves one level of one grid may compute (bounds time and memory for hostile
// files whose few bytes declare huge active tiles).
inline constexpr std::size_t kMaxLodLeavesPerLevel = std::size_t(1) << 18;

// The requested levels (ascending, 0 = the input itself) of a float, double, vec3s, vec3d, int32
// or int64 grid, named NAME_level_K with vdb_lod's metadata and pre-scaled transforms. Vector
// grids are reduced per component; integer grids are rounded to the nearest integer (vdb_lod
// makes levels of them too; it skips bool grids, which `lod` copies). Throws
// std::runtime_error naming the grid when a level exceeds the leaf limit.
openvdb::GridPtrVec level_of_detail(const openvdb::GridBase::Ptr& grid, const LowPass& low_pass,
                                    const std::vector<int>& levels, LodEdge edge,
                                    std::size_t max_leaves = kMaxLodLeavesPerLevel);

// True for the value types level_of_detail reduces (float, double, vec3s, vec3d, int32, int64).
bool has_lod(const openvdb::GridBase& grid);

}  // namespace pupwave::cli

#pragma once
// Volume files <-> the library's Volume / VolumeGrid: raw dense volumes (little endian) and
// OpenVDB files (FloatGrid, DoubleGrid; the OpenVDB code is in the module of vdb_module.h).
// Raw files compressed and decompressed in their own type, without a copy, go through
// volume_raw.h instead.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "codec/volume/volume.h"

namespace pupwave::cli {

// Largest raw volume accepted (voxels). A raw file must hold exactly dims * bytes per voxel, so
// memory use is bounded by the real file size; this only bounds absurd --dims early.
inline constexpr std::size_t kMaxRawVoxels = std::size_t(1) << 30;
// Largest dense box made from one OpenVDB grid by read_vdb_dense (voxels, 2 GiB as double). A
// tiny hostile .vdb can declare active tiles spanning any box, so the box is checked first.
inline constexpr std::size_t kMaxVdbBoxVoxels = std::size_t(1) << 28;

// Parses --dims "X,Y,Z" (or "X,Y" / "X", missing axes = 1); every extent >= 1.
// Throws std::invalid_argument with the offending text.
Extent parse_dims(std::string_view text);

// Bytes a raw file of dims x type must hold, checked against the file on disk; throws
// std::runtime_error naming the file (too many voxels, no such file, wrong size).
std::size_t raw_file_size(const std::filesystem::path& path, const Extent& dims, VoxelType type,
                          std::size_t max_voxels);

// Reads a raw dense volume of `dims` samples of `type`, little endian, x fastest. The file size
// must equal dims[0]*dims[1]*dims[2]*bytes_per_voxel(type) exactly; otherwise, for absurd dims or
// above max_voxels, throws std::runtime_error naming the file, the sizes and the options.
Volume read_raw_volume(const std::filesystem::path& path, const Extent& dims, VoxelType type,
                       std::size_t max_voxels = kMaxRawVoxels);

// Writes volume.samples as `volume.type`, little endian, atomically. Integer types are rounded
// and clamped to their range (NaN becomes 0). The active mask, if any, is not stored.
void write_raw_volume(const Volume& volume, const std::filesystem::path& path);

// True when the path names an OpenVDB file (extension .vdb, any case).
bool is_vdb_path(const std::filesystem::path& path);

// Reads the grids of an OpenVDB file; with a non-empty grid_name only the grids of that name (an
// error listing the available names when there is none). Grids of other value types than float
// and double (vec3s/d, int32/64, bool, mask, unknown) become opaque grids (VolumeGrid::opaque:
// OpenVDB's own serialisation, restored bit exact by write_vdb; their names also go to *skipped
// if given). Each float/double grid is read sparse-native (VolumeGrid::blocks and tiles): the
// leaf nodes of each 64^3 page become one block over their bounding box, tiles stay tiles
// (active ones and inactive ones that are not the background), so memory follows the leaves,
// not the bounding box (origin / volume.dims: the active bounding box). Background, class,
// linear transform and metadata are kept (string, bool, int32/64, float/double, vec3i/s/d
// entries; the per-file statistics "file_*" that OpenVDB rewrites on every write are dropped).
// Throws std::runtime_error for unreadable or corrupt input and non-linear (frustum) transforms.
std::vector<VolumeGrid> read_vdb(const std::filesystem::path& path, std::string_view grid_name = {},
                                 std::vector<std::string>* skipped = nullptr);

// read_vdb, then each float/double grid converted to a dense box over its active bounding box
// (make_dense_box); throws std::runtime_error when a box exceeds max_box_voxels.
std::vector<VolumeGrid> read_vdb_dense(const std::filesystem::path& path, std::string_view grid_name = {},
                                       std::vector<std::string>* skipped = nullptr,
                                       std::size_t max_box_voxels = kMaxVdbBoxVoxels);

// `pupwave info` of a .vdb file: every grid (any value type) with class, value type, active
// voxel and tile counts, active bounding box and voxel size. Throws like read_vdb.
std::string describe_vdb_file(const std::filesystem::path& path);

// Writes grids to an OpenVDB file atomically: opaque grids as they were read, f64 volumes as
// DoubleGrid, all others as FloatGrid,
// with the same background, active topology, values inside the box (or of the blocks and tiles
// of a sparse-native grid), class, transform and metadata (uniform leaves are pruned back into
// tiles). Grid names need not be unique.
void write_vdb(const std::vector<VolumeGrid>& grids, const std::filesystem::path& path);

}  // namespace pupwave::cli

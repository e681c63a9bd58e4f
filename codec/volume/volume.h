#pragma once
// The plain in-memory volume every layer exchanges (the 3-D sibling of codec/image/image.h): a dense
// scalar field, optionally sparse (active mask + background), plus the grid description the
// tools layer fills from OpenVDB or raw files and the codec stores opaquely. No file-format
// types appear here.

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "transforms/subband.h"

namespace pupwave {

// Sample type of the file a volume came from (and is written back as).
enum class VoxelType : std::uint8_t { u8 = 0, u16 = 1, f32 = 2, f64 = 3 };

// "u8", "u16", "f32", "f64" (the spelling of --dtype).
std::string to_string(VoxelType type);
// Inverse of to_string; throws std::invalid_argument naming the accepted spellings.
VoxelType parse_voxel_type(std::string_view name);
// Bytes per stored sample (1, 2, 4, 8).
std::size_t bytes_per_voxel(VoxelType type);
bool is_integer(VoxelType type);

// A dense field of dims[0] * dims[1] * dims[2] samples, x fastest
// (index = x + dims[0] * (y + dims[1] * z)). Samples are held as double, which represents every
// supported stored type exactly (u8, u16, f32, f64).
//
// Sparse grids (OpenVDB) are held over a box (usually the bounding box of the active voxels):
// `active` then has one byte per sample (1 = active, 0 = inactive) and the inactive samples keep
// their stored values (a level set's inside is -background). Outside the box every voxel is
// inactive with value `background`. An empty `active` means every sample is active (dense data).
struct Volume {
  Extent dims{0, 0, 0};
  VoxelType type = VoxelType::f32;
  std::vector<double> samples;
  std::vector<std::uint8_t> active;
  double background = 0.0;

  Volume() = default;
  Volume(const Extent& d, VoxelType t);

  std::size_t count() const { return dims[0] * dims[1] * dims[2]; }
  std::size_t index(std::size_t x, std::size_t y, std::size_t z) const {
    return x + dims[0] * (y + dims[1] * z);
  }
  double& at(std::size_t x, std::size_t y, std::size_t z) { return samples[index(x, y, z)]; }
  double at(std::size_t x, std::size_t y, std::size_t z) const { return samples[index(x, y, z)]; }
  bool is_sparse() const { return !active.empty(); }
  bool is_active(std::size_t i) const { return active.empty() || active[i] != 0; }
  std::size_t active_count() const;
};

// What a grid's values mean (OpenVDB's grid classes that matter for scalar fields).
enum class GridClass : std::uint8_t { unknown = 0, level_set = 1, fog_volume = 2 };
std::string to_string(GridClass grid_class);

// One metadata entry of a grid, typed so that it is written back with its original type.
struct MetaValue {
  enum class Kind : std::uint8_t { string = 0, boolean, int32, int64, float32, float64, vec3i, vec3f, vec3d };
  Kind kind = Kind::string;
  std::string text;                        // Kind::string
  std::int64_t integer = 0;                // boolean, int32, int64
  std::array<double, 3> numbers{0, 0, 0};  // float32/float64 use numbers[0]; vec3* all three
  bool operator==(const MetaValue&) const = default;
};

// Part of a sparse grid held natively (OpenVDB leaf nodes gathered into a block of at most one
// 64^3 page): `volume` (with its active mask) covers index-space box [origin, origin + dims).
// Voxels of a block that no leaf covers are inactive background.
struct VolumeBlock {
  std::array<std::int64_t, 3> origin{0, 0, 0};
  Volume volume;
};

// A tile of a sparse grid (an OpenVDB tile value): every voxel of the cube [origin, origin + edge)
// has `value` and the same active state. A constant region costs a tile, not its voxels.
struct VolumeTile {
  std::array<std::int64_t, 3> origin{0, 0, 0};
  std::uint32_t edge = 1;
  double value = 0.0;
  bool active = false;
  bool operator==(const VolumeTile&) const = default;
};

// A named volume with its placement in the world, as OpenVDB describes a grid. Sample (0,0,0)
// of `volume` sits at integer index-space coordinate `origin`; index_to_world maps index space to
// world space in OpenVDB's row-vector convention: [x y z 1] * M, so the translation is in row 3
// (index_to_world[12..14]) and M is stored row-major.
struct VolumeGrid {
  std::string name;
  GridClass grid_class = GridClass::unknown;
  std::array<std::int64_t, 3> origin{0, 0, 0};
  std::array<double, 16> index_to_world{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  std::map<std::string, MetaValue> metadata;
  Volume volume;
  // Sparse-native form (is_blocked()): the values live in `blocks` and `tiles`, disjoint, and
  // everything else is inactive background; `volume` then only carries type, background and the
  // active bounding box (dims, with `origin` its minimum), no samples.
  std::vector<VolumeBlock> blocks;
  std::vector<VolumeTile> tiles;
  // A grid the codec does not transform-code (OpenVDB vector, integer, bool, mask and unknown
  // value types): OpenVDB's own serialisation of it, carried verbatim so it comes back bit exact
  // (values, topology, transform, metadata). Only `name` and the "vdb_*" metadata describe it.
  std::vector<std::uint8_t> opaque;

  bool is_opaque() const { return !opaque.empty(); }

  bool is_blocked() const { return !blocks.empty() || !tiles.empty(); }
  // Active voxels (tiles counted voxel by voxel) and active tiles.
  std::size_t active_voxels() const;
  std::size_t active_tiles() const;

  // Voxel size along each index axis (length of the rows 0..2 of the linear part).
  std::array<double, 3> voxel_size() const;
};

// Converts a sparse-native grid to the dense-box form over its active bounding box (inactive
// values inside the box kept, tiles expanded). Throws std::runtime_error naming the grid when the
// box holds more than max_voxels. Dense grids are left unchanged.
void make_dense_box(VolumeGrid& grid, std::size_t max_voxels);

}  // namespace pupwave

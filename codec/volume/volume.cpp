#include "codec/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pupwave {

std::string to_string(VoxelType type) {
  switch (type) {
    case VoxelType::u8: return "u8";
    case VoxelType::u16: return "u16";
    case VoxelType::f32: return "f32";
    case VoxelType::f64: return "f64";
  }
  return "unknown";
}

VoxelType parse_voxel_type(std::string_view name) {
  for (VoxelType t : {VoxelType::u8, VoxelType::u16, VoxelType::f32, VoxelType::f64})
    if (name == to_string(t)) return t;
  throw std::invalid_argument("unknown voxel type '" + std::string(name) +
                              "' (expected u8, u16, f32 or f64)");
}

std::size_t bytes_per_voxel(VoxelType type) {
  switch (type) {
    case VoxelType::u8: return 1;
    case VoxelType::u16: return 2;
    case VoxelType::f32: return 4;
    case VoxelType::f64: return 8;
  }
  return 0;
}

bool is_integer(VoxelType type) { return type == VoxelType::u8 || type == VoxelType::u16; }

Volume::Volume(const Extent& d, VoxelType t) : dims(d), type(t), samples(d[0] * d[1] * d[2], 0.0) {}

std::size_t Volume::active_count() const {
  if (active.empty()) return count();
  return static_cast<std::size_t>(
      std::count_if(active.begin(), active.end(), [](std::uint8_t a) { return a != 0; }));
}

std::string to_string(GridClass grid_class) {
  switch (grid_class) {
    case GridClass::unknown: return "unknown";
    case GridClass::level_set: return "level set";
    case GridClass::fog_volume: return "fog volume";
  }
  return "unknown";
}

std::array<double, 3> VolumeGrid::voxel_size() const {
  std::array<double, 3> size{};
  for (int r = 0; r < 3; ++r) {
    const double* row = &index_to_world[static_cast<std::size_t>(4 * r)];
    size[static_cast<std::size_t>(r)] = std::sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]);
  }
  return size;
}

std::size_t VolumeGrid::active_voxels() const {
  if (!is_blocked()) return volume.active_count();
  std::size_t n = 0;
  for (const VolumeBlock& b : blocks) n += b.volume.active_count();
  for (const VolumeTile& t : tiles)
    if (t.active) n += std::size_t(t.edge) * t.edge * t.edge;
  return n;
}

std::size_t VolumeGrid::active_tiles() const {
  return std::size_t(std::count_if(tiles.begin(), tiles.end(), [](const VolumeTile& t) { return t.active; }));
}

namespace {

// Writes the part of the cube [at, at + edge) inside the box of `v` (at origin `o`).
void fill_box(Volume& v, const std::array<std::int64_t, 3>& o, const std::array<std::int64_t, 3>& at,
              const std::array<std::int64_t, 3>& size, double value, bool active) {
  std::array<std::int64_t, 3> lo{}, hi{};
  for (std::size_t a = 0; a < 3; ++a) {
    lo[a] = std::max(at[a], o[a]) - o[a];
    hi[a] = std::min(at[a] + size[a], o[a] + std::int64_t(v.dims[a])) - o[a];
    if (hi[a] <= lo[a]) return;
  }
  for (std::int64_t z = lo[2]; z < hi[2]; ++z)
    for (std::int64_t y = lo[1]; y < hi[1]; ++y)
      for (std::int64_t x = lo[0]; x < hi[0]; ++x) {
        const std::size_t i = v.index(std::size_t(x), std::size_t(y), std::size_t(z));
        v.samples[i] = value;
        v.active[i] = active ? 1 : 0;
      }
}

}  // namespace

void make_dense_box(VolumeGrid& grid, std::size_t max_voxels) {
  if (grid.is_opaque())
    throw std::runtime_error("grid '" + grid.name +
                             "' is not a float or double scalar field (carried as OpenVDB bytes only)");
  if (!grid.is_blocked()) return;
  const Extent dims = grid.volume.dims;
  std::size_t count = 1;
  for (std::size_t d : dims) count = d == 0 || count > max_voxels / d ? max_voxels + 1 : count * d;
  if (count > max_voxels)
    throw std::runtime_error("grid '" + grid.name + "' spans " + std::to_string(dims[0]) + "," +
                             std::to_string(dims[1]) + "," + std::to_string(dims[2]) +
                             " voxels, more than the limit of " + std::to_string(max_voxels) +
                             " for a dense box");
  Volume v(dims, grid.volume.type);
  v.background = grid.volume.background;
  std::fill(v.samples.begin(), v.samples.end(), v.background);
  v.active.assign(count, 0);
  for (const VolumeTile& t : grid.tiles) {
    const std::int64_t e = t.edge;
    fill_box(v, grid.origin, t.origin, {e, e, e}, t.value, t.active);
  }
  for (const VolumeBlock& b : grid.blocks) {
    const Volume& s = b.volume;
    for (std::size_t z = 0; z < s.dims[2]; ++z)
      for (std::size_t y = 0; y < s.dims[1]; ++y)
        for (std::size_t x = 0; x < s.dims[0]; ++x) {
          const std::size_t i = s.index(x, y, z);
          const std::array<std::int64_t, 3> at{b.origin[0] + std::int64_t(x), b.origin[1] + std::int64_t(y),
                                               b.origin[2] + std::int64_t(z)};
          if (s.is_active(i) || s.samples[i] != v.background)
            fill_box(v, grid.origin, at, {1, 1, 1}, s.samples[i], s.is_active(i));
        }
  }
  grid.volume = std::move(v);
  grid.blocks.clear();
  grid.tiles.clear();
}

}  // namespace pupwave

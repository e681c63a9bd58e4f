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

}  // namespace pupwave

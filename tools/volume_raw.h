#pragma once
// Raw dense volume files held in their own type: the input is memory-mapped read-only and
// viewed in place (u8 stays one byte a voxel), so compressing a raw file never copies it or
// widens it to double; the output is decoded into a buffer of the stored type brick by brick.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include "codec/volume/volume_view.h"
#include "tools/mapped_file.h"

namespace pupwave::cli {

// A raw file (little endian, x fastest) of `dims` voxels of `type`, mapped read-only for as
// long as the object lives (on big-endian hosts read and byte-swapped into memory instead).
class MappedRawVolume {
 public:
  // Throws std::runtime_error naming the file and the sizes, like read_raw_volume (volume_io.h):
  // the file size must equal dims * bytes_per_voxel(type) and dims at most max_voxels.
  MappedRawVolume(const std::filesystem::path& path, const Extent& dims, VoxelType type,
                  std::size_t max_voxels);
  MappedRawVolume(const MappedRawVolume&) = delete;
  MappedRawVolume& operator=(const MappedRawVolume&) = delete;

  // Contiguous view of the voxels (type and storage = the file's type).
  const VolumeView& view() const { return view_; }

 private:
  std::optional<MappedFile> file_;     // little-endian hosts
  std::vector<std::uint8_t> swapped_;  // big-endian hosts only
  VolumeView view_;
};

// Writes `bytes` (voxels of `type` in host order, x fastest) as a little-endian raw file,
// atomically.
void write_raw_bytes(std::vector<std::uint8_t> bytes, VoxelType type, const std::filesystem::path& path);

// Voxels of `type` in host order to little endian, in place (only big-endian hosts change them).
void swap_to_little_endian(std::span<std::uint8_t> bytes, VoxelType type);

}  // namespace pupwave::cli

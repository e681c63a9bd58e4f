#include "tools/volume_raw.h"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include "tools/atomic_file.h"
#include "tools/volume_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// VolumeView::drop_rows for a view of a mapped raw file: unmaps rows [y0, y1) of planes [z0, z1)
// (the encoder's passes read the input by rows of bricks; pages read stay resident until
// dropped). Whole pages around the rows go: a neighbour row still reading faults them back in.
void drop_rows(const void* context, const VolumeView& v, std::size_t z0, std::size_t z1, std::size_t y0,
               std::size_t y1) {
  const auto* file = static_cast<const MappedFile*>(context);
  const std::size_t voxel = bytes_per_voxel(v.storage);
  const std::size_t plane = std::size_t(v.strides[2]) * voxel, row = std::size_t(v.strides[1]) * voxel;
  const std::size_t start = std::size_t(static_cast<const std::uint8_t*>(v.data) - file->bytes().data());
  if (y0 == 0 && y1 == v.dims[1]) {  // whole planes: one call
    file->drop(start + z0 * plane, (z1 - z0) * plane);
    return;
  }
  for (std::size_t z = z0; z < z1; ++z) file->drop(start + z * plane + y0 * row, (y1 - y0) * row);
}

// Reverses the bytes of every `width`-byte element (raw files are little endian).
void swap_elements(std::span<std::uint8_t> bytes, std::size_t width) {
  for (std::size_t i = 0; i + width <= bytes.size(); i += width)
    std::reverse(bytes.begin() + std::ptrdiff_t(i), bytes.begin() + std::ptrdiff_t(i + width));
}

}  // namespace

MappedRawVolume::MappedRawVolume(const fs::path& path, const Extent& dims, VoxelType type,
                                 std::size_t max_voxels) {
  const std::size_t size = raw_file_size(path, dims, type, max_voxels);
  const void* data = nullptr;
  if constexpr (std::endian::native == std::endian::little) {
    file_.emplace(path);
    file_->advise_sequential();  // bricks are read slab by slab, z increasing
    data = file_->bytes().data();
  } else {
    swapped_ = read_file_bytes(path, size);
    swap_elements(swapped_, bytes_per_voxel(type));
    data = swapped_.data();
  }
  view_ = contiguous_view(data, dims, type);
  if (file_) view_.drop_context = &*file_, view_.drop_rows = drop_rows;
}

void write_raw_bytes(std::vector<std::uint8_t> bytes, VoxelType type, const fs::path& path) {
  if constexpr (std::endian::native == std::endian::big) swap_elements(bytes, bytes_per_voxel(type));
  write_output_bytes(path, bytes);
}

void swap_to_little_endian(std::span<std::uint8_t> bytes, VoxelType type) {
  if constexpr (std::endian::native == std::endian::big) swap_elements(bytes, bytes_per_voxel(type));
}

}  // namespace pupwave::cli

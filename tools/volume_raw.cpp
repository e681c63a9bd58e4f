#include "tools/volume_raw.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "tools/atomic_file.h"
#include "tools/volume_io.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// Reverses the bytes of every `width`-byte element (raw files are little endian).
void swap_elements(std::vector<std::uint8_t>& bytes, std::size_t width) {
  for (std::size_t i = 0; i + width <= bytes.size(); i += width)
    std::reverse(bytes.begin() + std::ptrdiff_t(i), bytes.begin() + std::ptrdiff_t(i + width));
}

}  // namespace

MappedRawVolume::MappedRawVolume(const fs::path& path, const Extent& dims, VoxelType type,
                                 std::size_t max_voxels)
    : size_(raw_file_size(path, dims, type, max_voxels)) {
  const void* data = nullptr;
  if constexpr (std::endian::native == std::endian::little) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error("cannot read " + path.string() + ": " + std::strerror(errno));
    map_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    const int err = errno;
    ::close(fd);
    if (map_ == MAP_FAILED) {
      map_ = nullptr;
      throw std::runtime_error("cannot map " + path.string() + ": " + std::strerror(err));
    }
    ::madvise(map_, size_, MADV_SEQUENTIAL);  // bricks are read slab by slab, z increasing
    data = map_;
  } else {
    swapped_ = read_file_bytes(path, size_);
    swap_elements(swapped_, bytes_per_voxel(type));
    data = swapped_.data();
  }
  view_ = contiguous_view(data, dims, type);
}

MappedRawVolume::~MappedRawVolume() {
  if (map_ != nullptr) ::munmap(map_, size_);
}

void write_raw_bytes(std::vector<std::uint8_t> bytes, VoxelType type, const fs::path& path) {
  if constexpr (std::endian::native == std::endian::big) swap_elements(bytes, bytes_per_voxel(type));
  write_bytes_atomically(path, bytes);
}

}  // namespace pupwave::cli

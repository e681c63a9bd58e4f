#include "tools/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace pupwave::cli {

MappedFile::MappedFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot read " + path.string() + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw std::runtime_error("cannot read " + path.string() + ": not a regular file");
  }
  size_ = std::size_t(st.st_size);
  if (size_ > 0) {
    map_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    const int err = errno;
    if (map_ == MAP_FAILED) {
      map_ = nullptr;
      ::close(fd);
      throw std::runtime_error("cannot map " + path.string() + ": " + std::strerror(err));
    }
  }
  ::close(fd);
}

void MappedFile::advise_sequential() const {
  if (map_ != nullptr) ::madvise(map_, size_, MADV_SEQUENTIAL);
}

void MappedFile::drop(std::size_t offset, std::size_t length) const {
  if (map_ == nullptr || offset >= size_) return;
  const auto page = std::size_t(::sysconf(_SC_PAGESIZE));
  const std::size_t first = offset / page * page, end = std::min(size_, offset + length);
  // MADV_DONTNEED on a read-only private mapping only unmaps: the file's pages stay cached.
  ::madvise(static_cast<std::uint8_t*>(map_) + first, end - first, MADV_DONTNEED);
}

MappedFile::~MappedFile() {
  if (map_ != nullptr) ::munmap(map_, size_);
}

}  // namespace pupwave::cli

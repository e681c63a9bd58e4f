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

MappedOutput::MappedOutput(const std::filesystem::path& path, std::size_t size,
                           const std::filesystem::path& target)
    : size_(size), target_(target) {
  const auto fail = [&](const std::string& why) {
    if (map_ != nullptr) ::munmap(map_, size_);
    if (fd_ >= 0) ::close(fd_);
    map_ = nullptr;
    fd_ = -1;
    throw std::runtime_error("cannot write " + target_.string() + ": " + why);
  };
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) fail(std::strerror(errno));
  if (size_ == 0) return;
  if (const int err = ::posix_fallocate(fd_, 0, off_t(size_)); err != 0) fail(std::strerror(err));
  void* map = ::mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
  if (map == MAP_FAILED) fail(std::strerror(errno));
  map_ = map;
}

void MappedOutput::release(std::size_t offset, std::size_t length) const {
  if (map_ == nullptr || offset >= size_) return;
  const auto page = std::size_t(::sysconf(_SC_PAGESIZE));
  const std::size_t first = (offset + page - 1) / page * page;  // whole pages only: its
  std::size_t end = std::min(size_, offset + length);           // neighbours may be in use
  if (end < size_) end = end / page * page;
  // On a shared file mapping MADV_DONTNEED only unmaps: the dirty bits pass to the page cache.
  if (end > first) ::madvise(static_cast<std::uint8_t*>(map_) + first, end - first, MADV_DONTNEED);
}

void MappedOutput::finish() {
  if (map_ != nullptr && ::munmap(map_, size_) != 0) {
    map_ = nullptr;
    throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(errno));
  }
  map_ = nullptr;
  const int fd = fd_;
  fd_ = -1;
  if (fd >= 0 && ::close(fd) != 0)
    throw std::runtime_error("cannot write " + target_.string() + ": " + std::strerror(errno));
}

MappedOutput::~MappedOutput() {
  if (map_ != nullptr) ::munmap(map_, size_);
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace pupwave::cli

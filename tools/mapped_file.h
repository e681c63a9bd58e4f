#pragma once
// A whole input file mapped read-only, so a decoder reads from disk only the pages it touches:
// a reduced-resolution decode never reads the finer resolutions' data, and a stream is never
// copied into the heap.

#include <cstdint>
#include <filesystem>
#include <span>

namespace pupwave::cli {

class MappedFile {
 public:
  // Throws std::runtime_error("cannot read PATH: reason") when the file cannot be opened or mapped.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const std::uint8_t> bytes() const { return {static_cast<const std::uint8_t*>(map_), size_}; }
  // Tells the kernel the pages will be read in order (read-ahead), as raw volume slabs are.
  void advise_sequential() const;
  // Drops the pages holding bytes [offset, offset + length) from the process's resident memory
  // (whole pages, clamped to the file); reading them again maps them back from the page cache.
  void drop(std::size_t offset, std::size_t length) const;

 private:
  void* map_ = nullptr;  // null for an empty file
  std::size_t size_ = 0;
};

// A new output file of a known size mapped writable, so a decoder writes its voxels straight
// into the page cache (no heap buffer to zero, no copy by write()). Its blocks are reserved
// first (posix_fallocate): a full disk is an error here, never a SIGBUS while writing through
// the map. Used under write_output, on its temporary name.
class MappedOutput {
 public:
  // Throws std::runtime_error("cannot write TARGET: reason") (target: the name the user gave).
  MappedOutput(const std::filesystem::path& path, std::size_t size, const std::filesystem::path& target);
  ~MappedOutput();
  MappedOutput(const MappedOutput&) = delete;
  MappedOutput& operator=(const MappedOutput&) = delete;

  std::span<std::uint8_t> bytes() const { return {static_cast<std::uint8_t*>(map_), size_}; }
  // Unmaps the whole pages of bytes [offset, offset + length) once written, so they leave this
  // process's resident memory: they stay in the page cache, dirty, and reach the file as any
  // other (writing them again maps them back). Thread-safe.
  void release(std::size_t offset, std::size_t length) const;
  // Unmaps and closes the file; throws like the constructor when closing fails.
  void finish();

 private:
  void* map_ = nullptr;
  std::size_t size_ = 0;
  int fd_ = -1;
  std::filesystem::path target_;
};

}  // namespace pupwave::cli

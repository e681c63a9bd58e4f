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

}  // namespace pupwave::cli

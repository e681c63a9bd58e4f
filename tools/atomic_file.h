#pragma once
// Where the CLI's outputs go. A regular file (or a new path) is written under a temporary name
// beside it and renamed into place, so it appears whole or not at all and a failure leaves an
// existing file as it was. Any other existing path, a character device, a FIFO or a socket, and
// "-" (stdout) is opened and written in place: never renamed over, truncated or unlinked, since
// it belongs to someone else (a device node, a pipe feeding another program). A block device
// is refused. A symbolic link is followed and stays a link. Every I/O error names the user's
// path and the system's reason.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

namespace pupwave::cli {

// What an output path names, decided by check_output_path.
enum class OutputKind {
  file,    // a regular file or a new path: written atomically
  stream,  // "-", a character device or a FIFO: opened and written in place
  socket,  // a Unix socket: connected to and written
};

// Checks that `target` can take an output and says how it is written; throws
// std::runtime_error naming the path and the reason otherwise (a directory, a block device, a
// missing folder, an empty name). Call before doing expensive work.
OutputKind check_output_path(const std::filesystem::path& target);

// Produces the output: calls write(path) to make the file at a path it may seek in and map,
// then puts it in place. For a regular file the path is a temporary name beside the target,
// renamed onto it (an existing file keeps its permission bits); for a stream it is a scratch
// file in the temporary folder whose bytes are then copied into the stream. The temporary
// name keeps the target's extension, which writers may read. On any exception nothing is left
// behind, the target is untouched, and the exception propagates with the temporary name
// replaced by the target's.
void write_output(const std::filesystem::path& target,
                  const std::function<void(const std::filesystem::path&)>& write);

// Writes bytes to `target` (see write_output; a stream is written directly).
void write_output_bytes(const std::filesystem::path& target, std::span<const std::uint8_t> bytes);

// A file opened for writing by descriptor, whose errors carry the system's reason and the name
// the user knows it by.
class OutputFile {
 public:
  // Creates or truncates `path`; `shown` is the name errors give (default: path).
  explicit OutputFile(const std::filesystem::path& path, const std::filesystem::path& shown = {});
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  // Throws std::runtime_error("cannot write SHOWN: reason") on a failed write.
  void write(std::span<const std::uint8_t> bytes);
  // Closes the file; throws like write (a full disk may show only here, on NFS for example).
  void close();

 private:
  int fd_ = -1;
  std::filesystem::path shown_;
};

// Throws std::runtime_error("cannot write PATH: reason"), the reason read from errno, for
// writers that go through stdio or iostreams (which keep errno from the failed call).
[[noreturn]] void throw_write_error(const std::filesystem::path& path);

// Reads a whole file ("-": stdin; a pipe or device is read to its end); throws std::runtime_error("cannot
// read PATH: reason") when it cannot, and refuses files larger than max_bytes so hostile input cannot exhaust
// memory.
std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& path,
                                          std::uintmax_t max_bytes = std::uintmax_t(1) << 34);

}  // namespace pupwave::cli

#include "tools/atomic_file.h"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

bool is_stdout(const fs::path& target) { return target == "-"; }

// The name errors give for an output: the user's path, or "stdout" for "-".
std::string shown(const fs::path& target) {
  return is_stdout(target) ? std::string("stdout") : target.string();
}

[[noreturn]] void fail(const std::string& verb, const fs::path& target, int error) {
  throw std::runtime_error("cannot " + verb + " " + shown(target) + ": " + std::strerror(error));
}

// The path a chain of symbolic links ends at (the path itself when it is no link), so that a
// link to a file, or a dangling link, is written through and stays a link.
fs::path follow_links(const fs::path& target) {
  fs::path at = target;
  for (int hops = 0; hops < 40; ++hops) {  // 40: the kernel's own limit (ELOOP)
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(at, ec))) return at;
    const fs::path link = fs::read_symlink(at, ec);
    if (ec) fail("write", target, ec.value());
    at = link.is_absolute() ? link : at.parent_path() / link;
  }
  fail("write", target, ELOOP);
}

// A unique hidden name beside the target, so the final rename stays on one file system; it
// keeps the extension, which format writers read.
fs::path temporary_name(const fs::path& target) {
  std::random_device rd;
  const auto tag = std::to_string(rd()) + std::to_string(rd());
  fs::path tmp = target;
  tmp.replace_filename("." + target.filename().string() + ".tmp" + tag + target.extension().string());
  return tmp;
}

// A fresh scratch name in the temporary folder, with the target's extension.
fs::path scratch_name(const fs::path& target) {
  std::random_device rd;
  const std::string extension = is_stdout(target) ? std::string() : target.extension().string();
  return fs::temp_directory_path() / ("pupwave-" + std::to_string(rd()) + std::to_string(rd()) + extension);
}

// Writes all of `bytes` to fd, however the kernel splits them.
void write_all(int fd, std::span<const std::uint8_t> bytes, const fs::path& target) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("write", target, n < 0 ? errno : EIO);
    bytes = bytes.subspan(std::size_t(n));
  }
}

// A descriptor for writing into an existing stream in place: no O_CREAT, no O_TRUNC (the node
// stays what it is); a socket is connected to.
class StreamFd {
 public:
  StreamFd(const fs::path& target, OutputKind kind) : target_(target) {
    if (is_stdout(target)) {
      std::fflush(stdout);  // status lines written through stdio go first
      fd_ = STDOUT_FILENO;
      return;
    }
    if (kind == OutputKind::socket) {
      connect_socket();
      return;
    }
    fd_ = ::open(target.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) fail("write", target, errno);
    owned_ = true;
  }
  ~StreamFd() {
    if (owned_) ::close(fd_);
  }
  StreamFd(const StreamFd&) = delete;
  StreamFd& operator=(const StreamFd&) = delete;
  void write(std::span<const std::uint8_t> bytes) { write_all(fd_, bytes, target_); }
  void close() {
    if (!owned_) return;
    owned_ = false;
    if (::close(fd_) != 0 && errno != EINTR) fail("write", target_, errno);
  }

 private:
  void connect_socket() {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    const std::string path = target_.string();
    if (path.size() >= sizeof address.sun_path) fail("write", target_, ENAMETOOLONG);
    std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
    fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd_ < 0) fail("write", target_, errno);
    owned_ = true;
    if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0)
      fail("write", target_, errno);
  }

  int fd_ = -1;
  bool owned_ = false;
  fs::path target_;
};

// Copies a finished scratch file into the stream, a megabyte at a time.
void copy_into_stream(const fs::path& scratch, const fs::path& target, OutputKind kind) {
  const int in = ::open(scratch.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) fail("write", target, errno);
  StreamFd out(target, kind);
  std::vector<std::uint8_t> buffer(std::size_t(1) << 20);
  for (;;) {
    const ssize_t n = ::read(in, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(in);
      fail("write", target, error);
    }
    if (n == 0) break;
    try {
      out.write({buffer.data(), std::size_t(n)});
    } catch (...) {
      ::close(in);
      throw;
    }
  }
  ::close(in);
  out.close();
}

// Rethrows the current exception with `temporary` replaced by `target` in its message: writers
// name the file they were given, and the user knows only their own path.
[[noreturn]] void rethrow_naming(const fs::path& temporary, const fs::path& target) {
  try {
    throw;
  } catch (const std::exception& e) {
    std::string message = e.what();
    const std::string from = temporary.string(), to = shown(target);
    if (message.find(from) == std::string::npos) throw;
    for (std::size_t at = message.find(from); at != std::string::npos;
         at = message.find(from, at + to.size()))
      message.replace(at, from.size(), to);
    throw std::runtime_error(message);
  }
}

}  // namespace

OutputKind check_output_path(const fs::path& target) {
  if (target.empty()) throw std::runtime_error("output path is empty");
  if (is_stdout(target)) return OutputKind::stream;
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0) {  // follows links: the kind is the link target's
    if (S_ISREG(st.st_mode)) return OutputKind::file;
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) return OutputKind::stream;
    if (S_ISSOCK(st.st_mode)) return OutputKind::socket;
    if (S_ISDIR(st.st_mode))
      throw std::runtime_error("cannot write " + target.string() + ": it is a directory");
    if (S_ISBLK(st.st_mode))
      throw std::runtime_error("cannot write " + target.string() +
                               ": it is a block device (refused: writing would overwrite a disk)");
    throw std::runtime_error("cannot write " + target.string() + ": not a file, device, FIFO or socket");
  }
  if (errno != ENOENT) fail("write", target, errno);
  const fs::path file = follow_links(target);  // a new path, or a dangling link's target
  const fs::path parent = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(parent, ec))
    throw std::runtime_error("cannot write " + target.string() + ": folder " + parent.string() +
                             " does not exist");
  return OutputKind::file;
}

void write_output(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  const OutputKind kind = check_output_path(target);
  const fs::path file = kind == OutputKind::file ? follow_links(target) : fs::path();
  const fs::path temporary = kind == OutputKind::file ? temporary_name(file) : scratch_name(target);
  try {
    write(temporary);
    std::error_code ec;
    if (!fs::is_regular_file(temporary, ec)) throw std::runtime_error("cannot write " + shown(target));
    if (kind != OutputKind::file) {
      copy_into_stream(temporary, target, kind);
      fs::remove(temporary, ec);
      return;
    }
    // A file written again keeps its mode (an executable bit, a private 0600).
    const fs::file_status existing = fs::status(file, ec);
    if (!ec && fs::is_regular_file(existing)) fs::permissions(temporary, existing.permissions(), ec);
    fs::rename(temporary, file, ec);
    if (ec) fail("write", target, ec.value());
  } catch (...) {
    std::error_code ec;
    fs::remove(temporary, ec);
    rethrow_naming(temporary, target);
  }
}

void write_output_bytes(const fs::path& target, std::span<const std::uint8_t> bytes) {
  const OutputKind kind = check_output_path(target);
  if (kind != OutputKind::file) {  // no scratch copy: the bytes are already whole
    StreamFd out(target, kind);
    out.write(bytes);
    out.close();
    return;
  }
  write_output(target, [&](const fs::path& temporary) {
    OutputFile out(temporary, target);
    out.write(bytes);
    out.close();
  });
}

OutputFile::OutputFile(const fs::path& path, const fs::path& shown_as)
    : shown_(shown_as.empty() ? path : shown_as) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd_ < 0) fail("write", shown_, errno);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputFile::write(std::span<const std::uint8_t> bytes) { write_all(fd_, bytes, shown_); }

void OutputFile::close() {
  const int fd = fd_;
  fd_ = -1;
  if (fd >= 0 && ::close(fd) != 0 && errno != EINTR) fail("write", shown_, errno);
}

void throw_write_error(const fs::path& path) { fail("write", path, errno != 0 ? errno : EIO); }

std::vector<std::uint8_t> read_file_bytes(const fs::path& path, std::uintmax_t max_bytes) {
  const bool from_stdin = path == "-";
  const int fd = from_stdin ? ::dup(STDIN_FILENO) : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("read", from_stdin ? fs::path("stdin") : path, errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
    const int error = S_ISDIR(st.st_mode) ? EISDIR : errno;
    ::close(fd);
    fail("read", path, error);
  }
  // A regular file is read at its size; a pipe or device until its end, within the same limit.
  std::vector<std::uint8_t> bytes;
  if (S_ISREG(st.st_mode)) {
    if (std::uintmax_t(st.st_size) > max_bytes) {
      ::close(fd);
      throw std::runtime_error("cannot read " + path.string() + ": file too large");
    }
    bytes.reserve(std::size_t(st.st_size));
  }
  std::uint8_t buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      fail("read", path, error);
    }
    if (n == 0) break;
    if (bytes.size() + std::size_t(n) > max_bytes) {
      ::close(fd);
      throw std::runtime_error("cannot read " + path.string() + ": file too large");
    }
    bytes.insert(bytes.end(), buffer, buffer + n);
  }
  ::close(fd);
  return bytes;
}

}  // namespace pupwave::cli

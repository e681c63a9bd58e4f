#include "tools/atomic_file.h"

#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace pupwave::cli {
namespace fs = std::filesystem;

void check_output_path(const fs::path& target) {
  std::error_code ec;
  if (target.empty()) throw std::runtime_error("output path is empty");
  if (fs::is_directory(target, ec)) throw std::runtime_error("output " + target.string() + " is a directory");
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec))
    throw std::runtime_error("cannot write " + target.string() + ": folder " + parent.string() +
                             " does not exist");
}

// A unique hidden name beside the target, so the final rename stays on one file system.
static fs::path temporary_name(const fs::path& target) {
  std::random_device rd;
  const auto tag = std::to_string(rd()) + std::to_string(rd());
  fs::path tmp = target;
  tmp.replace_filename("." + target.filename().string() + ".tmp" + tag + target.extension().string());
  return tmp;
}

void write_atomically(const fs::path& target, const std::function<void(const fs::path&)>& write) {
  check_output_path(target);
  const fs::path tmp = temporary_name(target);
  try {
    write(tmp);
    if (!fs::exists(tmp)) throw std::runtime_error("cannot write " + target.string());
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void write_bytes_atomically(const fs::path& target, std::span<const std::uint8_t> bytes) {
  write_atomically(target, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write " + target.string() + ": cannot create file");
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error("cannot write " + target.string() + ": write failed");
  });
}

std::vector<std::uint8_t> read_file_bytes(const fs::path& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::runtime_error("cannot read " + path.string() + ": no such file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw std::runtime_error("cannot read " + path.string() + ": " + ec.message());
  if (size > max_bytes) throw std::runtime_error("cannot read " + path.string() + ": file too large");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string() + ": cannot open");
  std::vector<std::uint8_t> bytes(size);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (static_cast<std::uintmax_t>(in.gcount()) != size)
    throw std::runtime_error("cannot read " + path.string() + ": read failed");
  return bytes;
}

}  // namespace pupwave::cli

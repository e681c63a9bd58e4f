#include "tools/cli_stdio.h"

#include <chrono>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <random>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include "tools/bench/progress.h"

namespace pupwave::cli {
namespace fs = std::filesystem;
namespace {

// A fresh name in the temporary folder.
fs::path temporary_path(const std::string& extension) {
  std::random_device rd;
  return fs::temp_directory_path() / ("pupwave-" + std::to_string(rd()) + std::to_string(rd()) + extension);
}

// The file extension the first bytes of a file identify (readers choose the format by it).
std::string extension_for(const std::string& head) {
  auto starts = [&](const char* magic, std::size_t n) {
    return head.size() >= n && std::memcmp(head.data(), magic, n) == 0;
  };
  if (starts("PUPW", 4) || starts("PUPV", 4)) return ".pw";
  if (starts("PWMS", 4)) return ".pwm";
  if (starts(" BDV", 4)) return ".vdb";  // OpenVDB's magic, the int64 0x56444220 little endian
  if (starts("ply", 3)) return ".ply";
  if (starts("OFF", 3)) return ".off";
  if (starts("v ", 2) || starts("# ", 2) || starts("o ", 2) || starts("mtllib", 6)) return ".obj";
  if (starts("\x89PNG", 4)) return ".png";
  if (starts("\x76\x2f\x31\x01", 4)) return ".exr";
  if (starts("II*\0", 4) || starts("MM\0*", 4)) return ".tif";
  if (starts("\xff\xd8\xff", 3)) return ".jpg";
  if (head.size() >= 2 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6') return ".pnm";
  if (head.size() >= 2 && head[0] == 'P' && (head[1] == 'f' || head[1] == 'F')) return ".pfm";
  return ".raw";
}

}  // namespace

std::ostream& Verbosity::out() const {
  static std::ostream sink(nullptr);  // no buffer: every write is dropped
  return quiet ? sink : (to_stderr ? std::cerr : std::cout);
}

CLI::Validator existing_file_or_stdin() {
  return CLI::Validator(
      [](std::string& path) -> std::string {
        if (is_stdio(path)) return {};
        return CLI::ExistingFile(path);
      },
      "FILE or -");
}

void add_verbosity_flags(CLI::App& cmd, Verbosity& v) {
  auto* quiet = cmd.add_flag("--quiet,-q", v.quiet, "print nothing but errors and warnings");
  cmd.add_flag("--verbose,-v", v.verbose, "print more detail (transform, entropy coder, base step)")
      ->excludes(quiet);
}

void add_report_verbosity_flags(CLI::App& cmd) {
  auto v = std::make_shared<Verbosity>();
  add_verbosity_flags(cmd, *v);
  cmd.parse_complete_callback([v] {
    if (!v->quiet) return;
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null < 0) return;  // nowhere to send it: the report is printed
    ::dup2(null, STDOUT_FILENO);
    ::close(null);
  });
}

StdinFile::StdinFile() {
  std::string data{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  if (data.empty()) throw std::runtime_error("stdin is empty (input '-')");
  path_ = temporary_path(extension_for(data.substr(0, 8)));
  std::ofstream out(path_, std::ios::binary);
  out.write(data.data(), std::streamsize(data.size()));
  if (!out) throw std::runtime_error("cannot save stdin to " + path_.string());
}

StdinFile::~StdinFile() {
  std::error_code ec;
  fs::remove(path_, ec);
}

ElapsedLine::ElapsedLine(std::string label, bool enabled) : label_(std::move(label)) {
  if (enabled && bench::Progress::is_terminal(2)) thread_ = std::thread([this] { run(); });
}

ElapsedLine::~ElapsedLine() {
  {
    std::lock_guard lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void ElapsedLine::run() {
  const auto start = std::chrono::steady_clock::now();
  std::unique_lock lock(mutex_);
  // Quiet for the first second: short runs print nothing extra.
  if (wake_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; })) return;
  while (!done_) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "\r%s ... %s ", label_.c_str(), bench::format_duration(s).c_str());
    std::fflush(stderr);
    drawn_ = true;
    wake_.wait_for(lock, std::chrono::milliseconds(500), [this] { return done_; });
  }
  if (drawn_) std::fprintf(stderr, "\r\033[K");  // erase the line
}

}  // namespace pupwave::cli

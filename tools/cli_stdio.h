#pragma once
// Command-line conventions shared by compress and decompress (as cjxl, opj_compress and zfp):
// "-" as input or output means stdin or stdout, status lines then go to stderr; --quiet
// prints nothing but errors, --verbose adds detail; a long run shows an elapsed-time line on
// a terminal.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

namespace pupwave::cli {

// True for the "-" that names stdin or stdout.
inline bool is_stdio(const std::string& path) { return path == "-"; }

// Where status lines go and how many.
struct Verbosity {
  bool quiet = false;      // errors and warnings only
  bool verbose = false;    // a second line of detail
  bool to_stderr = false;  // stdout carries the data
  // The stream for status lines (null with --quiet).
  std::FILE* stream() const { return quiet ? nullptr : (to_stderr ? stderr : stdout); }
  // The same as an ostream: std::cout, std::cerr, or a sink that drops everything.
  std::ostream& out() const;
};

// An existing file, or "-" for stdin.
CLI::Validator existing_file_or_stdin();

// Adds --quiet and --verbose to a subcommand.
void add_verbosity_flags(CLI::App& cmd, Verbosity& v);

// The same for a command whose stdout is its report (info, psnr, filters, bench): --quiet
// points stdout at the null device once parsing ends, so the command still runs its checks and
// its exit status tells the result; --verbose is accepted and changes nothing.
void add_report_verbosity_flags(CLI::App& cmd);

// stdin saved to a temporary file (readers take paths), named with the extension its first
// bytes identify (.pw, .pwm, .vdb, .ply, .off, .png, .pnm, .pfm, .tif, .exr, .jpg, or .raw);
// removed on destruction.
class StdinFile {
 public:
  StdinFile();
  ~StdinFile();
  StdinFile(const StdinFile&) = delete;
  StdinFile& operator=(const StdinFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A command's input as a readable path: the file itself, or stdin saved to a temporary file
// ("-"), since readers take paths.
struct InputPath {
  std::optional<StdinFile> spooled;
  std::string path;
  explicit InputPath(const std::string& input) : path(input) {
    if (!is_stdio(input)) return;
    spooled.emplace();
    path = spooled->path().string();
  }
};

// An elapsed-time line on stderr while a long step runs, only when stderr is a terminal: it
// appears after about a second and is erased when the step ends (the library reports no
// finer progress for one image).
class ElapsedLine {
 public:
  ElapsedLine(std::string label, bool enabled);
  ~ElapsedLine();
  ElapsedLine(const ElapsedLine&) = delete;
  ElapsedLine& operator=(const ElapsedLine&) = delete;

 private:
  void run();
  std::string label_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  bool drawn_ = false;
  std::thread thread_;
};

}  // namespace pupwave::cli

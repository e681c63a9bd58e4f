#pragma once
// Runs external programs (our own CLI and the anchor codecs) as subprocesses, timed, without a
// shell, so the harness measures every codec the same way and stays decoupled from their APIs.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace pupwave::bench {

struct ProcessResult {
  int exit_code = -1;    // exit status; 128 + signal number when killed by a signal
  double seconds = 0.0;  // wall-clock time from spawn to exit
};

// Runs argv[0] (an absolute or relative path, not searched in PATH) with the given arguments,
// stdin from /dev/null and stdout + stderr appended to `log_file`. Throws std::runtime_error
// when the program cannot be started.
ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log_file);

// Finds an executable by name in a PATH-style list of directories (':'-separated); nullopt when
// no directory holds an executable file of that name.
std::optional<std::filesystem::path> find_tool(const std::string& name, const std::string& search_path);

// Runs a tool like run_process; a non-zero exit or a missing `product` file becomes a
// std::runtime_error quoting the tool's own message. Returns the wall time.
double run_checked(const std::vector<std::string>& argv, const std::filesystem::path& log_file,
                   const std::filesystem::path& product);

// The process's PATH (empty when unset).
std::string environment_path();

// The last `max_chars` characters of a log file as one line (whitespace runs collapsed), for
// error messages ("" when it cannot be read).
std::string log_tail(const std::filesystem::path& log_file, std::size_t max_chars = 400);

}  // namespace pupwave::bench

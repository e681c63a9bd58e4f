#pragma once
// Runs the CLI in a child process under a 1 GiB address-space limit (setrlimit RLIMIT_AS)
// and a wall-clock limit, so that a hostile stream demanding gigabytes or minutes fails the
// test instead of the machine. Not built with sanitizers (ASan reserves terabytes of address
// space and cannot run under RLIMIT_AS): see tests/CMakeLists.txt.

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace pupwave::testing {

inline constexpr rlim_t kAddressSpaceLimit = rlim_t(1) << 30;

struct ChildResult {
  int exit_code = -1;  // -1: killed (signal or wall-clock limit)
  bool timed_out = false;
  double seconds = 0.0;      // wall clock: follows the machine's load, so recorded, not asserted
  double cpu_seconds = 0.0;  // the child's user + system time (wait4's rusage): a bound on its work
  long max_rss_kb = 0;       // the child's peak resident memory (wait4's rusage)
  std::string output;        // stdout and stderr together
};

// Runs PUPWAVE_CLI with `args` under the address-space limit, killing it after `wall_seconds` (a
// hang guard only: a loaded 2-core CI machine stretches wall time several-fold).
inline ChildResult run_cli_bounded(const std::vector<std::string>& args, double wall_seconds = 60.0,
                                   rlim_t limit = kAddressSpaceLimit) {
  const auto log = std::filesystem::temp_directory_path() / ("pupwave_bounded_" + std::to_string(::getpid()));
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {
    const rlimit as{limit, limit};
    ::setrlimit(RLIMIT_AS, &as);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::setenv("MALLOC_ARENA_MAX", "2", 1);  // per-thread malloc arenas reserve 64 MiB of address space each
    std::vector<char*> argv{const_cast<char*>(PUPWAVE_CLI)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(PUPWAVE_CLI, argv.data());
    ::_exit(127);
  }
  ChildResult r;
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, WNOHANG, &usage) == 0) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > wall_seconds) {
      ::kill(pid, SIGKILL);
      ::wait4(pid, &status, 0, &usage);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!r.timed_out && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.max_rss_kb = usage.ru_maxrss;
  r.cpu_seconds = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                  1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  std::ifstream in(log);
  std::ostringstream text;
  text << in.rdbuf();
  r.output = text.str();
  std::filesystem::remove(log);
  return r;
}

}  // namespace pupwave::testing

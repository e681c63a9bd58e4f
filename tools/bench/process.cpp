#include "tools/bench/process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace pupwave::bench {
namespace {

// posix_spawn file actions that live as long as the spawn call.
class FileActions {
 public:
  FileActions() { posix_spawn_file_actions_init(&actions_); }
  ~FileActions() { posix_spawn_file_actions_destroy(&actions_); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;
  posix_spawn_file_actions_t* get() { return &actions_; }

 private:
  posix_spawn_file_actions_t actions_{};
};

int wait_for(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("waitpid failed: ") + std::strerror(errno));
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

ProcessResult run_process(const std::vector<std::string>& argv, const std::filesystem::path& log_file) {
  if (argv.empty()) throw std::invalid_argument("run_process: empty command");
  FileActions actions;
  posix_spawn_file_actions_addopen(actions.get(), 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(actions.get(), 1, log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(actions.get(), 1, 2);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0].c_str(), actions.get(), nullptr, args.data(), environ);
  if (rc != 0) throw std::runtime_error("cannot run " + argv[0] + ": " + std::strerror(rc));
  ProcessResult result;
  result.exit_code = wait_for(pid);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::optional<std::filesystem::path> find_tool(const std::string& name, const std::string& search_path) {
  std::istringstream dirs(search_path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return std::nullopt;
}

std::string environment_path() {
  const char* path = std::getenv("PATH");
  return path ? path : "";
}

std::string log_tail(const std::filesystem::path& log_file, std::size_t max_chars) {
  std::ifstream in(log_file, std::ios::binary);
  std::string text;
  // One line of text: runs of whitespace (newlines included) become one space.
  for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
    const bool space = std::isspace(static_cast<unsigned char>(*it)) != 0;
    if (!space)
      text += *it;
    else if (!text.empty() && text.back() != ' ')
      text += ' ';
  }
  if (!text.empty() && text.back() == ' ') text.pop_back();
  if (text.size() > max_chars) text = "..." + text.substr(text.size() - max_chars);
  return text;
}

double run_checked(const std::vector<std::string>& argv, const std::filesystem::path& log_file,
                   const std::filesystem::path& product) {
  const ProcessResult r = run_process(argv, log_file);
  std::error_code ec;
  if (r.exit_code != 0 || !std::filesystem::is_regular_file(product, ec)) {
    const std::string tail = log_tail(log_file);
    throw std::runtime_error(std::filesystem::path(argv[0]).filename().string() + " failed (exit " +
                             std::to_string(r.exit_code) + (tail.empty() ? ")" : "): " + tail));
  }
  return r.seconds;
}

}  // namespace pupwave::bench

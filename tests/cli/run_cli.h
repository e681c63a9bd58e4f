#pragma once
// Runs the `pupwave` binary from a test and captures what it printed and its exit code.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

namespace pupwave::test {

struct CliResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Quotes an argument for /bin/sh.
inline std::string shell_quote(const std::string& arg) {
  std::string q = "'";
  for (char c : arg) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs a shell command line (for pipes and redirections), capturing stdout only.
inline CliResult run_shell_output(const std::string& command) {
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) result.output.append(buf.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

// Runs PUPWAVE_CLI with the given arguments (no shell interpretation of the arguments).
inline CliResult run_cli(const std::vector<std::string>& args) {
  std::string command = shell_quote(PUPWAVE_CLI);
  for (const auto& a : args) command += " " + shell_quote(a);
  return run_shell_output(command + " 2>&1 </dev/null");
}

}  // namespace pupwave::test

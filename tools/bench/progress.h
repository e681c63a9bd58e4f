#pragma once
// Progress of a long run: a bar with ETA redrawn in place on a terminal, plain lines otherwise
// (logs, CI), safe to update from worker threads.

#include <chrono>
#include <cstddef>
#include <mutex>
#include <ostream>
#include <string>

namespace pupwave::bench {

class Progress {
 public:
  // `total` steps reported on `out`; `terminal` selects the redrawn bar (see is_terminal).
  Progress(std::ostream& out, std::size_t total, std::string label, bool terminal);

  // Marks one more step done; `what` names it (shown after the bar, or on its own line).
  void step(const std::string& what);

  // Prints a message without breaking the bar (it is redrawn below the message).
  void note(const std::string& message);

  // Ends the bar line on a terminal; idempotent.
  void finish();

  // True when file descriptor `fd` is an interactive terminal.
  static bool is_terminal(int fd);

 private:
  std::string status_line(const std::string& what) const;

  std::ostream& out_;
  std::size_t total_;
  std::size_t done_ = 0;
  std::string label_;
  bool terminal_;
  bool finished_ = false;
  std::string last_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
};

// "1m05s" style duration for ETA and elapsed time.
std::string format_duration(double seconds);

}  // namespace pupwave::bench

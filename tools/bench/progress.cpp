#include "tools/bench/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace pupwave::bench {

Progress::Progress(std::ostream& out, std::size_t total, std::string label, bool terminal)
    : out_(out),
      total_(total),
      label_(std::move(label)),
      terminal_(terminal),
      start_(std::chrono::steady_clock::now()) {}

bool Progress::is_terminal(int fd) { return isatty(fd) == 1; }

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

std::string Progress::status_line(const std::string& what) const {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double fraction = total_ ? static_cast<double>(done_) / static_cast<double>(total_) : 1.0;
  // ETA from the mean time per finished step, which is what a user can check against.
  const double eta = done_ ? elapsed / static_cast<double>(done_) * static_cast<double>(total_ - done_) : NAN;
  char head[160];
  std::snprintf(head, sizeof head, "%s %zu/%zu %3.0f%% elapsed %s ETA %s", label_.c_str(), done_, total_,
                fraction * 100.0, format_duration(elapsed).c_str(), format_duration(eta).c_str());
  if (!terminal_) return std::string(head) + "  " + what;
  constexpr int kWidth = 28;
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar = "[" + std::string(static_cast<std::size_t>(filled), '#') +
                    std::string(static_cast<std::size_t>(kWidth - filled), '.') + "] ";
  std::string line = bar + head + "  " + what;
  if (line.size() > 110) line.resize(110);  // keep it on one terminal row so \r redraws it
  return line;
}

void Progress::step(const std::string& what) {
  std::lock_guard lock(mutex_);
  if (done_ < total_) ++done_;
  last_ = status_line(what);
  if (terminal_)
    out_ << "\r\033[K" << last_ << std::flush;
  else
    out_ << last_ << '\n' << std::flush;
}

void Progress::note(const std::string& message) {
  std::lock_guard lock(mutex_);
  if (terminal_)
    out_ << "\r\033[K" << message << '\n' << last_ << std::flush;
  else
    out_ << message << '\n' << std::flush;
}

void Progress::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  if (terminal_ && !last_.empty()) out_ << '\n' << std::flush;
}

}  // namespace pupwave::bench

#include "tools/bench/size_search.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace pupwave::bench {

namespace fs = std::filesystem;

EncodeOutcome search_parameter(const EncodeRequest& q, const ParameterRange& range,
                               const TrialEncoder& encode,
                               const std::function<std::string(double)>& describe) {
  constexpr int kMaxTrials = 16;
  constexpr double kGoodEnough = 0.01;  // |log(bytes / target)|
  const double target =
      std::max(1.0, std::round(q.target_bpp * static_cast<double>(q.width * q.height) / 8.0));
  auto to_u = [&](double v) { return range.log_scale ? std::log(v) : v; };
  auto to_value = [&](double u) {
    const double v = range.log_scale ? std::exp(u) : u;
    return range.integer ? std::round(v) : v;
  };
  double lo = to_u(range.lo), hi = to_u(range.hi);
  const fs::path trial = q.output.string() + ".trial";
  EncodeOutcome best;
  double best_miss = INFINITY, best_value = 0.0;
  std::set<double> tried;
  for (int n = 0; n < kMaxTrials && best_miss > kGoodEnough; ++n) {
    // The first trial is the coarsest end: when even it is too big, there is nothing to search.
    const double u = n == 0 ? (range.larger_is_smaller ? hi : lo) : 0.5 * (lo + hi);
    const double value = to_value(u);
    if (!tried.insert(value).second) break;  // an integer range has collapsed
    const double seconds = encode(value, trial);
    const double bytes = static_cast<double>(fs::file_size(trial));
    const double miss = std::abs(std::log(bytes / target));
    if (miss < best_miss) {
      best_miss = miss, best_value = value;
      best.bytes = static_cast<std::uintmax_t>(bytes), best.seconds = seconds;
      fs::rename(trial, q.output);
    }
    if (n == 0 && bytes >= target) break;
    // Too big: move toward the smaller-file end; too small: toward the larger-file end.
    const bool toward_hi = (bytes > target) == range.larger_is_smaller;
    (toward_hi ? lo : hi) = to_u(value);
  }
  fs::remove(trial);
  best.setting = describe(best_value) + " (" + std::to_string(tried.size()) + " trials)";
  return best;
}

}  // namespace pupwave::bench

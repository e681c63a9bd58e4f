#include "transforms/analysis_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace pupwave {
namespace {

// The farthest coefficient a NaN at one sample in the middle of a line of n samples reaches.
std::size_t nan_reach(const Transform1D& t, std::size_t n) {
  const std::size_t half = coarse_size(n);
  std::size_t reach = 0;
  for (std::size_t position : {n / 2, n / 2 + 1}) {  // both parities
    std::vector<float> line(n, 0.0f);
    line[position] = std::numeric_limits<float>::quiet_NaN();
    t.analyze(std::span<float>(line));
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isnan(line[i])) continue;
      const std::size_t q = i < half ? 2 * i : 2 * (i - half) + 1;
      reach = std::max(reach, q > position ? q - position : position - q);
    }
  }
  return reach;
}

}  // namespace

std::size_t analysis_reach(const Transform1D& t) {
  constexpr std::size_t kMaxReach = 32;
  const std::size_t reach = nan_reach(t, 1024);
  return reach <= kMaxReach && nan_reach(t, 2048) == reach ? reach : 0;
}

}  // namespace pupwave

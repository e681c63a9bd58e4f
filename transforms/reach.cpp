#include "transforms/reach.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace pupwave {
namespace {

// The farthest coefficient a NaN at one sample in the middle of a line of n samples reaches.
std::size_t analysis_nan_reach(const Transform1D& t, std::size_t n) {
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

// The farthest output sample a NaN at one coarse or detail coefficient in the middle of a
// line of n samples reaches.
std::size_t synthesis_nan_reach(const Transform1D& t, std::size_t n) {
  const std::size_t j = n / 4;
  std::size_t reach = 0;
  for (std::size_t wire = 0; wire < 2; ++wire) {
    std::vector<float> line(n, 0.0f);
    line[wire == 0 ? j : n / 2 + j] = std::numeric_limits<float>::quiet_NaN();
    const std::size_t position = 2 * j + wire;  // coarse j sits at 2j, detail j at 2j + 1
    t.synthesize(std::span<float>(line));
    for (std::size_t i = 0; i < n; ++i)
      if (std::isnan(line[i])) reach = std::max(reach, i > position ? i - position : position - i);
  }
  return reach;
}

// Probed on two line lengths: a reach that grows with the line is not local.
std::size_t local_reach(const Transform1D& t, std::size_t (*probe)(const Transform1D&, std::size_t)) {
  constexpr std::size_t kMaxReach = 32;
  const std::size_t reach = probe(t, 1024);
  return reach <= kMaxReach && probe(t, 2048) == reach ? reach : 0;
}

}  // namespace

std::size_t analysis_reach(const Transform1D& t) { return local_reach(t, analysis_nan_reach); }

std::size_t synthesis_reach(const Transform1D& t) { return local_reach(t, synthesis_nan_reach); }

}  // namespace pupwave

#include "transforms/norms.h"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

#include "transforms/separable.h"

namespace pupwave {
namespace {

// L2 norm of the 1-D synthesis of a unit impulse at `position` of an n-sample line
// decomposed with `levels` levels.
double impulse_norm(const Transform1D& t, std::size_t n, int levels, std::size_t position) {
  std::vector<double> line(n, 0.0);
  line[position] = 1.0;
  inverse(t, line.data(), Extent{n, 1, 1}, levels);
  double sum = 0;
  for (double v : line) sum += v * v;
  return std::sqrt(sum);
}

// Per-axis norms indexed by level: low[l] for the level-l coarse band (low[0] = 1),
// high[l] for the level-l detail band (high[0] unused, 0 when the band is empty).
struct AxisNorms {
  std::vector<double> low, high;
};

AxisNorms axis_norms(const Transform1D& t, std::size_t n, int levels) {
  AxisNorms a{std::vector<double>(static_cast<std::size_t>(levels) + 1, 1.0),
              std::vector<double>(static_cast<std::size_t>(levels) + 1, 0.0)};
  for (int l = 1; l <= levels; ++l) {
    const std::size_t outer = level_extent({n, 1, 1}, l - 1)[0];
    const std::size_t inner = level_extent({n, 1, 1}, l)[0];
    const auto li = static_cast<std::size_t>(l);
    a.low[li] = impulse_norm(t, n, l, inner / 2);
    if (outer > inner) a.high[li] = impulse_norm(t, n, l, inner + (outer - inner) / 2);
  }
  return a;
}

std::vector<double> compute_norms(const Transform1D& t, const Extent& dims, int levels) {
  AxisNorms axes[3];
  for (std::size_t a = 0; a < 3; ++a) axes[a] = axis_norms(t, dims[a], levels);
  std::vector<double> norms;
  for (const Subband& b : subbands(dims, levels)) {
    double norm = 1;
    const auto l = static_cast<std::size_t>(b.level);
    for (std::size_t a = 0; a < 3; ++a) norm *= (b.orientation >> a) & 1u ? axes[a].high[l] : axes[a].low[l];
    norms.push_back(norm);
  }
  return norms;
}

using Key = std::tuple<std::string, Extent, int>;
// Bounded so that a stream of distinct hostile headers cannot grow memory without limit.
constexpr std::size_t kMaxCacheEntries = 4096;

}  // namespace

std::vector<double> synthesis_norms(const Transform1D& t, const Extent& dims, int levels) {
  for (std::size_t d : dims)
    if (d == 0) throw std::invalid_argument("synthesis_norms: array extent must be >= 1");
  if (levels < 0 || levels > kMaxLevels) throw std::invalid_argument("synthesis_norms: levels out of range");
  static std::mutex mutex;
  static std::map<Key, std::vector<double>> cache;
  Key key{t.spec(), dims, levels};
  {
    const std::lock_guard lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  auto norms = compute_norms(t, dims, levels);  // outside the lock: may take a while
  const std::lock_guard lock(mutex);
  if (cache.size() >= kMaxCacheEntries) cache.clear();
  cache.emplace(std::move(key), norms);
  return norms;
}

std::vector<double> synthesis_norms_1d(const Transform1D& t, std::size_t n, int levels) {
  return synthesis_norms(t, Extent{n, 1, 1}, levels);
}

}  // namespace pupwave

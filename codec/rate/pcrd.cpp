#include "codec/rate/pcrd.h"

#include <cmath>
#include <limits>

namespace pupwave {

std::vector<HullPoint> rd_hull(const EncodedBlock& block) {
  std::vector<HullPoint> hull;
  double removed = 0.0;
  for (int n = 1; n <= block.pass_count(); ++n) {
    removed += block.distortion_drop[std::size_t(n - 1)];
    HullPoint p{n, block.size(n), removed, 0.0};
    // Drop earlier points that lie on or below the chord to the new point.
    while (true) {
      const std::size_t prev_bytes = hull.empty() ? 0 : hull.back().bytes;
      const double prev_removed = hull.empty() ? 0.0 : hull.back().removed;
      if (p.removed <= prev_removed) break;  // no gain over the hull so far: not a hull point
      if (p.bytes <= prev_bytes) {           // gain for free: supersedes the previous point
        if (!hull.empty()) {
          hull.pop_back();
          continue;
        }
        p.slope = std::numeric_limits<double>::infinity();
        hull.push_back(p);
        break;
      }
      p.slope = (p.removed - prev_removed) / double(p.bytes - prev_bytes);
      if (!hull.empty() && p.slope >= hull.back().slope) {
        hull.pop_back();
        continue;
      }
      hull.push_back(p);
      break;
    }
  }
  return hull;
}

int passes_at_slope(const std::vector<HullPoint>& hull, double lambda) {
  int passes = 0;
  for (const HullPoint& p : hull) {
    if (p.slope < lambda) break;
    passes = p.passes;
  }
  return passes;
}

std::vector<int> passes_at_slope(const std::vector<std::vector<HullPoint>>& hulls, double lambda) {
  std::vector<int> passes(hulls.size());
  for (std::size_t i = 0; i < hulls.size(); ++i) passes[i] = passes_at_slope(hulls[i], lambda);
  return passes;
}

double bytes_at_slope(const std::vector<std::vector<HullPoint>>& hulls, double lambda) {
  double bytes = 0.0;
  for (const auto& hull : hulls) {
    std::size_t b = 0;
    for (const HullPoint& p : hull) {
      if (p.slope < lambda) break;
      b = p.bytes;
    }
    bytes += double(b);
  }
  return bytes;
}

double overflow_slope(const std::vector<std::vector<HullPoint>>& hulls, double budget, double floor) {
  if (!(bytes_at_slope(hulls, floor) > budget)) return floor;
  double lo = floor, hi = 0.0, least = std::numeric_limits<double>::infinity();
  for (const auto& hull : hulls)
    for (const HullPoint& p : hull)
      if (std::isfinite(p.slope)) {
        hi = std::max(hi, p.slope * 2.0);
        least = std::min(least, p.slope);
      }
  if (!(hi > 0.0)) return floor;  // only free points: they hold no bytes
  if (lo <= 0.0) lo = least;      // every point has slope >= least: the same bytes as at floor
  // Bisection on log lambda, keeping lo a threshold that is verified to overflow; the bound
  // only needs to be valid, so a coarse precision will do.
  for (int iter = 0; iter < 40 && hi / lo > 1.0 + 1e-4; ++iter) {
    const double mid = std::sqrt(lo * hi);
    (bytes_at_slope(hulls, mid) > budget ? lo : hi) = mid;
  }
  return lo;
}

std::size_t points_to_keep(const std::vector<HullPoint>& hull, double bound) {
  std::size_t n = 0;
  while (n < hull.size() && hull[n].slope >= bound) ++n;
  return std::min(hull.size(), n + 1);
}

}  // namespace pupwave

#pragma once
// Post-compression rate-distortion optimization (PCRD, Taubman's EBCOT): every code-block
// has a convex hull of (bytes, distortion removed) truncation points; one global slope
// threshold lambda picks in every block the last hull point whose slope is >= lambda,
// which minimizes the total distortion for the total size it gives.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "codec/entropy/block_encoder.h"

namespace pupwave {

// A truncation point on a block's convex hull.
struct HullPoint {
  int passes = 0;
  std::size_t bytes = 0;
  double removed = 0.0;  // cumulative distortion removed (index units squared)
  double slope = 0.0;    // removed / bytes gained from the previous hull point
};

// The hull of a block's truncation points (the empty truncation excluded), slopes strictly
// decreasing. Passes that add bytes without removing distortion never appear.
std::vector<HullPoint> rd_hull(const EncodedBlock& block);

// Passes to keep at threshold lambda: the last hull point with slope >= lambda (0 if none).
int passes_at_slope(const std::vector<HullPoint>& hull, double lambda);

// Per-block passes at one threshold.
std::vector<int> passes_at_slope(const std::vector<std::vector<HullPoint>>& hulls, double lambda);

// Bytes of all blocks cut at threshold lambda (the sizes of their passes_at_slope points).
double bytes_at_slope(const std::vector<std::vector<HullPoint>>& hulls, double lambda);

// A lower bound on PCRD's threshold for a byte budget, from the blocks coded so far: a
// threshold (at least `floor`, which must itself be a bound) at which these blocks alone
// hold more than `budget` bytes. Blocks coded later only add bytes, so no threshold at or
// below it fits the budget; returns `floor` when the blocks so far do not exceed it.
double overflow_slope(const std::vector<std::vector<HullPoint>>& hulls, double budget, double floor);

// Hull points a size-target PCRD can still use once its threshold is known to be above
// `bound`: those with slope >= bound, and the first one below (the next truncation point
// fill_budget may add). Cutting a hull to them changes no passes_at_slope result that fits
// the budget, and makes every one that does not still not fit.
std::size_t points_to_keep(const std::vector<HullPoint>& hull, double bound);

// The slope threshold where `accept(passes_at_slope(hulls, lambda))` changes, by bisection
// on log lambda. accept must be monotone in lambda: with `accept_high` (a size budget) it
// holds for large lambda and the smallest accepted lambda is returned (most bytes that fit);
// otherwise (a distortion target) it holds for small lambda and the largest accepted lambda
// is returned (fewest bytes that suffice). Falls back to the threshold of no passes / all
// passes (0) when nothing is accepted.
template <class Accept>
double slope_threshold(const std::vector<std::vector<HullPoint>>& hulls, bool accept_high, Accept&& accept) {
  double lo = 1e-12, hi = 1e12;  // lambda in index-units^2 per byte
  for (const auto& h : hulls)
    if (!h.empty() && std::isfinite(h.front().slope)) hi = std::max(hi, h.front().slope * 2.0);
  if (accept_high ? accept(passes_at_slope(hulls, 0.0)) : !accept(passes_at_slope(hulls, 0.0))) return 0.0;
  if (accept_high ? !accept(passes_at_slope(hulls, hi)) : accept(passes_at_slope(hulls, hi))) return hi;
  double best = accept_high ? hi : 0.0;
  for (int iter = 0; iter < 64 && hi / lo > 1.0 + 1e-7; ++iter) {
    const double mid = std::sqrt(lo * hi);
    const bool ok = accept(passes_at_slope(hulls, mid));
    if (ok) best = mid;
    if (ok == accept_high)
      hi = mid;
    else
      lo = mid;
  }
  return best;
}

// The per-block passes at slope_threshold(hulls, accept_high, accept).
template <class Accept>
std::vector<int> allocate_by_slope(const std::vector<std::vector<HullPoint>>& hulls, bool accept_high,
                                   Accept&& accept) {
  return passes_at_slope(hulls, slope_threshold(hulls, accept_high, accept));
}

}  // namespace pupwave

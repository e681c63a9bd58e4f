#include "transforms/kobbelt/subdivision.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "transforms/kobbelt/cyclic_reduction.h"

namespace pupwave::kobbelt {
namespace {

// Wrapped neighbours added on each side of a closed polygon. The periodic solution is the
// open one in the middle of the unrolled polygon, because the influence of the open ends
// decays geometrically (at most 1/3 per sample for uniform K3, the slowest scheme), so
// 64 neighbours put it far below double precision.
constexpr std::size_t kClosedPadding = 64;

// Odd samples of one refinement step: A p_odd = -B p_even (Eq. 7), solved by the CR network.
std::vector<double> odd_samples(const EulerLagrangeSystem& el, const CyclicReduction& cr,
                                std::span<const double> even) {
  std::vector<double> odd(el.a.size(), 0.0);
  unlift<double>(el.b, even, odd);  // predict odd: -B p_even
  cr.solve(std::span<double>(odd));
  return odd;
}

// One refinement step of an open polyline with per-edge parameter steps dt (uniform: null).
std::vector<Point2> refine_open_polyline(std::span<const Point2> p, std::span<const double> dt, Scheme scheme,
                                         bool uniform) {
  const std::size_t n = p.size(), fine = 2 * n - 1;
  EulerLagrangeSystem el;
  if (uniform) {
    el = euler_lagrange_system(scheme, fine);
  } else {
    std::vector<double> t(fine, 0.0);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      t[2 * i + 1] = t[2 * i] + 0.5 * dt[i];
      t[2 * i + 2] = t[2 * i] + dt[i];
    }
    el = euler_lagrange_system(scheme, t);
  }
  const CyclicReduction cr(el.a);
  std::vector<double> xs(n), ys(n);
  for (std::size_t i = 0; i < n; ++i) xs[i] = p[i].x, ys[i] = p[i].y;
  const std::vector<double> ox = odd_samples(el, cr, xs), oy = odd_samples(el, cr, ys);
  std::vector<Point2> out(fine);
  for (std::size_t i = 0; i < n; ++i) out[2 * i] = p[i];
  for (std::size_t i = 0; i + 1 < n; ++i) out[2 * i + 1] = {ox[i], oy[i]};
  return out;
}

// One refinement step of a closed polygon: unroll it with wrapped neighbours, refine as an
// open polyline, keep the middle period.
std::vector<Point2> refine_closed_polygon(std::span<const Point2> p, std::span<const double> dt,
                                          Scheme scheme, bool uniform) {
  const std::size_t n = p.size(), q = kClosedPadding, m = n + 2 * q + 1;
  std::vector<Point2> unrolled(m);
  std::vector<double> unrolled_dt(m - 1);
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = (k + n * (q / n + 1) - q) % n;  // index of the wrapped point
    unrolled[k] = p[i];
    if (k + 1 < m) unrolled_dt[k] = dt[i];
  }
  const std::vector<Point2> fine = refine_open_polyline(unrolled, unrolled_dt, scheme, uniform);
  return {fine.begin() + static_cast<std::ptrdiff_t>(2 * q),
          fine.begin() + static_cast<std::ptrdiff_t>(2 * q + 2 * n)};
}

std::vector<double> edge_parameters(std::span<const Point2> p, bool closed, bool uniform) {
  const std::size_t edges = closed ? p.size() : p.size() - 1;
  std::vector<double> dt(edges, 1.0);
  if (uniform) return dt;
  for (std::size_t i = 0; i < edges; ++i) {
    const Point2 a = p[i], b = p[(i + 1) % p.size()];
    dt[i] = std::sqrt(std::hypot(b.x - a.x, b.y - a.y));
    if (!(dt[i] > 0.0)) {
      throw std::invalid_argument("centripetal parameterization: points " + std::to_string(i) + " and " +
                                  std::to_string((i + 1) % p.size()) + " coincide");
    }
  }
  return dt;
}

void validate(std::span<const Point2> points, const SubdivisionOptions& o) {
  if (points.size() < 2) throw std::invalid_argument("subdivision needs at least 2 points");
  if (o.levels < 0 || o.levels > kMaxSubdivisionLevels) {
    throw std::invalid_argument("subdivision levels must be between 0 and " +
                                std::to_string(kMaxSubdivisionLevels));
  }
  for (const Point2& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
      throw std::invalid_argument("subdivision points must be finite");
    }
  }
  if (o.parameterization == Parameterization::centripetal && o.scheme != Scheme::k2 &&
      o.scheme != Scheme::k3) {
    throw std::invalid_argument("centripetal parameterization is implemented for k2 and k3 only");
  }
}

}  // namespace

std::vector<Point2> subdivide(std::span<const Point2> points, const SubdivisionOptions& o) {
  validate(points, o);
  const bool uniform = o.parameterization == Parameterization::uniform;
  std::vector<Point2> p(points.begin(), points.end());
  std::vector<double> dt = edge_parameters(p, o.closed, uniform);
  for (int level = 0; level < o.levels; ++level) {
    p = o.closed ? refine_closed_polygon(p, dt, o.scheme, uniform)
                 : refine_open_polyline(p, dt, o.scheme, uniform);
    std::vector<double> half(2 * dt.size());  // new parameters are edge midpoints
    for (std::size_t i = 0; i < dt.size(); ++i) half[2 * i] = half[2 * i + 1] = 0.5 * dt[i];
    dt = std::move(half);
  }
  return p;
}

std::vector<double> refine_open(Scheme scheme, std::span<const double> coarse) {
  if (coarse.empty()) return {};
  const EulerLagrangeSystem el = euler_lagrange_system(scheme, 2 * coarse.size() - 1);
  const std::vector<double> odd = odd_samples(el, CyclicReduction(el.a), coarse);
  std::vector<double> fine(2 * coarse.size() - 1);
  for (std::size_t i = 0; i < coarse.size(); ++i) fine[2 * i] = coarse[i];
  for (std::size_t i = 0; i < odd.size(); ++i) fine[2 * i + 1] = odd[i];
  return fine;
}

}  // namespace pupwave::kobbelt

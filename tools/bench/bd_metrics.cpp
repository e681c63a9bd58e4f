#include "tools/bench/bd_metrics.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace pupwave::bench {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A curve as (x, y) samples with the x range it covers.
struct Samples {
  std::vector<double> x, y;
  double lo = 0.0, hi = 0.0;
};

// Keeps the usable points; x = log10(bpp) and y = PSNR, or swapped for the rate metric.
Samples to_samples(const std::vector<RdPoint>& curve, bool psnr_as_x) {
  Samples s;
  for (const RdPoint& p : curve) {
    if (!(p.bpp > 0.0) || !std::isfinite(p.bpp) || !std::isfinite(p.psnr)) continue;
    const double lr = std::log10(p.bpp);
    s.x.push_back(psnr_as_x ? p.psnr : lr);
    s.y.push_back(psnr_as_x ? lr : p.psnr);
  }
  if (!s.x.empty()) {
    s.lo = *std::min_element(s.x.begin(), s.x.end());
    s.hi = *std::max_element(s.x.begin(), s.x.end());
  }
  return s;
}

// Least-squares polynomial coefficients (ascending powers) of degree min(3, n - 1).
// x is centred on `mid` to keep the Vandermonde system well conditioned.
Eigen::VectorXd fit(const Samples& s, double mid) {
  const auto n = static_cast<Eigen::Index>(s.x.size());
  const Eigen::Index degree = std::min<Eigen::Index>(3, n - 1);
  Eigen::MatrixXd v(n, degree + 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    double power = 1.0;
    for (Eigen::Index k = 0; k <= degree; ++k, power *= s.x[i] - mid) v(i, k) = power;
    y(i) = s.y[i];
  }
  return v.colPivHouseholderQr().solve(y);
}

// Integral of the centred polynomial over [lo, hi].
double integrate(const Eigen::VectorXd& c, double mid, double lo, double hi) {
  double sum = 0.0;
  for (Eigen::Index k = 0; k < c.size(); ++k) {
    const double e = static_cast<double>(k + 1);
    sum += c(k) / e * (std::pow(hi - mid, e) - std::pow(lo - mid, e));
  }
  return sum;
}

// Mean of (test fit - anchor fit) over the overlap of the two x ranges.
double mean_gap(const Samples& anchor, const Samples& test) {
  auto distinct = [](const Samples& s) { return s.x.size() >= 2 && s.hi > s.lo; };
  if (!distinct(anchor) || !distinct(test)) return kNaN;
  const double lo = std::max(anchor.lo, test.lo);
  const double hi = std::min(anchor.hi, test.hi);
  if (!(hi > lo)) return kNaN;
  const double mid = 0.5 * (lo + hi);
  const double area = integrate(fit(test, mid), mid, lo, hi) - integrate(fit(anchor, mid), mid, lo, hi);
  return area / (hi - lo);
}

}  // namespace

double bd_psnr(const std::vector<RdPoint>& anchor, const std::vector<RdPoint>& test) {
  return mean_gap(to_samples(anchor, false), to_samples(test, false));
}

double bd_rate(const std::vector<RdPoint>& anchor, const std::vector<RdPoint>& test) {
  const double gap = mean_gap(to_samples(anchor, true), to_samples(test, true));
  return std::isnan(gap) ? kNaN : (std::pow(10.0, gap) - 1.0) * 100.0;
}

}  // namespace pupwave::bench

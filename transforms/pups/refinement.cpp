#include "transforms/pups/refinement.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace pupwave::pups {

namespace {

// Uniform B-spline of degree n on the knots 0, 1, ..., n+1 (Cox-de Boor recursion).
double bspline(int n, double u) {
  if (u < 0 || u >= n + 1) return 0;
  std::vector<double> N(static_cast<std::size_t>(n) + 1, 0.0);
  const int span = static_cast<int>(std::floor(u));
  for (int i = 0; i <= n; ++i) N[static_cast<std::size_t>(i)] = (i == span) ? 1.0 : 0.0;
  for (int p = 1; p <= n; ++p)
    for (int i = 0; i + p <= n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      N[k] = ((u - i) * N[k] + (i + p + 1 - u) * N[k + 1]) / p;
    }
  return N[0];
}

// The bump of Eq. 33; exactly zero outside (-c, c).
double bump(double c, double sigma, double u) {
  if (std::abs(u) >= c) return 0;
  return std::exp(-sigma * u * u / (c * c - u * u));
}

// Normalized sinc sin(pi u) / (pi u).
double sinc(double u) {
  if (u == 0) return 1;
  const double x = std::numbers::pi * u;
  return std::sin(x) / x;
}

// Integer width of a support of real length `len` (zeros extend it to a multiple of d = 1).
int integer_width(double len) { return static_cast<int>(std::ceil(len - 1e-9)); }

void check_cinpact(const DesignParams& p) {
  if (!(p.c > 0) || p.c > 200) throw std::invalid_argument("CINPACT needs 0 < c <= 200");
  if (!(p.sigma >= 0) || !std::isfinite(p.sigma))
    throw std::invalid_argument("CINPACT needs a finite sigma >= 0");
}

}  // namespace

PlacedWeight make_weight(const DesignParams& p) {
  PlacedWeight pw;
  switch (p.weight) {
    case WeightKind::bspline: {
      if (p.degree < 0 || p.degree > 20) throw std::invalid_argument("B-spline degree must be in 0..20");
      pw.width = p.degree + 1;
      pw.first = -(pw.width / 2);
      const int n = p.degree, first = pw.first;
      pw.w = [n, first](double u) { return bspline(n, u - first); };
      break;
    }
    case WeightKind::polynomial: {
      if (p.coeffs.empty()) throw std::invalid_argument("polynomial needs coefficients");
      if (!(p.domain_hi > p.domain_lo) || p.domain_hi - p.domain_lo > 400)
        throw std::invalid_argument("polynomial domain [a,b] needs a < b (width <= 400)");
      pw.width = integer_width(p.domain_hi - p.domain_lo);
      pw.first = -(pw.width / 2);
      // Centre the domain in the extended support [first, first + W].
      const double delta = pw.first - (0.5 * (p.domain_lo + p.domain_hi) - 0.5 * pw.width);
      pw.w = [a = p.coeffs, lo = p.domain_lo, hi = p.domain_hi, delta](double u) {
        const double x = u - delta;
        if (x < lo || x > hi) return 0.0;
        double s = 0;
        for (auto it = a.rbegin(); it != a.rend(); ++it) s = s * x + *it;  // Horner
        return s;
      };
      break;
    }
    case WeightKind::cinpact: {
      check_cinpact(p);
      pw.width = integer_width(2 * p.c);
      pw.first = -(pw.width / 2);
      const double delta = pw.first + 0.5 * pw.width;  // centre of the extended support
      pw.w = [c = p.c, s = p.sigma, delta](double u) { return bump(c, s, u - delta); };
      break;
    }
    case WeightKind::cinpact_interp: {
      check_cinpact(p);
      // Interpolation needs the centre on an integer: extend symmetrically to [-ceil c, ceil c].
      const int half = integer_width(p.c);
      pw.width = 2 * half;
      pw.first = -half;
      pw.interpolating = true;
      pw.w = [c = p.c, s = p.sigma](double u) { return sinc(u) * bump(c, s, u); };
      break;
    }
    case WeightKind::given: throw std::invalid_argument("a design from given taps has no weight function");
  }
  return pw;
}

Refinement refine(const PlacedWeight& weight, int samples) {
  const int ncoef = weight.width + 1;
  // Columns that are free: all, or for interpolation only odd indices and the centre.
  std::vector<int> free;
  for (int i = weight.first; i <= weight.first + weight.width; ++i)
    if (!weight.interpolating || i == 0 || i % 2 != 0) free.push_back(i);
  if (samples <= static_cast<int>(free.size()) || samples > 50'000'000)
    throw std::invalid_argument("refinement needs more samples than coefficients (and <= 5e7)");
  Eigen::MatrixXd M(samples, static_cast<Eigen::Index>(free.size()));
  Eigen::VectorXd wbar(samples);
  const double lo = weight.first, step = static_cast<double>(weight.width) / (samples - 1);
  for (int s = 0; s < samples; ++s) {
    const double u = lo + s * step;  // uniform over the extended support, ends included
    wbar(s) = weight.w(u);
    for (std::size_t k = 0; k < free.size(); ++k)
      M(s, static_cast<Eigen::Index>(k)) = weight.w(2 * u - free[k]);
  }
  const Eigen::VectorXd c = M.householderQr().solve(wbar);
  const double wnorm = wbar.norm();
  if (!(wnorm > 0)) throw std::invalid_argument("weight function is zero on its support");
  Refinement r;
  r.first = weight.first;
  r.coeffs.assign(static_cast<std::size_t>(ncoef), 0.0);
  for (std::size_t k = 0; k < free.size(); ++k)
    r.coeffs[static_cast<std::size_t>(free[k] - weight.first)] = c(static_cast<Eigen::Index>(k));
  r.error = (wbar - M * c).norm() / wnorm;
  return r;
}

Refinement refine(const DesignParams& params) { return refine(make_weight(params), params.samples); }

double optimize_sigma(DesignParams params, double lo, double hi) {
  if (params.weight != WeightKind::cinpact && params.weight != WeightKind::cinpact_interp)
    throw std::invalid_argument("sigma optimization needs a CINPACT weight");
  if (!(lo > 0) || !(hi > lo)) throw std::invalid_argument("sigma range must be 0 < lo < hi");
  auto error_at = [&params](double sigma) {
    params.sigma = sigma;
    return refine(params).error;
  };
  // Coarse log-spaced scan (E(sigma) can have several local minima), then golden section
  // on the bracket around the best grid point.
  constexpr int kGrid = 48;
  const double ratio = std::pow(hi / lo, 1.0 / (kGrid - 1));
  int best = 0;
  double best_e = INFINITY;
  for (int g = 0; g < kGrid; ++g) {
    const double e = error_at(lo * std::pow(ratio, g));
    if (e < best_e) best_e = e, best = g;
  }
  double a = lo * std::pow(ratio, std::max(0, best - 1));
  double b = lo * std::pow(ratio, std::min(kGrid - 1, best + 1));
  const double phi = (std::sqrt(5.0) - 1) / 2;
  double x1 = b - phi * (b - a), x2 = a + phi * (b - a);
  double f1 = error_at(x1), f2 = error_at(x2);
  while (b - a > 1e-4 * (1 + a)) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - phi * (b - a), f1 = error_at(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + phi * (b - a), f2 = error_at(x2);
    }
  }
  return f1 < f2 ? x1 : x2;
}

}  // namespace pupwave::pups

#include "transforms/pups/mask_weight.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "transforms/pups/refinement.h"

namespace pupwave::pups {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

std::vector<double> convolve(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> out(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) out[i + j] += a[i] * b[j];
  return out;
}

// The refinable function of `mask` on [-h, h] by the cascade algorithm, at spacing 2^-levels.
std::vector<double> cascade(const std::vector<double>& mask, int levels) {
  std::vector<double> phi{1.0};
  for (int j = 0; j < levels; ++j) {
    std::vector<double> up(2 * phi.size() - 1, 0.0);
    for (std::size_t i = 0; i < phi.size(); ++i) up[2 * i] = phi[i];
    phi = convolve(up, mask);
    double m = 0;
    for (double v : phi) m = std::max(m, std::abs(v));
    if (!(m < 1e12)) throw std::invalid_argument("mask has no refinable function (the cascade diverges)");
  }
  return phi;
}

// Monomial coefficients a_0..a_degree of sum_k b_k T_2k(u / h) (Chebyshev on [-h, h]).
std::vector<double> to_monomial(const VectorXd& b, int degree, double h) {
  std::vector<std::vector<double>> T(static_cast<std::size_t>(degree) + 1,
                                     std::vector<double>(static_cast<std::size_t>(degree) + 1, 0.0));
  T[0][0] = 1;
  if (degree >= 1) T[1][1] = 1 / h;
  for (int m = 2; m <= degree; ++m)
    for (int j = 0; j <= degree; ++j) T[m][j] = -T[m - 2][j] + (j > 0 ? 2 / h * T[m - 1][j - 1] : 0.0);
  std::vector<double> a(static_cast<std::size_t>(degree) + 1, 0.0);
  for (Eigen::Index k = 0; k < b.size(); ++k)
    for (int j = 0; j <= degree; ++j)
      a[static_cast<std::size_t>(j)] += b(k) * T[static_cast<std::size_t>(2 * k)][j];
  return a;
}

DesignParams weight_params(const VectorXd& b, int degree, double h, int samples) {
  DesignParams p;
  p.weight = WeightKind::polynomial;
  p.coeffs = to_monomial(b, degree, h);
  p.domain_lo = -h;
  p.domain_hi = h;
  p.samples = samples;
  return p;
}

// Taps 0..h of the refinement, scaled to sum 2, minus the mask's (the right half: the weight
// is even, so the refinement is symmetric).
VectorXd residual(const VectorXd& b, const std::vector<double>& mask, int degree, int samples) {
  const int h = static_cast<int>(mask.size() / 2);
  const Refinement r = refine(weight_params(b, degree, h, samples));
  double sum = 0;
  for (double v : r.coeffs) sum += v;
  VectorXd out(h + 1);
  for (int i = 0; i <= h; ++i)
    out(i) = 2 * r.coeffs[static_cast<std::size_t>(h + i)] / sum - mask[static_cast<std::size_t>(h + i)];
  return out;
}

// Least-squares fit of the even Chebyshev series to the cascade samples.
VectorXd fit(const std::vector<double>& phi, int degree, double h, double* rel_error) {
  const auto n = static_cast<Eigen::Index>(phi.size());
  MatrixXd A(n, degree / 2 + 1);
  VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = -1 + 2.0 * static_cast<double>(i) / static_cast<double>(n - 1);
    y(i) = phi[static_cast<std::size_t>(i)];
    for (Eigen::Index k = 0; k < A.cols(); ++k)
      A(i, k) = std::cos(2.0 * static_cast<double>(k) * std::acos(x));
  }
  const VectorXd b = A.colPivHouseholderQr().solve(y);
  *rel_error = (A * b - y).norm() / y.norm();
  (void)h;
  return b / b.cwiseAbs().maxCoeff();
}

}  // namespace

std::vector<double> vanishing_moment_mask(int moments, double t) {
  if (moments < 2 || moments > 12 || moments % 2 != 0)
    throw std::invalid_argument("vanishing moments of a mask must be even, 2..12");
  if (!std::isfinite(t)) throw std::invalid_argument("mask parameter must be finite");
  std::vector<double> p{2.0};
  for (int k = 0; k < moments / 2; ++k) p = convolve(p, {0.25, 0.5, 0.25});  // cos(w/2)^2
  return convolve(p, {-0.25 * t, 1 + 0.5 * t, -0.25 * t});                   // 1 + t sin(w/2)^2
}

MaskWeight polynomial_weight_for_mask(const std::vector<double>& mask, int degree, int samples) {
  if (mask.size() < 3 || mask.size() % 2 == 0 || mask.size() > 41)
    throw std::invalid_argument("mask must have an odd number of taps, 3..41");
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (std::abs(mask[i] - mask[mask.size() - 1 - i]) > 1e-12)
      throw std::invalid_argument("mask must be symmetric");
  if (degree < 4 || degree > 24 || degree % 2 != 0) throw std::invalid_argument("degree must be even, 4..24");
  const int h = static_cast<int>(mask.size() / 2);
  MaskWeight out;
  VectorXd b = fit(cascade(mask, 10), degree, h, &out.fit_error);
  VectorXd r = residual(b, mask, degree, samples);
  for (int it = 0; it < 40 && r.cwiseAbs().maxCoeff() > 1e-12; ++it) {
    MatrixXd J(r.size(), b.size());
    for (Eigen::Index k = 0; k < b.size(); ++k) {
      VectorXd bk = b;
      const double step = 1e-7 * std::max(1.0, std::abs(b(k)));
      bk(k) += step;
      J.col(k) = (residual(bk, mask, degree, samples) - r) / step;
    }
    const VectorXd delta = J.completeOrthogonalDecomposition().solve(-r);  // minimum-norm step
    double scale = 1;
    for (; scale > 1e-4; scale /= 2) {  // damped: accept the first step that reduces |r|
      const VectorXd rn = residual(b + scale * delta, mask, degree, samples);
      if (rn.norm() < r.norm()) {
        b += scale * delta;
        r = rn;
        break;
      }
    }
    if (scale <= 1e-4) break;
  }
  out.max_tap_error = r.cwiseAbs().maxCoeff();
  if (!(out.max_tap_error <= 1e-11))
    throw std::invalid_argument("no polynomial weight of this degree refines to the mask (residual " +
                                std::to_string(out.max_tap_error) + ")");
  out.params = weight_params(b, degree, h, samples);
  return out;
}

}  // namespace pupwave::pups

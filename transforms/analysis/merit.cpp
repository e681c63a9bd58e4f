// The finite-operator side of the figures of merit: the explicit n x n matrices of the
// multi-level analysis and synthesis (boundaries included), coding gain per coefficient,
// condition numbers and the coarse band's gain per level.
#include "transforms/analysis/merit.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include <span>
#include "transforms/separable.h"

namespace pupwave::merit {

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// The separable engine's Mallat recursion on one line (level l transforms the first
// level_extent(n, l-1) samples), without its per-call set-up: these loops run n times.
void analyze_levels(const Transform1D& t, std::vector<double>& x, int levels) {
  std::size_t m = x.size();
  for (int l = 0; l < levels && m > 1; ++l, m = coarse_size(m)) t.analyze(std::span<double>(x.data(), m));
}

void synthesize_levels(const Transform1D& t, std::vector<double>& x, int levels) {
  std::vector<std::size_t> sizes;
  for (std::size_t m = x.size(); static_cast<int>(sizes.size()) < levels && m > 1; m = coarse_size(m))
    sizes.push_back(m);
  for (auto it = sizes.rbegin(); it != sizes.rend(); ++it) t.synthesize(std::span<double>(x.data(), *it));
}

// Columns = transforms of unit impulses: the levels-level analysis (or synthesis) operator.
MatrixXd operator_matrix(const Transform1D& t, std::size_t n, int levels, bool analysis) {
  const auto m = static_cast<Eigen::Index>(n);
  MatrixXd out(m, m);
  std::vector<double> col(n);
  for (Eigen::Index j = 0; j < m; ++j) {
    std::fill(col.begin(), col.end(), 0.0);
    col[static_cast<std::size_t>(j)] = 1.0;
    if (analysis)
      analyze_levels(t, col, levels);
    else
      synthesize_levels(t, col, levels);
    out.col(j) = Eigen::Map<const VectorXd>(col.data(), m);
  }
  return out;
}

// R v for the AR(1) covariance R_ij = rho^|i-j| in O(n): a forward and a backward recursion.
VectorXd ar1_apply(const VectorXd& v, double rho) {
  const Eigen::Index n = v.size();
  VectorXd f(n), b(n);
  for (Eigen::Index i = 0; i < n; ++i) f(i) = v(i) + (i ? rho * f(i - 1) : 0.0);
  for (Eigen::Index i = n - 1; i >= 0; --i) b(i) = v(i) + (i + 1 < n ? rho * b(i + 1) : 0.0);
  return f + b - v;
}

// AR(1) variance of every coefficient: diag(T R T^T).
VectorXd coefficient_variances(const MatrixXd& T, double rho) {
  VectorXd var(T.rows());
  for (Eigen::Index k = 0; k < T.rows(); ++k) {
    const VectorXd row = T.row(k).transpose();
    var(k) = row.dot(ar1_apply(row, rho));
  }
  return var;
}

// sigma_max / sigma_min from the eigenvalues of T^T T (half the work of an SVD; exact enough
// for condition numbers below about 1e7, far beyond any bank here).
double condition_number(const MatrixXd& T) {
  const MatrixXd gram = T.transpose() * T;
  const VectorXd ev = Eigen::SelfAdjointEigenSolver<MatrixXd>(gram, Eigen::EigenvaluesOnly).eigenvalues();
  return std::sqrt(ev.maxCoeff() / ev.minCoeff());
}

void check(const MeritOptions& o) {
  if (o.levels < 1 || o.levels > 12) throw std::invalid_argument("figures of merit: levels must be 1..12");
  if (o.n < (std::size_t(1) << o.levels) || o.n > 4096)
    throw std::invalid_argument("figures of merit: n must be in [2^levels, 4096]");
  if (!(o.rho > -1 && o.rho < 1)) throw std::invalid_argument("figures of merit: rho must be in (-1, 1)");
}

// Worst-case gain and AR(1) RMS of the coarse band after each level. The coarse rows of the
// j-level operator are the one-level coarse rows (on the level-(j-1) coarse length) times
// those of level j-1, so the matrices shrink by half per level.
void coarse_gains(const Transform1D& t, const MeritOptions& o, Merit& m) {
  MatrixXd C = MatrixXd::Identity(static_cast<Eigen::Index>(o.n), static_cast<Eigen::Index>(o.n));
  for (int j = 1; j <= o.levels; ++j) {
    const auto len = static_cast<std::size_t>(C.rows());
    const MatrixXd T = operator_matrix(t, len, 1, true);
    C = (T.topRows(static_cast<Eigen::Index>(coarse_size(len))) * C).eval();
    const MatrixXd gram = C * C.transpose();
    const VectorXd ev = Eigen::SelfAdjointEigenSolver<MatrixXd>(gram, Eigen::EigenvaluesOnly).eigenvalues();
    m.coarse_gain.push_back(std::sqrt(ev.maxCoeff()));
    m.coarse_rms.push_back(std::sqrt(coefficient_variances(C, o.rho).mean()));
  }
}

std::string fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string general(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// The figures that explain a loss, worst first; empty when none is out of range.
std::string diagnosis(const Merit& m) {
  std::string out;
  auto add = [&out](const std::string& s) { out += (out.empty() ? "" : "; ") + s; };
  if (m.dc_leak > kMaxDcLeak)
    add("details carry " + fixed(100 * m.dc_leak, 2) + "% of the local mean (no vanishing moment)");
  if (!m.coarse_gain.empty() && m.coarse_gain.back() > kMaxCoarseGain)
    add("coarse band gain " + fixed(m.coarse_gain.front(), 2) + " at level 1, " +
        general(m.coarse_gain.back()) + " at level " + std::to_string(m.coarse_gain.size()));
  if (m.norm_product > kMaxNormProduct)
    add("analysis and synthesis functions differ: |h||g| up to " + fixed(m.norm_product, 2) +
        " (orthogonal: 1)");
  if (m.condition > kMaxConditionNumber)
    add("multi-level condition number " + general(m.condition) + " (one level " +
        general(m.condition_one_level) + ")");
  return out;
}

}  // namespace

// High-rate theory with one quantizer step per coefficient: D = c 2^(-2R) prod_k
// (sigma_k^2 |s_k|^2)^(1/n) against c sigma_x^2 2^(-2R) for PCM (sigma_x = 1).
double finite_coding_gain_db(const MatrixXd& T, const MatrixXd& S, double rho) {
  if (T.rows() != T.cols() || S.rows() != T.rows() || S.cols() != T.cols() || T.rows() == 0)
    throw std::invalid_argument("coding gain: T and S must be square and of equal size");
  const VectorXd var = coefficient_variances(T, rho);
  double log_sum = 0;
  for (Eigen::Index k = 0; k < T.rows(); ++k) log_sum += std::log10(var(k) * S.col(k).squaredNorm());
  return -10.0 * log_sum / static_cast<double>(T.rows());
}

CodingVerdict coding_verdict(const Merit& m) {
  CodingVerdict v;
  v.coding = m.coding_gain_db >= kMinCodingGainDb;
  const std::string why = diagnosis(m);
  if (v.coding)
    v.reason = why;
  else
    v.reason = "coding gain " + fixed(m.coding_gain_db, 2) + " dB < " + fixed(kMinCodingGainDb, 1) + " dB" +
               (why.empty() ? "" : ": " + why);
  return v;
}

double coding_gain_db(const Transform1D& t, const MeritOptions& o) {
  check(o);
  return finite_coding_gain_db(operator_matrix(t, o.n, o.levels, true),
                               operator_matrix(t, o.n, o.levels, false), o.rho);
}

Merit figures_of_merit(const Transform1D& t, const MeritOptions& o) {
  check(o);
  Merit m;
  const MatrixXd T = operator_matrix(t, o.n, o.levels, true);
  m.coding_gain_db = finite_coding_gain_db(T, operator_matrix(t, o.n, o.levels, false), o.rho);
  if (o.condition) {
    m.condition = condition_number(T);
    // One level is nearly independent of the length; a shorter line keeps the SVD cheap.
    m.condition_one_level = condition_number(operator_matrix(t, std::min<std::size_t>(o.n, 128), 1, true));
  }
  coarse_gains(t, o, m);
  try {
    const InteriorFilters f = interior_filters(t);
    m.interior_coding_gain_db = interior_coding_gain_db(f, o.levels, o.rho);
    constexpr double kMomentTol = 1e-8;  // relative; exact designs reach about 1e-15
    m.analysis_moments = vanishing_moments(f.h1, kMomentTol, &m.analysis_residual);
    m.synthesis_moments = vanishing_moments(f.g1, kMomentTol, &m.synthesis_residual);
    double s0 = 0, s1 = 0;
    for (double c : f.h0.c) s0 += c;
    for (double c : f.h1.c) s1 += c;
    m.dc_leak = std::abs(s1) / std::abs(s0);
    const std::vector<double> products = norm_products(f, o.levels);
    m.norm_product = *std::max_element(products.begin(), products.end());
  } catch (const std::invalid_argument&) {
    // Filters longer than the probe line: the interior figures are unknown, not zero.
    m.interior_coding_gain_db = m.dc_leak = m.norm_product = std::nan("");
    m.analysis_moments = m.synthesis_moments = -1;
  }
  return m;
}

}  // namespace pupwave::merit

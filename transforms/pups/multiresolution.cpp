#include "transforms/pups/multiresolution.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace pupwave::pups {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// The systems of Eq. 41 for a padded P of K taps (K0 before the extension by l zeros):
// hard rows sum_t b[t] q[t + 2s] (s in hard_lo..), soft rows sum_t p[t] q[t + 2s].
struct ConstraintSystem {
  MatrixXd C, M;
  int hard_lo = 0;  // shift s of the first hard row
};

// B from P (Eq. 35 and 58): b[t] = -p[K-1-t] for even t, +p[K-1-t] for odd t (0-based).
std::vector<double> b_from_p(const std::vector<double>& p) {
  const std::size_t K = p.size();
  std::vector<double> b(K);
  for (std::size_t t = 0; t < K; ++t) b[t] = (t % 2 == 0 ? -1.0 : 1.0) * p[K - 1 - t];
  return b;
}

// A from Q (Eq. 44): a[t] = q[K-1-t] for even t, -q[K-1-t] for odd t (0-based).
std::vector<double> a_from_q(const std::vector<double>& q) {
  const std::size_t K = q.size();
  std::vector<double> a(K);
  for (std::size_t t = 0; t < K; ++t) a[t] = (t % 2 == 0 ? 1.0 : -1.0) * q[K - 1 - t];
  return a;
}

// P padded to even length K0 and then by l zeros (Eq. 57).
std::vector<double> pad(const std::vector<double>& p, int l) {
  std::vector<double> out = p;
  if (out.size() % 2 != 0) out.push_back(0.0);
  out.resize(out.size() + static_cast<std::size_t>(l), 0.0);
  return out;
}

ConstraintSystem build_system(const std::vector<double>& pp, int l) {
  const int K = static_cast<int>(pp.size()), K0 = K - l;
  const std::vector<double> b = b_from_p(pp);
  ConstraintSystem sys;
  // Hard rows: b is structurally non-zero on t in [l, K-1]; soft rows: p on [0, K0-1].
  sys.hard_lo = -(K - 2) / 2;
  const int hard_hi = (K - 2 - l) / 2, soft_lo = -(K0 - 2) / 2, soft_hi = (K - 2) / 2;
  sys.C = MatrixXd::Zero(hard_hi - sys.hard_lo + 1, K);
  sys.M = MatrixXd::Zero(soft_hi - soft_lo + 1, K);
  for (int s = sys.hard_lo; s <= hard_hi; ++s)
    for (int t = l; t < K; ++t)
      if (t + 2 * s >= 0 && t + 2 * s < K)
        sys.C(s - sys.hard_lo, t + 2 * s) += b[static_cast<std::size_t>(t)];
  for (int s = soft_lo; s <= soft_hi; ++s)
    for (int t = 0; t < K0; ++t)
      if (t + 2 * s >= 0 && t + 2 * s < K) sys.M(s - soft_lo, t + 2 * s) += pp[static_cast<std::size_t>(t)];
  return sys;
}

// Drops exactly-zero taps at both ends (structural zeros of the padding), moving the offset.
Filter trimmed(std::vector<double> taps, int offset) {
  std::size_t lo = 0, hi = taps.size();
  while (hi > lo + 1 && taps[hi - 1] == 0.0) --hi;
  while (lo + 1 < hi && taps[lo] == 0.0) ++lo;
  return {std::vector<double>(taps.begin() + static_cast<std::ptrdiff_t>(lo),
                              taps.begin() + static_cast<std::ptrdiff_t>(hi)),
          offset + static_cast<int>(lo)};
}

void check_p(const std::vector<double>& p) {
  if (p.size() < 2 || p.size() > 1024) throw std::invalid_argument("P needs 2..1024 taps");
  for (double v : p)
    if (!std::isfinite(v)) throw std::invalid_argument("P taps must be finite");
}

}  // namespace

std::vector<QDesign> design_q_all_shifts(const std::vector<double>& p, int l) {
  check_p(p);
  if (l < 0 || l % 2 != 0 || l > 256) throw std::invalid_argument("extension l must be even, 0..256");
  const std::vector<double> pp = pad(p, l);
  const ConstraintSystem sys = build_system(pp, l);
  const Index h = sys.C.rows(), K = sys.C.cols();
  // Null-space method for min ||M q|| subject to C q = e_s: C^T Pi = Qc R gives
  // q = Qc1 y + Qc2 z with R^T y = Pi^T e_s, then z solves a plain least-squares problem.
  const Eigen::ColPivHouseholderQR<MatrixXd> qr(sys.C.transpose());
  if (qr.rank() < h) return {};
  const MatrixXd Qc = qr.householderQ() * MatrixXd::Identity(K, K);
  const MatrixXd R = qr.matrixR().topLeftCorner(h, h).triangularView<Eigen::Upper>();
  const MatrixXd Qc1 = Qc.leftCols(h), Qc2 = Qc.rightCols(K - h);
  const MatrixXd MQ2 = sys.M * Qc2;
  const Eigen::CompleteOrthogonalDecomposition<MatrixXd> ls(MQ2);
  std::vector<QDesign> out;
  for (Index row = 0; row < h; ++row) {
    VectorXd e = VectorXd::Zero(h);
    e(row) = 1.0;
    const VectorXd pe = qr.colsPermutation().transpose() * e;
    const VectorXd y = R.transpose().triangularView<Eigen::Lower>().solve(pe);
    const VectorXd q0 = Qc1 * y;
    VectorXd q = q0;
    if (K > h) q -= Qc2 * ls.solve(sys.M * q0);
    QDesign d;
    d.q.assign(q.data(), q.data() + q.size());
    d.error = (sys.M * q).norm();
    d.shift = sys.hard_lo + static_cast<int>(row);
    out.push_back(std::move(d));
  }
  return out;
}

FilterBank design_bank(const std::vector<double>& p, int p_offset, const ExtensionRule& rule) {
  check_p(p);
  if (rule.extension && (*rule.extension < 0 || *rule.extension % 2 != 0))
    throw std::invalid_argument("extension l must be even and >= 0");
  if (!rule.extension && !(rule.threshold > 0))
    throw std::invalid_argument("extension search needs a threshold > 0");
  int l = rule.extension.value_or(0);
  for (;; l += 2) {
    const auto designs = design_q_all_shifts(p, l);
    if (designs.empty()) throw std::invalid_argument("no admissible shift: B Q = I is singular");
    // Smallest orthogonality error; of mirror-image near-ties the first in shift order wins,
    // as in the loop of Algorithm 5.1 (this gives the E_{-1} filter printed in Section 5.4).
    const QDesign* best = &designs.front();
    for (const auto& d : designs)
      if (d.error < best->error - 1e-12 * std::max(1.0, best->error)) best = &d;
    const bool last =
        rule.extension.has_value() || best->error <= rule.threshold || l + 2 > rule.max_extension;
    if (!last) continue;
    FilterBank bank;
    bank.design.weight = WeightKind::given;
    bank.design.coeffs = p;
    bank.design.extension = l;
    bank.P = {p, p_offset};
    bank.Q = trimmed(best->q, p_offset);
    bank.B = trimmed(b_from_p(pad(p, l)), p_offset + 2 * best->shift);
    bank.A = trimmed(a_from_q(best->q), p_offset + 2 * best->shift);
    bank.orthogonality_error = best->error;
    bank.shift = best->shift;
    return bank;
  }
}

namespace {

// Dense circulant matrix of an analysis filter (rows = n coarse, cols = 2n fine) or, with
// transpose_layout, of a synthesis filter (rows = 2n fine, cols = n coarse).
MatrixXd circulant(const Filter& f, int n, bool synthesis) {
  const int m = 2 * n;
  MatrixXd out = synthesis ? MatrixXd::Zero(m, n) : MatrixXd::Zero(n, m);
  for (int j = 0; j < n; ++j)
    for (std::size_t t = 0; t < f.taps.size(); ++t) {
      const int x = (((2 * j + f.offset + static_cast<int>(t)) % m) + m) % m;
      (synthesis ? out(x, j) : out(j, x)) += f.taps[t];
    }
  return out;
}

}  // namespace

int min_circulant_size(const FilterBank& bank) {
  std::size_t span = 0;
  for (const Filter* f : {&bank.P, &bank.Q, &bank.A, &bank.B}) span = std::max(span, f->taps.size());
  return static_cast<int>((span + 1) / 2);
}

double circulant_identity_error(const FilterBank& bank, int n) {
  if (n < min_circulant_size(bank)) throw std::invalid_argument("circulant size too small for the filters");
  const MatrixXd A = circulant(bank.A, n, false), B = circulant(bank.B, n, false);
  const MatrixXd P = circulant(bank.P, n, true), Q = circulant(bank.Q, n, true);
  const MatrixXd I = MatrixXd::Identity(n, n);
  double err = (A * P - I).cwiseAbs().maxCoeff();
  err = std::max(err, (B * Q - I).cwiseAbs().maxCoeff());
  err = std::max(err, (A * Q).cwiseAbs().maxCoeff());
  return std::max(err, (B * P).cwiseAbs().maxCoeff());
}

}  // namespace pupwave::pups

#include "transforms/sqrt3/boundary_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "transforms/sqrt3/local_lsq.h"

namespace pupwave::sqrt3 {
namespace {

// Loops at least this long use the infinite curve's stencils (no filter wraps onto itself).
constexpr std::size_t kStencilLoop = 10;
// The loop the stencils are read from, and the displaced point they are read at.
constexpr std::size_t kReferenceLoop = 12;
constexpr std::ptrdiff_t kReferencePoint = 4;

constexpr std::array<double, 9> kMask = {1, 4, 10, 16, 19, 16, 10, 4, 1};  // / 27, Fig. 17

std::size_t wrap(std::ptrdiff_t i, std::size_t n) {
  const std::ptrdiff_t r = i % std::ptrdiff_t(n);
  return std::size_t(r < 0 ? r + std::ptrdiff_t(n) : r);
}

// Distinct fine indices home - w .. home + w on a loop of n fine points.
std::vector<std::size_t> window(std::ptrdiff_t home, int lo, int hi, std::size_t n) {
  std::vector<std::size_t> rows;
  for (int o = lo; o <= hi; ++o) {
    const std::size_t r = wrap(home + o, n);
    if (std::find(rows.begin(), rows.end(), r) == rows.end()) rows.push_back(r);
  }
  return rows;
}

// Columns of M with a non-zero in any of `rows`.
std::vector<std::size_t> touching_columns(const Eigen::MatrixXd& M, const std::vector<std::size_t>& rows) {
  std::vector<std::size_t> cols;
  for (Eigen::Index c = 0; c < M.cols(); ++c) {
    for (std::size_t r : rows) {
      if (M(Eigen::Index(r), c) != 0.0) {
        cols.push_back(std::size_t(c));
        break;
      }
    }
  }
  return cols;
}

Eigen::MatrixXd submatrix(const Eigen::MatrixXd& M, const std::vector<std::size_t>& rows,
                          const std::vector<std::size_t>& cols) {
  Eigen::MatrixXd S(rows.size(), cols.size());
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (std::size_t j = 0; j < cols.size(); ++j)
      S(Eigen::Index(i), Eigen::Index(j)) = M(Eigen::Index(rows[i]), Eigen::Index(cols[j]));
  return S;
}

Eigen::RowVectorXd unit_at(const std::vector<std::size_t>& cols, std::size_t home) {
  Eigen::RowVectorXd u = Eigen::RowVectorXd::Zero(Eigen::Index(cols.size()));
  for (std::size_t j = 0; j < cols.size(); ++j)
    if (cols[j] == home) u(Eigen::Index(j)) = 1.0;
  return u;
}

std::size_t introduced_fine(std::size_t detail) { return 3 * (detail / 2) + 1 + detail % 2; }

Eigen::MatrixXd curve_p(std::size_t m) {
  const std::size_t n = 3 * m;
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(m));
  for (std::size_t c = 0; c < m; ++c)
    for (int o = -4; o <= 4; ++o)
      P(Eigen::Index(wrap(std::ptrdiff_t(3 * c) + o, n)), Eigen::Index(c)) +=
          kMask[std::size_t(o + 4)] / 27.0;
  return P;
}

// A rows of width 4: minimum-norm a with a P_S = u (Eq. 5.2 applied to the curve).
bool build_a(DenseCurveFilters& f, std::size_t m) {
  const std::size_t n = 3 * m;
  f.A = Eigen::MatrixXd::Zero(Eigen::Index(m), Eigen::Index(n));
  for (std::size_t k = 0; k < m; ++k) {
    const std::vector<std::size_t> rows = window(std::ptrdiff_t(3 * k), -4, 4, n);
    const std::vector<std::size_t> cols = touching_columns(f.P, rows);
    double residual = 0;
    const Eigen::RowVectorXd a = min_norm_row(submatrix(f.P, rows, cols), unit_at(cols, k), &residual);
    if (residual > 1e-12) return false;
    for (std::size_t j = 0; j < rows.size(); ++j)
      f.A(Eigen::Index(k), Eigen::Index(rows[j])) = a(Eigen::Index(j));
  }
  return true;
}

// Q columns of width 2: the null space of the A rows they meet, 1 on the home node (Sec. 6).
bool build_q(DenseCurveFilters& f, std::size_t m) {
  const std::size_t n = 3 * m;
  f.Q = Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(2 * m));
  const Eigen::MatrixXd At = f.A.transpose();
  for (std::size_t d = 0; d < 2 * m; ++d) {
    const std::size_t home = introduced_fine(d);
    const std::vector<std::size_t> rows = window(std::ptrdiff_t(home), -2, 2, n);
    const std::vector<std::size_t> arows = touching_columns(At, rows);
    const Eigen::MatrixXd ns = null_space(submatrix(At, rows, arows).transpose());
    if (ns.cols() != 1) return false;
    const std::size_t h = std::size_t(std::find(rows.begin(), rows.end(), home) - rows.begin());
    if (std::abs(ns(Eigen::Index(h), 0)) < 1e-12) return false;
    for (std::size_t j = 0; j < rows.size(); ++j)
      f.Q(Eigen::Index(rows[j]), Eigen::Index(d)) = ns(Eigen::Index(j), 0) / ns(Eigen::Index(h), 0);
  }
  return true;
}

// T rows, widened until T Q_S = u is consistent (Sec. 7), then B = T (I - P A) (Eq. 7.1).
bool build_b(DenseCurveFilters& f, std::size_t m) {
  const std::size_t n = 3 * m;
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(Eigen::Index(2 * m), Eigen::Index(n));
  for (std::size_t d = 0; d < 2 * m; ++d) {
    bool found = false;
    for (int w = 0; w <= 6 && !found; ++w) {
      const std::vector<std::size_t> rows = window(std::ptrdiff_t(introduced_fine(d)), -w, w, n);
      const std::vector<std::size_t> cols = touching_columns(f.Q, rows);
      double residual = 0;
      const Eigen::RowVectorXd t = min_norm_row(submatrix(f.Q, rows, cols), unit_at(cols, d), &residual);
      if (residual > 1e-10) continue;
      for (std::size_t j = 0; j < rows.size(); ++j)
        T(Eigen::Index(d), Eigen::Index(rows[j])) = t(Eigen::Index(j));
      f.t_width = std::max(f.t_width, w);
      found = true;
    }
    if (!found) return false;
  }
  f.B = T * (Eigen::MatrixXd::Identity(Eigen::Index(n), Eigen::Index(n)) - f.P * f.A);
  return true;
}

bool is_exact(const DenseCurveFilters& f) {
  Eigen::MatrixXd AB(f.A.rows() + f.B.rows(), f.A.cols());
  AB << f.A, f.B;
  Eigen::MatrixXd PQ(f.P.rows(), f.P.cols() + f.Q.cols());
  PQ << f.P, f.Q;
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(PQ.rows(), PQ.rows());
  return (AB * PQ - I).cwiseAbs().maxCoeff() < 1e-10 && (PQ * AB - I).cwiseAbs().maxCoeff() < 1e-10;
}

// Exact fallback for loops where the local construction is not unique: A = P^+, Q an
// orthonormal basis of the complement of range(P), B = Q^T.
void build_global(DenseCurveFilters& f) {
  f.local = false;
  f.t_width = 0;
  f.A = pseudo_inverse(f.P);
  f.Q = null_space(f.P.transpose());
  f.B = f.Q.transpose();
}

template <std::size_t N>
std::array<double, N> taps(const Eigen::MatrixXd& M, Eigen::Index fixed, std::ptrdiff_t centre, int lo,
                           bool row) {
  std::array<double, N> t{};
  const std::size_t n = std::size_t(row ? M.cols() : M.rows());
  for (std::size_t j = 0; j < N; ++j) {
    const Eigen::Index i = Eigen::Index(wrap(centre + lo + std::ptrdiff_t(j), n));
    t[j] = row ? M(fixed, i) : M(i, fixed);
  }
  return t;
}

CurveStencils read_stencils() {
  const DenseCurveFilters f = build_curve_filters(kReferenceLoop);
  if (!f.local) throw std::logic_error("curve stencils: local construction failed");
  const std::ptrdiff_t k = 3 * kReferencePoint;
  CurveStencils s;
  s.a = taps<9>(f.A, kReferencePoint, k, -4, true);
  s.b_before = taps<12>(f.B, 2 * (kReferencePoint - 1) + 1, k, -7, true);
  s.b_after = taps<12>(f.B, 2 * kReferencePoint, k, -4, true);
  s.q_before = taps<5>(f.Q, 2 * (kReferencePoint - 1) + 1, k - 1, -2, false);
  s.q_after = taps<5>(f.Q, 2 * kReferencePoint, k + 1, -2, false);
  return s;
}

}  // namespace

std::vector<Vec3> curve_subdivide(std::span<const Vec3> c) {
  const std::size_t m = c.size();
  if (m < 3) throw std::invalid_argument("curve_subdivide: a closed loop needs at least 3 points");
  std::vector<Vec3> f(3 * m);
  for (std::size_t i = 0; i < m; ++i) {
    const Vec3& a = c[wrap(std::ptrdiff_t(i) - 1, m)];
    const Vec3& b = c[i];
    const Vec3& d = c[(i + 1) % m];
    const Vec3& e = c[(i + 2) % m];
    f[3 * i] = (4.0 * a + 19.0 * b + 4.0 * d) / 27.0;
    f[3 * i + 1] = (a + 16.0 * b + 10.0 * d) / 27.0;
    f[3 * i + 2] = (10.0 * b + 16.0 * d + e) / 27.0;
  }
  return f;
}

DenseCurveFilters build_curve_filters(std::size_t m) {
  if (m < 3) throw std::invalid_argument("curve filters: a closed loop needs at least 3 points");
  DenseCurveFilters f;
  f.P = curve_p(m);
  if (!(build_a(f, m) && build_q(f, m) && build_b(f, m) && is_exact(f))) build_global(f);
  if (!is_exact(f))
    throw std::logic_error("curve filters: no exact construction for " + std::to_string(m) + " points");
  return f;
}

const CurveStencils& curve_stencils() {
  static const CurveStencils s = read_stencils();  // thread-safe one-time build
  return s;
}

CurveFilters::CurveFilters(std::size_t m) : m_(m), dense_(m < kStencilLoop) {
  if (m < 3) throw std::invalid_argument("curve filters: a closed loop needs at least 3 points");
  if (dense_) filters_ = build_curve_filters(m);
}

void CurveFilters::analyse(std::span<const Vec3> fine, std::span<Vec3> coarse,
                           std::span<Vec3> details) const {
  const std::size_t n = 3 * m_;
  if (fine.size() != n || coarse.size() != m_ || details.size() != 2 * m_) {
    throw std::invalid_argument("curve analyse: size mismatch");
  }
  if (dense_) {
    for (std::size_t k = 0; k < m_; ++k) {
      Vec3 c = Vec3::Zero();
      for (std::size_t j = 0; j < n; ++j) c += filters_.A(Eigen::Index(k), Eigen::Index(j)) * fine[j];
      coarse[k] = c;
    }
    for (std::size_t d = 0; d < 2 * m_; ++d) {
      Vec3 v = Vec3::Zero();
      for (std::size_t j = 0; j < n; ++j) v += filters_.B(Eigen::Index(d), Eigen::Index(j)) * fine[j];
      details[d] = v;
    }
    return;
  }
  const CurveStencils& s = curve_stencils();
  for (std::size_t k = 0; k < m_; ++k) {
    const std::ptrdiff_t home = std::ptrdiff_t(3 * k);
    Vec3 c = Vec3::Zero(), after = Vec3::Zero(), before = Vec3::Zero();
    for (int o = -4; o <= 4; ++o) c += s.a[std::size_t(o + 4)] * fine[wrap(home + o, n)];
    for (int o = -4; o <= 7; ++o) after += s.b_after[std::size_t(o + 4)] * fine[wrap(home + o, n)];
    // Fine 3k + 2 is the point before displaced point 3 (k + 1).
    for (int o = -7; o <= 4; ++o) before += s.b_before[std::size_t(o + 7)] * fine[wrap(home + 3 + o, n)];
    coarse[k] = c;
    details[2 * k] = after;
    details[2 * k + 1] = before;
  }
}

void CurveFilters::synthesise(std::span<const Vec3> coarse, std::span<const Vec3> details,
                              std::span<Vec3> fine) const {
  const std::size_t n = 3 * m_;
  if (fine.size() != n || coarse.size() != m_ || details.size() != 2 * m_) {
    throw std::invalid_argument("curve synthesise: size mismatch");
  }
  const std::vector<Vec3> p = curve_subdivide(coarse);
  for (std::size_t j = 0; j < n; ++j) fine[j] = p[j];
  if (dense_) {
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t d = 0; d < 2 * m_; ++d)
        fine[j] += filters_.Q(Eigen::Index(j), Eigen::Index(d)) * details[d];
    return;
  }
  const CurveStencils& s = curve_stencils();
  for (std::size_t d = 0; d < 2 * m_; ++d) {
    const std::ptrdiff_t home = std::ptrdiff_t(introduced_fine(d));
    const std::array<double, 5>& q = d % 2 == 0 ? s.q_after : s.q_before;
    for (int o = -2; o <= 2; ++o) fine[wrap(home + o, n)] += q[std::size_t(o + 2)] * details[d];
  }
}

}  // namespace pupwave::sqrt3

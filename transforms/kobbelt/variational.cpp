#include "transforms/kobbelt/variational.h"

#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace pupwave::kobbelt {
namespace {

using Row = std::array<double, 7>;  // C row on fine samples c-3 .. c+3 (c = the odd sample)
// Fills the taps beta_i of the energy term K(p_i) = sum_k beta_i[k] p_{i+k}.
using TermFn = std::function<void(std::size_t i, std::span<double> beta)>;

// Row c of C = the gradient of E = sum_i K(p_i)^2 with respect to p_c (up to the factor 2),
// summing only the terms i whose stencil i .. i+order lies on the line (natural boundary).
Row energy_row(std::size_t n, std::size_t order, const TermFn& beta_of, std::size_t c) {
  Row row{};
  if (n <= order) return row;
  std::array<double, 4> beta{};
  const std::size_t i0 = c >= order ? c - order : 0, i1 = std::min(c, n - 1 - order);
  for (std::size_t i = i0; i <= i1; ++i) {
    beta_of(i, std::span<double>(beta.data(), order + 1));
    for (std::size_t k = 0; k <= order; ++k) row[i + k + 3 - c] += beta[c - i] * beta[k];
  }
  return row;
}

// Splits a C row into a unit-diagonal row of A and the four B taps (even j-1 .. j+2).
void store_row(const Row& row, std::size_t j, EulerLagrangeSystem& s) {
  const double diag = row[3];
  if (!(std::abs(diag) > 0.0) || !std::isfinite(diag)) {
    throw std::domain_error("variational subdivision: degenerate Euler-Lagrange row " + std::to_string(j));
  }
  s.a.sub[j] = row[1] / diag;
  s.a.diag[j] = 1.0;
  s.a.super[j] = row[5] / diag;
  for (std::size_t k = 0; k < 4; ++k) s.b.at(j, k) = row[2 * k] / diag;
}

EulerLagrangeSystem empty_system(std::size_t n) {
  const std::size_t no = n / 2;
  EulerLagrangeSystem s;
  s.n = n;
  s.a = Tridiagonal{std::vector<double>(no, 0.0), std::vector<double>(no, 1.0), std::vector<double>(no, 0.0)};
  s.b = make_banded_step(no, 4, -1);
  return s;
}

EulerLagrangeSystem from_rows(std::size_t n, const std::function<Row(std::size_t c)>& row_of) {
  EulerLagrangeSystem s = empty_system(n);
  for (std::size_t j = 0; j < n / 2; ++j) store_row(row_of(2 * j + 1), j, s);
  return s;
}

EulerLagrangeSystem from_energy(std::size_t n, std::size_t order, const TermFn& beta_of) {
  return from_rows(n, [&](std::size_t c) { return energy_row(n, order, beta_of, c); });
}

// Uniform difference stencils: K1 = first differences (only for lines of 2 samples),
// K2 = Delta^2, K3 = Delta^3.
std::vector<double> uniform_stencil(std::size_t order) {
  switch (order) {
    case 1: return {-1.0, 1.0};
    case 2: return {1.0, -2.0, 1.0};
    default: return {-1.0, 3.0, -3.0, 1.0};
  }
}

EulerLagrangeSystem uniform_energy_system(std::size_t order, std::size_t n) {
  const std::vector<double> st = uniform_stencil(order);
  return from_energy(
      n, order, [&](std::size_t, std::span<double> beta) { std::copy(st.begin(), st.end(), beta.begin()); });
}

// K4pt rows. Inside, the Euler-Lagrange row of (3 + sqrt 3) K2 + K3 is 6 Delta^4 + Delta^6
// = (1, 0, -9, 16, -9, 0, 1): the 4-point rule with A = I. At the ends the energy summed
// over existing differences is badly conditioned (cond 605 for one level, 5e8 for eight;
// docs/kobbelt.md), so there the odd sample is the polynomial through the even samples of
// its stencil that exist (quadratic, or linear beyond the last even sample of an even line).
Row four_point_row(std::size_t n, std::size_t c) {
  const auto last = static_cast<std::ptrdiff_t>((n - 1) / 2);  // last even (coarse) index
  const auto j = static_cast<std::ptrdiff_t>(c / 2);
  const std::ptrdiff_t k0 = std::max<std::ptrdiff_t>(j - 1, 0), k1 = std::min(j + 2, last);
  Row row{};
  row[3] = 1.0;
  const double x = static_cast<double>(j) + 0.5;  // the odd sample in coarse units
  for (std::ptrdiff_t k = k0; k <= k1; ++k) {
    double w = 1.0;  // Lagrange weight of even sample k at x
    for (std::ptrdiff_t l = k0; l <= k1; ++l) {
      if (l != k) w *= (x - static_cast<double>(l)) / static_cast<double>(k - l);
    }
    row[static_cast<std::size_t>(2 * (k - j) + 2)] = -w;
  }
  return row;
}

// Kspl rows (Eq. 8 inside, Appendix A Eq. 21 at the ends, uniform knots): the natural cubic
// spline through the even samples, evaluated at the odd ones. Interior rows are
// 2 Delta^4 - Delta^6; the first segment's row is s''(t_0) = 0 eliminated against the C^2
// conditions at t_1 (Eq. 21 with unit spacing, times 2), the last segment's its mirror, and
// for even n the sample beyond the last knot lies on the spline's linear extension: with
// the last segment's knots a, b, midpoint m and s''(b) = 0, that tangent line gives
// e = (13 b + a - 8 m) / 6.
Row spline_row(std::size_t n, std::size_t c) {
  const std::size_t last_knot = n % 2 == 1 ? n - 1 : n - 2;
  if (c == n - 1) return {-1, 8, -13, 6, 0, 0, 0};           // beyond the last knot (n even)
  if (c == 1) return {0, 0, 9, -24, 22, -8, 1};              // first segment, s''(t_0) = 0
  if (c + 1 == last_knot) return {1, -8, 22, -24, 9, 0, 0};  // last segment, mirrored
  return {-1, 8, -23, 32, -23, 8, -1};
}

// Coefficients of the divided difference [t_i .. t_{i+order}] p (Section 1.1).
void divided_difference(std::span<const double> t, std::size_t i, std::span<double> beta) {
  const std::size_t order = beta.size() - 1;
  for (std::size_t k = 0; k <= order; ++k) {
    double denom = 1.0;
    for (std::size_t l = 0; l <= order; ++l) {
      if (l != k) denom *= t[i + k] - t[i + l];
    }
    beta[k] = 1.0 / denom;
  }
}

}  // namespace

std::string_view scheme_name(Scheme s) {
  switch (s) {
    case Scheme::k2: return "k2";
    case Scheme::k3: return "k3";
    case Scheme::kspl: return "kspl";
    case Scheme::k4pt: return "k4pt";
  }
  return "?";
}

Scheme parse_scheme(std::string_view name) {
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl, Scheme::k4pt}) {
    if (name == scheme_name(s)) return s;
  }
  throw std::invalid_argument("unknown variational scheme '" + std::string(name) +
                              "' (valid: k2, k3, kspl, k4pt)");
}

EulerLagrangeSystem euler_lagrange_system(Scheme scheme, std::size_t n) {
  if (n < 3) return uniform_energy_system(1, n);
  if (scheme == Scheme::k2 || n < 5) return uniform_energy_system(2, n);
  switch (scheme) {
    case Scheme::k3: return uniform_energy_system(3, n);
    case Scheme::k4pt: return from_rows(n, [n](std::size_t c) { return four_point_row(n, c); });
    default: return from_rows(n, [n](std::size_t c) { return spline_row(n, c); });
  }
}

EulerLagrangeSystem euler_lagrange_system(Scheme scheme, std::span<const double> t) {
  if (scheme != Scheme::k2 && scheme != Scheme::k3) {
    throw std::invalid_argument("non-uniform parameterization is implemented for k2 and k3 only");
  }
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (!(t[i] > t[i - 1])) {
      throw std::invalid_argument("parameter values must be strictly increasing");
    }
  }
  const std::size_t n = t.size();
  const std::size_t order = n < 3 ? 1 : (scheme == Scheme::k2 || n < 5 ? 2 : 3);
  return from_energy(n, order,
                     [&](std::size_t i, std::span<double> beta) { divided_difference(t, i, beta); });
}

std::vector<double> euler_lagrange_row(const EulerLagrangeSystem& s, std::size_t j) {
  std::vector<double> row(7, 0.0);
  const std::size_t no = s.a.size();
  if (j >= no) throw std::out_of_range("euler_lagrange_row: no such odd row");
  const auto c = static_cast<std::ptrdiff_t>(2 * j + 1), n = static_cast<std::ptrdiff_t>(s.n);
  const double values[7] = {s.b.at(j, 0), j > 0 ? s.a.sub[j] : 0.0,        s.b.at(j, 1), 1.0,
                            s.b.at(j, 2), j + 1 < no ? s.a.super[j] : 0.0, s.b.at(j, 3)};
  for (std::ptrdiff_t k = 0; k < 7; ++k) {
    const std::ptrdiff_t pos = c - 3 + k;
    if (pos >= 0 && pos < n) row[static_cast<std::size_t>(k)] = values[k];
  }
  return row;
}

}  // namespace pupwave::kobbelt

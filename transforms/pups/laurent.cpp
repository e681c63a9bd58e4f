#include "transforms/pups/laurent.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pupwave::pups {

double Laurent::at(int k) const {
  if (k < lo || k > hi()) return 0;
  return c[static_cast<std::size_t>(k - lo)];
}

double Laurent::max_abs() const {
  double m = 0;
  for (double x : c) m = std::max(m, std::abs(x));
  return m;
}

namespace {

// a + s b over the union of the spans.
Laurent axpy(const Laurent& a, double s, const Laurent& b) {
  if (a.is_zero() && b.is_zero()) return {};
  if (a.is_zero()) return s * b;
  if (b.is_zero()) return a;
  const int lo = std::min(a.lo, b.lo), hi = std::max(a.hi(), b.hi());
  Laurent r{lo, std::vector<double>(static_cast<std::size_t>(hi - lo + 1), 0.0)};
  for (int k = lo; k <= hi; ++k) r.c[static_cast<std::size_t>(k - lo)] = a.at(k) + s * b.at(k);
  return r;
}

}  // namespace

Laurent operator+(const Laurent& a, const Laurent& b) { return axpy(a, 1.0, b); }
Laurent operator-(const Laurent& a, const Laurent& b) { return axpy(a, -1.0, b); }

Laurent operator*(double s, const Laurent& a) {
  Laurent r = a;
  for (double& x : r.c) x *= s;
  return r;
}

Laurent operator*(const Laurent& a, const Laurent& b) {
  if (a.is_zero() || b.is_zero()) return {};
  Laurent r{a.lo + b.lo, std::vector<double>(a.c.size() + b.c.size() - 1, 0.0)};
  for (std::size_t i = 0; i < a.c.size(); ++i)
    for (std::size_t j = 0; j < b.c.size(); ++j) r.c[i + j] += a.c[i] * b.c[j];
  return r;
}

Laurent trimmed(const Laurent& a, double tol) {
  std::size_t lo = 0, hi = a.c.size();
  while (hi > lo && std::abs(a.c[hi - 1]) <= tol) --hi;
  while (lo < hi && std::abs(a.c[lo]) <= tol) ++lo;
  if (lo == hi) return {};
  return {a.lo + static_cast<int>(lo), std::vector<double>(a.c.begin() + static_cast<std::ptrdiff_t>(lo),
                                                           a.c.begin() + static_cast<std::ptrdiff_t>(hi))};
}

namespace {

// Collects taps[t] at exponent k(t) for the taps whose sample parity is ph.
template <class ExponentOf>
Laurent phase(const Filter& f, int ph, ExponentOf exponent_of) {
  Laurent out;
  std::vector<std::pair<int, double>> terms;
  for (std::size_t t = 0; t < f.taps.size(); ++t) {
    const int pos = f.offset + static_cast<int>(t);
    if (((pos % 2) + 2) % 2 == ph) terms.emplace_back(exponent_of(pos), f.taps[t]);
  }
  for (const auto& [k, v] : terms) out = out + Laurent::monomial(v, k);
  return out;
}

// Interleaves sample positions 2k + ph (weight v) into a filter over [min, max].
Filter interleave(const std::vector<std::pair<int, double>>& at_position) {
  if (at_position.empty()) return {{0.0}, 0};
  int lo = at_position.front().first, hi = lo;
  for (const auto& [p, v] : at_position) lo = std::min(lo, p), hi = std::max(hi, p);
  Filter f{std::vector<double>(static_cast<std::size_t>(hi - lo + 1), 0.0), lo};
  for (const auto& [p, v] : at_position) f.taps[static_cast<std::size_t>(p - lo)] += v;
  return f;
}

}  // namespace

Laurent analysis_phase(const Filter& f, int ph) {
  // x[2j + pos] with pos = 2k + ph is wire ph at index j + k.
  return phase(f, ph, [ph](int pos) { return (pos - ph) / 2; });
}

Laurent synthesis_phase(const Filter& f, int ph) {
  // x[2i + ph] gets taps at pos = ph - 2k from band index i + k.
  return phase(f, ph, [ph](int pos) { return (ph - pos) / 2; });
}

Filter analysis_filter(const Laurent& even, const Laurent& odd) {
  std::vector<std::pair<int, double>> pts;
  for (int k = even.lo; !even.is_zero() && k <= even.hi(); ++k) pts.emplace_back(2 * k, even.at(k));
  for (int k = odd.lo; !odd.is_zero() && k <= odd.hi(); ++k) pts.emplace_back(2 * k + 1, odd.at(k));
  return interleave(pts);
}

Filter synthesis_filter(const Laurent& even, const Laurent& odd) {
  std::vector<std::pair<int, double>> pts;
  for (int k = even.lo; !even.is_zero() && k <= even.hi(); ++k) pts.emplace_back(-2 * k, even.at(k));
  for (int k = odd.lo; !odd.is_zero() && k <= odd.hi(); ++k) pts.emplace_back(1 - 2 * k, odd.at(k));
  return interleave(pts);
}

Laurent euclid_quotient(const Laurent& v, const Laurent& w, Laurent* remainder) {
  if (w.is_zero() || v.c.size() < w.c.size())
    throw std::invalid_argument("euclid_quotient: divisor is zero or longer than the dividend");
  const int Lv = static_cast<int>(v.c.size()), Lw = static_cast<int>(w.c.size());
  const int nq = Lv - Lw + 1;
  Laurent best;
  double best_max = std::numeric_limits<double>::infinity();
  int best_low = 0;
  for (int low = 0; low <= nq; ++low) {
    // q spans z^(v.lo - w.lo) ... ; its `low` first coefficients cancel v's lowest ones
    // (forward substitution), the other nq - low cancel v's highest ones (backward).
    std::vector<double> q(static_cast<std::size_t>(nq), 0.0);
    for (int j = 0; j < low; ++j) {
      double s = v.c[static_cast<std::size_t>(j)];
      for (int i = std::max(0, j - Lw + 1); i < j; ++i)
        s -= q[static_cast<std::size_t>(i)] * w.c[static_cast<std::size_t>(j - i)];
      q[static_cast<std::size_t>(j)] = s / w.c.front();
    }
    for (int j = 0; j < nq - low; ++j) {
      const int pos = Lv - 1 - j, qi = nq - 1 - j;  // v position, q index solved here
      double s = v.c[static_cast<std::size_t>(pos)];
      for (int i = qi + 1; i < nq; ++i)
        if (pos - i >= 0 && pos - i < Lw)
          s -= q[static_cast<std::size_t>(i)] * w.c[static_cast<std::size_t>(pos - i)];
      q[static_cast<std::size_t>(qi)] = s / w.c.back();
    }
    Laurent cand{v.lo - w.lo, q};
    const double m = cand.max_abs();
    if (std::isfinite(m) && m < best_max * (1 - 1e-12)) best = cand, best_max = m, best_low = low;
  }
  if (!std::isfinite(best_max)) throw std::invalid_argument("euclid_quotient: division failed");
  if (remainder) {
    // Keep only the Lw - 1 coefficients that were not cancelled (the others are zero by
    // construction; dropping them avoids carrying rounding residue).
    const Laurent full = v - best * w;
    const int lo = v.lo + best_low;
    Laurent r{lo, std::vector<double>(static_cast<std::size_t>(Lw - 1), 0.0)};
    for (int k = 0; k < Lw - 1; ++k) r.c[static_cast<std::size_t>(k)] = full.at(lo + k);
    *remainder = r;
  }
  return best;
}

}  // namespace pupwave::pups

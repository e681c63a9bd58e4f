#include "transforms/pups/lifting_factorization.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pupwave::pups {

namespace {

using Kind = LiftingStep::Kind;

// A column (or row) of polyphase symbols: the even and the odd wire.
struct Pair {
  Laurent e, o;
};

void apply(const LiftingStep& s, Pair& v) {
  if (s.kind == Kind::predict)
    v.o = v.o + s.filter * v.e;
  else
    v.e = v.e + s.filter * v.o;
}

void undo(const LiftingStep& s, Pair& v) {
  if (s.kind == Kind::predict)
    v.o = v.o - s.filter * v.e;
  else
    v.e = v.e - s.filter * v.o;
}

// U^{-1} v for the steps U (applied in analysis order).
Pair inverse_apply(const std::vector<LiftingStep>& steps, Pair v) {
  for (auto it = steps.rbegin(); it != steps.rend(); ++it) undo(*it, v);
  return v;
}

// Moves a monomial gcd m z^k (on the odd wire if even is zero) to a constant on the even
// wire with steps of unit coefficients; z^k and z^-k factors are not lifting steps alone.
void normalize_gcd(Pair& v, std::vector<LiftingStep>& steps) {
  auto push = [&](Kind kind, Laurent f) {
    steps.push_back({kind, std::move(f)});
    apply(steps.back(), v);
  };
  if (v.e.is_zero()) {
    const int k = v.o.lo;
    push(Kind::update, Laurent::monomial(1, -k));   // even = m
    push(Kind::predict, Laurent::monomial(-1, k));  // odd = 0
    v.o = {};
  }
  const int k = v.e.lo;
  if (k != 0) {
    push(Kind::predict, Laurent::monomial(1, -2 * k));                           // odd = m z^-k
    push(Kind::update, Laurent::monomial(-1, 2 * k) + Laurent::monomial(1, k));  // even = m
    push(Kind::predict, Laurent::monomial(-1, -k));                              // odd = 0
    v.e = trimmed(v.e, 0);
    v.o = {};
  }
}

// Euclidean algorithm on (P_even, P_odd): steps U with U (P_even, P_odd) = (m, 0).
std::vector<LiftingStep> euclid_steps(Pair v, double* m) {
  const double tol = 1e-13 * std::max(v.e.max_abs(), v.o.max_abs());
  std::vector<LiftingStep> steps;
  for (int guard = 0; guard < 512 && !v.e.is_zero() && !v.o.is_zero(); ++guard) {
    Laurent r;
    if (v.e.c.size() >= v.o.c.size()) {
      steps.push_back({Kind::update, -1.0 * euclid_quotient(v.e, v.o, &r)});
      v.e = trimmed(r, tol);
    } else {
      steps.push_back({Kind::predict, -1.0 * euclid_quotient(v.o, v.e, &r)});
      v.o = trimmed(r, tol);
    }
  }
  const Laurent& g = v.e.is_zero() ? v.o : v.e;
  if (g.c.size() != 1)
    throw std::invalid_argument(
        "PUPs bank: the polyphase components of P share a factor, so no FIR perfect "
        "reconstruction exists");
  normalize_gcd(v, steps);
  *m = v.e.c.at(0);
  return steps;
}

// Largest |a - b| over the union of spans.
double distance(const Laurent& a, const Laurent& b) { return (a - b).max_abs(); }

double filter_sum(const Filter& f) {
  double s = 0;
  for (double t : f.taps) s += t;
  return s;
}

// Removes rounding residue at the ends of a realized filter.
Filter clean(const Filter& f) {
  double m = 0;
  for (double t : f.taps) m = std::max(m, std::abs(t));
  std::size_t lo = 0, hi = f.taps.size();
  while (hi > lo + 1 && std::abs(f.taps[hi - 1]) <= 1e-13 * m) --hi;
  while (lo + 1 < hi && std::abs(f.taps[lo]) <= 1e-13 * m) ++lo;
  return {std::vector<double>(f.taps.begin() + static_cast<std::ptrdiff_t>(lo),
                              f.taps.begin() + static_cast<std::ptrdiff_t>(hi)),
          f.offset + static_cast<int>(lo)};
}

}  // namespace

LiftingFactorization factor_bank(const FilterBank& bank, bool normalize_dc) {
  const Pair p{trimmed(synthesis_phase(bank.P, 0), 0), trimmed(synthesis_phase(bank.P, 1), 0)};
  if (p.e.is_zero() && p.o.is_zero()) throw std::invalid_argument("PUPs bank: P is zero");
  LiftingFactorization out;
  double m = 1;
  out.steps = euclid_steps(p, &m);
  // Rows of U: apply the steps to the identity's rows as row operations.
  Pair row1{Laurent::monomial(1, 0), {}}, row2{{}, Laurent::monomial(1, 0)};
  for (const auto& s : out.steps) {
    if (s.kind == Kind::predict)
      row2 = {row2.e + s.filter * row1.e, row2.o + s.filter * row1.o};
    else
      row1 = {row1.e + s.filter * row2.e, row1.o + s.filter * row2.o};
  }
  // The update that turns m A_U into m A: u = m A Q_U with Q_U = U^{-1} (0, 1).
  const Pair a{analysis_phase(bank.A, 0), analysis_phase(bank.A, 1)};
  const Pair qu = inverse_apply(out.steps, {{}, Laurent::monomial(1, 0)});
  const Laurent u0 = m * (a.e * qu.e + a.o * qu.o);
  const Laurent u = trimmed(u0, 1e-14 * std::max(1.0, u0.max_abs()));
  if (!u.is_zero()) {
    out.steps.push_back({Kind::update, u});
    row1 = {row1.e + u * row2.e, row1.o + u * row2.o};
  }
  // Detail scale: the design's B is mu z^n (second row of U); the index shift n is kept.
  const Pair b{analysis_phase(bank.B, 0), analysis_phase(bank.B, 1)};
  const bool use_even = !trimmed(b.e, 0).is_zero();
  const Laurent bt = trimmed(use_even ? b.e : b.o, 0), rt = trimmed(use_even ? row2.e : row2.o, 1e-14);
  if (bt.is_zero() || rt.is_zero()) throw std::invalid_argument("PUPs bank: B is not the complement of P");
  out.odd_scale = bt.c.front() / rt.c.front();
  const int n = bt.lo - rt.lo;
  out.dc_gain = filter_sum(bank.A);
  if (normalize_dc && !(std::abs(out.dc_gain) > 1e-6))
    throw std::invalid_argument("PUPs bank: A has no DC gain to normalize");
  const double g = normalize_dc ? out.dc_gain : 1.0;
  out.even_scale = 1.0 / (m * g);
  // Check that the steps realize the design (they do for any PR bank; a non-PR bank fails).
  const double scale = std::max({a.e.max_abs(), a.o.max_abs(), b.e.max_abs(), b.o.max_abs(), 1.0});
  const Laurent zn = Laurent::monomial(out.odd_scale, n);
  const double err = std::max({distance((1.0 / m) * row1.e, a.e), distance((1.0 / m) * row1.o, a.o),
                               distance(zn * row2.e, b.e), distance(zn * row2.o, b.o)});
  if (!(err <= 1e-9 * scale))
    throw std::invalid_argument("PUPs bank is not perfectly reconstructing (lifting residual " +
                                std::to_string(err) + ")");
  // Realized interior filters: analysis rows scaled, synthesis columns from G = H^{-1}.
  FilterBank& in = out.interior;
  in = bank;
  in.A = clean(analysis_filter(out.even_scale * row1.e, out.even_scale * row1.o));
  in.B = clean(analysis_filter(out.odd_scale * row2.e, out.odd_scale * row2.o));
  const std::vector<LiftingStep>& st = out.steps;
  const Pair pc = inverse_apply(st, {Laurent::monomial(1.0 / out.even_scale, 0), {}});
  const Pair qc = inverse_apply(st, {{}, Laurent::monomial(1.0 / out.odd_scale, 0)});
  in.P = clean(synthesis_filter(pc.e, pc.o));
  in.Q = clean(synthesis_filter(qc.e, qc.o));
  return out;
}

}  // namespace pupwave::pups

#pragma once
// Laurent polynomials with double coefficients: the symbols of the polyphase filters of a
// two-channel filter bank, used to factor a PUPs bank into lifting steps.
//
// Symbol convention: an operator v -> w with w[i] = sum_k t_k v[i + k] has the symbol
// sum_k t_k z^k, so composing operators multiplies symbols (this is also the convention of
// lifting::Taps: taps[k] at z^(offset + k)).

#include <vector>

#include "transforms/pups/filter_bank.h"

namespace pupwave::pups {

struct Laurent {
  int lo = 0;             // exponent of c[0]
  std::vector<double> c;  // coefficients of z^lo, z^(lo+1), ...

  bool is_zero() const { return c.empty(); }
  int hi() const { return lo + static_cast<int>(c.size()) - 1; }
  double at(int k) const;  // coefficient of z^k (0 outside)
  double max_abs() const;
  static Laurent monomial(double a, int k) { return {k, {a}}; }
};

Laurent operator+(const Laurent& a, const Laurent& b);
Laurent operator-(const Laurent& a, const Laurent& b);
Laurent operator*(const Laurent& a, const Laurent& b);
Laurent operator*(double s, const Laurent& a);

// Drops end coefficients with |c| <= tol (all of them for a zero polynomial).
Laurent trimmed(const Laurent& a, double tol);

// Polyphase components of an analysis filter (c[j] = sum_t taps[t] x[2j + offset + t]):
// component ph maps wire ph of x (x[2i + ph]) to the output band.
Laurent analysis_phase(const Filter& f, int ph);
// Polyphase components of a synthesis filter (x[2j + offset + t] += taps[t] c[j]): component
// ph maps the band to wire ph of x.
Laurent synthesis_phase(const Filter& f, int ph);
// Inverses of the two: a filter (taps from the lowest to the highest sample) from components.
Filter analysis_filter(const Laurent& even, const Laurent& odd);
Filter synthesis_filter(const Laurent& even, const Laurent& odd);

// One division step of the Euclidean algorithm for Laurent polynomials: the quotient q with
// v - q w shorter than w (length(w) - 1 coefficients). Of the admissible quotients (which
// differ in how many coefficients are cancelled at the low vs. the high end) the one with
// the smallest largest coefficient is chosen. w must be non-zero and not longer than v.
Laurent euclid_quotient(const Laurent& v, const Laurent& w, Laurent* remainder);

}  // namespace pupwave::pups

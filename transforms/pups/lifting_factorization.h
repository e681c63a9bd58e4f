#pragma once
// Factorization of a PUPs filter bank into lifting steps, so that the transform is
// invertible on finite lines by construction (every step is undone by its mirror, whatever
// the boundary rule). See docs/pups.md for the route and its measured conditioning.
//
// Route: the Euclidean algorithm on the polyphase components (P_even, P_odd) of the
// subdivision filter gives steps U with U (P_even, P_odd) = (m, 0); the second row of U
// is then the detail filter B up to a constant and an index shift (B is fixed by P, Eq. 35).
// Every bank with this P and B differs only in Q and A (Q' = Q + P S), so one final update
// step of the coarse wire from the detail wire turns U's first row into the designed A.
// That last step carries all of the bandwidth extension; the Euclidean part depends on P
// alone and stays short and well conditioned.

#include <vector>

#include "transforms/pups/filter_bank.h"
#include "transforms/pups/laurent.h"

namespace pupwave::pups {

struct LiftingStep {
  enum class Kind { predict, update } kind;  // predict: odd += f even; update: even += f odd
  Laurent filter;                            // symbol of f (taps[k] at z^(lo + k))
};

struct LiftingFactorization {
  std::vector<LiftingStep> steps;  // analysis order
  double even_scale = 1;           // coarse = even_scale * (even wire after the steps)
  double odd_scale = 1;            // detail = odd_scale * (odd wire after the steps)
  double dc_gain = 1;              // sum of the designed A taps (divided out if normalized)
  // The banded filters the steps realize away from the boundaries (same taps as the design
  // up to the DC normalization, offsets as realized: the detail index may be shifted).
  FilterBank interior;
};

// Factors `bank`. With normalize_dc, the coarse band is divided by the DC gain of A (so a
// constant line gives that constant as coarse band) and P multiplied by it.
// Throws std::invalid_argument if the bank is not perfectly reconstructing (A P != I, ...)
// or its P has polyphase components with a common non-trivial factor.
LiftingFactorization factor_bank(const FilterBank& bank, bool normalize_dc = true);

}  // namespace pupwave::pups

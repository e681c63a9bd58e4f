#pragma once
// PUPs weight functions and their refinement by least squares (framework paper, Eq. 17-22):
// w(u) ~ sum_i alpha_i w(2u - i) with shift d = 1, solved on a dense sample set.

#include <functional>
#include <vector>

#include "transforms/pups/filter_bank.h"

namespace pupwave::pups {

// A weight function placed on the integer grid. Its support, extended with zeros to an
// integer width W (a multiple of d = 1), is [first, first + W] with first = -floor(W/2), so
// the refinement indices are i = first..first+W (W + 1 coefficients; CINPACT c = 2.5 has
// W = 5 and 6 coefficients). Symmetric functions are centred in that interval.
struct PlacedWeight {
  std::function<double(double)> w;  // the placed function, zero outside the support
  int first = 0;                    // left end of the extended support = first index i
  int width = 0;                    // W
  bool interpolating = false;       // adds the hard constraints of Section 6.4
};

// Builds the placed weight function of a design (weight, degree, coeffs, domain, c, sigma).
// Throws std::invalid_argument for unusable parameters (degree < 0 or > 20, c <= 0,
// sigma < 0, empty polynomial, empty or inverted domain, WeightKind::given).
PlacedWeight make_weight(const DesignParams& params);

// Result of a refinement: P taps alpha_first..alpha_{first+W} and the error E.
struct Refinement {
  std::vector<double> coeffs;
  int first = 0;     // refinement index of coeffs[0]
  double error = 0;  // E = ||w - M c|| / ||w|| (Eq. 22)
};

// Solves Eq. 18 by least squares on `samples` points spread uniformly over the extended
// support; for an interpolating weight the coefficients with even index other than 0 are
// held at zero (hard constraints). samples must exceed the number of coefficients.
Refinement refine(const PlacedWeight& weight, int samples);

// Convenience: make_weight + refine with params.samples.
Refinement refine(const DesignParams& params);

// For a CINPACT family (plain or interpolating) and fixed c, the sigma in [lo, hi] that
// minimizes E (grid search followed by golden-section refinement). Returns that sigma.
double optimize_sigma(DesignParams params, double lo = 0.5, double hi = 60.0);

}  // namespace pupwave::pups

#pragma once
// Polynomial PUPs weights (framework paper, Section 6.2) whose least-squares refinement
// (Eq. 17-22) is a chosen subdivision mask: the route by which `filters search --weight
// polynomial` designs banks with vanishing moments. The weight is fitted to the refinable
// function of the mask (cascade algorithm) and its coefficients are then corrected by
// Gauss-Newton until refine() returns the mask itself.

#include <vector>

#include "transforms/pups/filter_bank.h"

namespace pupwave::pups {

// The symmetric mask of 2h+1 taps (h = moments/2 + 1) with `moments` zeros at z = -1 and one
// free parameter t: P(w) = 2 cos(w/2)^moments (1 + t sin(w/2)^2), taps summing to 2.
// moments must be even, 2..12. B of the bank then has `moments` vanishing moments.
std::vector<double> vanishing_moment_mask(int moments, double t);

struct MaskWeight {
  DesignParams params;       // polynomial on [-h, h], even degree `degree`, samples as asked
  double max_tap_error = 0;  // max |refine(params) - mask| over the taps, after the correction
  double fit_error = 0;      // relative L2 error of the polynomial against the refinable function
};

// Finds the polynomial weight of even `degree` (4..24) on [-h, h] (mask of 2h+1 taps, centred)
// whose refinement with `samples` samples is `mask` (symmetric, odd length, sum 2). Throws
// std::invalid_argument for a mask that is not symmetric or has no refinable function (the
// cascade diverges), and when Gauss-Newton does not reach 1e-11 (then no such weight was found).
MaskWeight polynomial_weight_for_mask(const std::vector<double>& mask, int degree, int samples = 100000);

}  // namespace pupwave::pups

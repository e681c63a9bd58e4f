#pragma once
// The candidate designs of `pupwave filters search`: grids over the parameters the seeds
// allow (weight, c, sigma, extension l) plus the boundary rule, as spec bodies that
// `compress --transform pups:<body>` accepts. Ranking them (coding gain, or the codec on
// images) is the CLI's job (tools/cmd_filters_search.cpp). Method: docs/pups.md.

#include <string>
#include <vector>

#include "transforms/pups/design.h"

namespace pupwave::pups {

struct SearchSpace {
  WeightKind weight = WeightKind::cinpact_interp;
  // CINPACT families: c = c_lo, c_lo + c_step, ..., c_hi.
  double c_lo = 3, c_hi = 9, c_step = 0.5;
  // sigma = scale x the sigma of least refinement error E for that c ...
  std::vector<double> sigma_scales{1.0};
  // ... or, when set, every sigma in [0.3, 80] at which B . 1 = 0 (the detail of a constant
  // line vanishes: two vanishing moments for the symmetric interpolating masks).
  bool leak_free_sigma = false;
  std::vector<int> degrees{1, 2, 3, 4, 5};  // B-splines
  // Polynomials: a weight of degree poly_degree on [-h, h] refining to the mask with
  // `moments` vanishing moments and parameter t (mask_weight.h), for every t in mask_params.
  int moments = 4;
  std::vector<double> mask_params{2.0, 2.25, 2.5, 2.75, 3.0, 3.25, 3.5};
  int poly_degree = 16;
  std::vector<int> extensions{0, 8, 16, 32};
  std::vector<BoundaryRule> boundaries{BoundaryRule::wire_hss, BoundaryRule::line_wss};
  int samples = 100000;
};

// Every design of the space as a canonical spec body, in a stable order (weight parameters,
// then l, then boundary). Parameter sets that cannot be designed (no refinable function, a
// singular Eq. 41) are left out and described in *skipped when given.
std::vector<std::string> search_candidates(const SearchSpace& space,
                                           std::vector<std::string>* skipped = nullptr);

// The sigmas in [lo, hi] at which the refinement of a CINPACT weight with this c has equal
// sums over its even and odd taps (B . 1 = 0), by a log-grid scan and bisection.
std::vector<double> leak_free_sigmas(DesignParams params, double lo = 0.3, double hi = 80.0);

}  // namespace pupwave::pups

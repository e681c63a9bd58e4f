#pragma once
// Optimal banded multiresolution filters from a subdivision filter P (multiresolution paper,
// Section 5, Eq. 35-61, Algorithm 5.1): B from P, Q by equality-constrained least squares
// over every admissible shift, bandwidth extension, A from Q.

#include <optional>
#include <vector>

#include "transforms/pups/filter_bank.h"

namespace pupwave::pups {

// How far to extend the bandwidth of Q and A.
struct ExtensionRule {
  std::optional<int> extension;  // fixed l (even, >= 0); wins over threshold if set
  double threshold = 0;          // else: smallest l = 0, 2, ... with error <= threshold
  int max_extension = 64;        // upper bound on l when searching by threshold
};

// One constrained least-squares design for a fixed l and shift (exposed for tests/CLI).
struct QDesign {
  std::vector<double> q;  // k + l taps, aligned with the padded P
  double error = 0;       // orthogonality error ||soft-constraint residual||_2
  int shift = 0;          // i of E_i: B Q = I holds with B shifted by 2i samples
};

// All admissible shifts for extension l, in increasing shift order; shifts whose hard
// system is singular are left out.
std::vector<QDesign> design_q_all_shifts(const std::vector<double>& p, int l);

// Algorithm 5.1 for the refinement taps p (P.offset = p_offset). The returned bank has the
// design errors, the chosen shift and design.extension = the l used; name and other design
// fields are left for the caller. Throws std::invalid_argument for bad input.
FilterBank design_bank(const std::vector<double>& p, int p_offset, const ExtensionRule& rule);

// Largest |entry - identity| of A P, B Q, A Q, B P built as circulant matrices on n coarse
// samples (2n fine). n must be at least as large as every filter's span.
double circulant_identity_error(const FilterBank& bank, int n);

// Smallest n for which circulant_identity_error is meaningful (no filter wraps onto itself).
int min_circulant_size(const FilterBank& bank);

}  // namespace pupwave::pups

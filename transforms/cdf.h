#pragma once
// The JPEG 2000 baseline wavelets: irreversible CDF 9/7 and reversible CDF 5/3 (lifting).
//
// Both follow JPEG 2000 Part 1 (Annex F): the first sample of a line is even (goes to the
// coarse band), the line is extended whole-sample symmetrically at both ends, the
// coarse band has DC gain 1 (the coarse band of a constant line is that constant) and the
// detail band has Nyquist gain 2. A line of one sample is left unchanged.

#include "transforms/transform1d.h"

namespace pupwave {

// JPEG 2000 irreversible 9/7 lifting constants (ITU-T T.800 Table F.4).
struct Cdf97Constants {
  static constexpr double alpha = -1.586134342059924;
  static constexpr double beta = -0.052980118572961;
  static constexpr double gamma = 0.882911075530934;
  static constexpr double delta = 0.443506852043971;
  static constexpr double K = 1.230174104914001;  // coarse /= K, detail *= K
};

// Spec "cdf97": float and double only (the int32_t overloads throw std::logic_error).
Transform1DPtr make_cdf97();

// Spec "cdf53": the int32_t overloads are the reversible integer transform of JPEG 2000
// (bit-exact lossless); the float/double overloads are the same lifting without rounding.
Transform1DPtr make_cdf53();

}  // namespace pupwave

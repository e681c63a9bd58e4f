#pragma once
// A PUPs multiresolution filter bank as plain data: the four banded filters P, Q, A, B of
// Moltaji-Runions-Samavati (Eq. 23-29) with their offsets, the design parameters that made
// them and the errors of the design. Serializable to compact bytes for file headers (the JSON
// form is the CLI's, tools/filter_bank_json.h); both rebuild the bank bit-exactly.

#include <cstdint>
#include <string>
#include <vector>

namespace pupwave::pups {

// One banded filter: non-zero taps and the index of taps[0] relative to the band start.
// How the offset is read depends on the role (see FilterBank).
struct Filter {
  std::vector<double> taps;
  int offset = 0;
  bool operator==(const Filter&) const = default;
};

// The weight-function families of the framework paper, Section 6.
enum class WeightKind : std::uint8_t {
  bspline = 0,         // uniform B-spline of a given degree (Section 6.1)
  polynomial = 1,      // polynomial on a bounded domain (Section 6.2)
  cinpact = 2,         // C-infinity bump exp(-sigma u^2 / (c^2 - u^2)) (Section 6.3)
  cinpact_interp = 3,  // sinc times the bump, interpolating (Section 6.4)
  given = 4,           // refinement coefficients given directly (no weight function)
};

// Parameters of a design; only the fields of the chosen family are meaningful.
struct DesignParams {
  WeightKind weight = WeightKind::bspline;
  int degree = 3;                       // bspline
  std::vector<double> coeffs;           // polynomial a_0..a_kappa (Eq. 32); or given taps
  double domain_lo = 0, domain_hi = 0;  // polynomial domain [mu_l, mu_r]
  double c = 0, sigma = 0;              // cinpact, cinpact_interp
  int samples = 100000;                 // dense samples of the refinement system (Eq. 18)
  int extension = 0;                    // bandwidth extension l actually used (Section 5.4)
  bool operator==(const DesignParams&) const = default;
};

// Index conventions (n fine samples x, coarse c and detail d of n/2 samples each):
//   synthesis  x[2j + P.offset + t] += P.taps[t] * c[j],  x[2j + Q.offset + t] += Q.taps[t] * d[j]
//   analysis   c[j] = sum_t A.taps[t] * x[2j + A.offset + t],
//              d[j] = sum_t B.taps[t] * x[2j + B.offset + t]
// so that A P = I, B Q = I, A Q = 0, B P = 0 on bi-infinite (or long circulant) signals.
struct FilterBank {
  std::string name;  // preset name, empty for a custom design
  DesignParams design;
  Filter P, Q, A, B;
  double refinement_error = 0;     // normalized least-squares error E (Eq. 22)
  double orthogonality_error = 0;  // residual of the soft constraints P^T Q = 0 (Eq. 41)
  int shift = 0;                   // chosen arrangement i of E_i (Section 5.3)
  bool operator==(const FilterBank&) const = default;
};

// Name of a weight family as used by the CLI and in specs ("bspline", "cinpact-interp", ...).
std::string to_string(WeightKind kind);
// Inverse of to_string; throws std::invalid_argument for an unknown name.
WeightKind weight_kind_from_string(const std::string& name);

// Compact little-endian binary form for file headers (layout in docs/pups.md).
std::vector<std::uint8_t> to_bytes(const FilterBank& bank);
// Parses to_bytes output; every length is validated against the input and against sane
// limits, and malformed input throws std::invalid_argument (never reads out of bounds).
FilterBank filter_bank_from_bytes(const std::vector<std::uint8_t>& bytes);

}  // namespace pupwave::pups

#pragma once
// Variational subdivision schemes (Kobbelt-Schroder, Section 1.1): the new (odd) samples of
// a refined polygon minimise a quadratic fairness energy with the old (even) samples fixed.
// The discrete Euler-Lagrange equations C p = 0 (Eq. 5/9), one row per odd sample, split
// into A = C U_o (tridiagonal) and B = C U_e, so that A p_odd = -B p_even (Eq. 7).
//
// Finite open polygons (odd and even lengths): K2 and K3 use natural boundary conditions,
// the energy summing only the differences that exist; Kspl uses the natural spline's end
// conditions (Appendix A), K4pt the polynomial through the existing stencil samples (its
// energy boundary is badly conditioned). docs/kobbelt.md lists all boundary rows.

#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "transforms/kobbelt/banded_lifting.h"
#include "transforms/kobbelt/cyclic_reduction.h"

namespace pupwave::kobbelt {

enum class Scheme {
  k2,    // minimal second differences (4th-order Butterworth half-band)
  k3,    // minimal third differences (6th-order Butterworth half-band)
  kspl,  // interpolating cubic splines (natural end conditions, Appendix A)
  k4pt,  // the 4-point rule (-1, 9, 9, -1)/16
};

// "k2", "k3", "kspl", "k4pt".
std::string_view scheme_name(Scheme s);
// Inverse of scheme_name; std::invalid_argument listing the valid names otherwise.
Scheme parse_scheme(std::string_view name);

// The Euler-Lagrange system of one refinement step on a line of n fine samples
// (ceil(n/2) even = known, floor(n/2) odd = unknown), rows normalised so that A has a unit
// diagonal: the detail C p of a row is then p_odd minus its variational prediction.
struct EulerLagrangeSystem {
  std::size_t n = 0;  // fine samples
  Tridiagonal a;      // A = C U_o, floor(n/2) rows, diag == 1
  BandedStep b;       // B = C U_e: odd row j reads even samples j-1 .. j+2 (offset -1, width 4)
};

// Uniform parameterisation of `scheme` for n >= 1 fine samples. Lines too short for the
// scheme's differences fall back to the next lower order (K3, K4pt: n < 5 use K2;
// Kspl: n < 5 uses K2, which is the natural spline of <= 2 knots; K2: n == 2 uses first
// differences, i.e. constant extension).
EulerLagrangeSystem euler_lagrange_system(Scheme scheme, std::size_t n);

// Non-uniform parameterisation (divided differences, Section 1.1) for K2 and K3; t holds
// the n strictly increasing fine parameter values. std::invalid_argument for other schemes
// or non-increasing t.
EulerLagrangeSystem euler_lagrange_system(Scheme scheme, std::span<const double> t);

// The full row of C for odd row j: 7 coefficients on fine samples 2j+1-3 .. 2j+1+3
// (zero outside the line). For documentation and tests.
std::vector<double> euler_lagrange_row(const EulerLagrangeSystem& s, std::size_t j);

}  // namespace pupwave::kobbelt

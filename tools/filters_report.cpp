#include "tools/filters_report.h"

#include <cmath>
#include <cstdio>

namespace pupwave::cli {

namespace {

void print_filter(std::ostream& os, const char* name, const pups::Filter& f) {
  os << "  " << name << " (" << f.taps.size() << " taps, offset " << f.offset << "):";
  for (double t : f.taps) os << ' ' << fmt(t);
  os << '\n';
}

std::string moments(int m) { return m < 0 ? "unknown" : std::to_string(m); }

// Leaks below 1e-12 are rounding: exact designs print 0.
std::string percent(double x) {
  if (std::isnan(x)) return "unknown";
  return x < 1e-12 ? std::string("0") : fmt(100 * x, 3) + "%";
}

}  // namespace

std::string fmt(double x, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

void print_bank(std::ostream& os, const pups::FilterBank& b, pups::BoundaryRule boundary) {
  os << "weight: " << pups::to_string(b.design.weight);
  if (!b.name.empty()) os << " (preset " << b.name << ")";
  os << "\nspec: pups:" << pups::canonical_spec_body(b, boundary) << '\n';
  os << "refinement error E: " << fmt(b.refinement_error) << '\n';
  os << "extension l: " << b.design.extension << "\nshift: " << b.shift
     << "\northogonality error: " << fmt(b.orthogonality_error) << '\n';
  os << "boundary: "
     << (boundary == pups::BoundaryRule::line_wss ? "whole-sample symmetric line (wss)"
                                                  : "half-sample symmetric wires (hss)")
     << '\n';
  print_filter(os, "P", b.P);
  print_filter(os, "A", b.A);
  print_filter(os, "B", b.B);
  print_filter(os, "Q", b.Q);
}

void print_merit(std::ostream& os, const merit::Merit& m, const merit::MeritOptions& o) {
  os << "figures of merit (AR(1) rho = " << fmt(o.rho, 3) << ", " << o.levels << " levels, N = " << o.n
     << "):\n";
  os << "  coding gain: " << fmt(m.coding_gain_db, 4) << " dB (finite operator, boundaries included), "
     << fmt(m.interior_coding_gain_db, 4) << " dB (bi-infinite filters)\n";
  os << "  condition number (2-norm): " << fmt(m.condition, 4) << " (" << o.levels << " levels), "
     << fmt(m.condition_one_level, 4) << " (one level)\n";
  os << "  coarse band gain per level (worst case):";
  for (double g : m.coarse_gain) os << ' ' << fmt(g, 4);
  os << "\n  coarse band RMS per level (AR(1), unit input):";
  for (double g : m.coarse_rms) os << ' ' << fmt(g, 4);
  os << "\n  vanishing moments: analysis " << moments(m.analysis_moments);
  if (m.analysis_moments >= 0 && m.analysis_residual > 0)
    os << " (next: " << fmt(m.analysis_residual, 2) << ")";
  os << ", synthesis " << moments(m.synthesis_moments);
  if (m.synthesis_moments >= 0 && m.synthesis_residual > 0)
    os << " (next: " << fmt(m.synthesis_residual, 2) << ")";
  os << "\n  DC leak into the details: " << percent(m.dc_leak) << '\n';
  os << "  non-orthogonality (largest |h||g| of a band, orthogonal: 1): " << fmt(m.norm_product, 4) << '\n';
  os << "use: " << use_line(m) << '\n';
}

std::string use_line(const merit::Merit& m) {
  const merit::CodingVerdict v = merit::coding_verdict(m);
  if (v.coding) return v.reason.empty() ? "coding" : "coding (" + v.reason + ")";
  return "curve/surface design only: " + v.reason;
}

std::string merit_summary(const merit::Merit& m) {
  const std::string condition = m.condition > 0 ? ", condition " + fmt(m.condition, 3) : std::string();
  return "coding gain " + fmt(m.coding_gain_db, 4) + " dB" + condition + ", vanishing moments " +
         moments(m.analysis_moments) + "/" + moments(m.synthesis_moments) + ", |h||g| " +
         fmt(m.norm_product, 3) + ", DC leak " + percent(m.dc_leak) + ", coarse gain " +
         (m.coarse_gain.empty() ? std::string("-")
                                : fmt(m.coarse_gain.front(), 3) + ".." + fmt(m.coarse_gain.back(), 3));
}

}  // namespace pupwave::cli

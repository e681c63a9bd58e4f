#pragma once
// Figures of merit of a 1-D two-channel transform for coding: the coding gain of the
// multi-level transform for an AR(1) source, computed from the actual finite operator with
// its boundaries (and, for comparison with published values, from the bi-infinite filters),
// the condition number of the multi-level operator, the coarse band's gain per level and the
// vanishing moments of the analysis and synthesis sides. Works for any Transform1D (PUPs,
// CDF, Kobbelt) from its impulse responses. Definitions and validation: docs/pups.md.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "transforms/transform1d.h"

namespace pupwave::merit {

// What to measure on: a line of n samples, `levels` dyadic levels, an AR(1) source with
// correlation rho between neighbours (rho = 0.95 is the standard figure).
struct MeritOptions {
  std::size_t n = 512;
  int levels = 5;
  double rho = 0.95;
  bool condition = true;  // the multi-level condition number (an n x n SVD) is the slowest part
};

// One filter with the index of its first tap (synthesis: sample index of taps[0] for the
// coefficient at 0; analysis: sample index read by taps[0] for coefficient 0).
struct Taps {
  std::vector<double> c;
  long first = 0;
};

// The single-level filters a transform applies away from the ends: analysis low h0 and high
// h1 (rows), synthesis low g0 and high g1 (columns), read from impulse responses in the
// middle of a long line. Throws std::invalid_argument if the responses are not shift
// invariant there (a transform whose filters are longer than the probe line).
struct InteriorFilters {
  Taps h0, h1, g0, g1;
};
InteriorFilters interior_filters(const Transform1D& t);

// Number of vanishing moments of a filter: the largest m with |sum_t c_t t^k| <= tol *
// sum_t |c_t| |t|^k for k < m (t measured from the filter's centre), at most 12; `residual`
// gets the relative size of the first moment that does not vanish (0 if all 12 do).
int vanishing_moments(const Taps& f, double tol, double* residual);

// Katto-Yasuda generalized coding gain of the bi-infinite `levels`-level filter bank
// (iterated interior filters, no boundaries), in dB: -sum_b eta_b log10(sigma_b^2 |g_b|^2) * 10
// with eta_b the band's share of samples, sigma_b^2 its AR(1) variance, g_b its synthesis filter.
double interior_coding_gain_db(const InteriorFilters& f, int levels, double rho);

// |h_b| |g_b| of the iterated interior filters of every band (details of levels 1..levels,
// then the coarse band): 1 when a band's analysis and synthesis functions are equal up to
// scale, as in an orthogonal bank; the excess is what non-orthogonality costs that band in
// coding gain (10 log10 of its square, at most, for a white band).
std::vector<double> norm_products(const InteriorFilters& f, int levels);

// Everything `filters show` prints about a transform.
struct Merit {
  double coding_gain_db = 0;           // finite operator with boundaries, per coefficient
  double interior_coding_gain_db = 0;  // bi-infinite filters (the published definition)
  double condition = 0;                // 2-norm condition number of the levels-level operator
  double condition_one_level = 0;      // same for one level (min(n, 128) samples)
  // Coarse band after level j (j = 1..levels): largest gain ||C_j x|| / ||x|| over all
  // inputs (the 2-norm of the coarse rows of the j-level operator) ...
  std::vector<double> coarse_gain;
  // ... and its RMS on the AR(1) source (unit variance input).
  std::vector<double> coarse_rms;
  int analysis_moments = 0;   // vanishing moments of the analysis high-pass h1 (-1: unknown)
  int synthesis_moments = 0;  // vanishing moments of the synthesis high-pass g1 (the wavelet)
  double analysis_residual = 0, synthesis_residual = 0;  // first non-vanishing moment, relative
  // Detail of a constant line: |h1 . 1| / |h0 . 1|, the DC leak into the details (NaN: unknown).
  double dc_leak = 0;
  // Largest norm_products entry over the bands (non-orthogonality; 1 for orthogonal banks).
  double norm_product = 0;
};

// Measures all figures; throws std::invalid_argument for n < 2^levels or levels < 1.
Merit figures_of_merit(const Transform1D& t, const MeritOptions& options = {});

// The coding gain alone (finite operator), for searches.
double coding_gain_db(const Transform1D& t, const MeritOptions& options = {});

// Coding gain in dB of any invertible linear transform given as matrices: T (analysis, rows =
// coefficients) and S = T^-1 (synthesis, columns = basis functions), one quantizer per
// coefficient, AR(1) source: -10/n sum_k log10(sigma_k^2 |s_k|^2). Exposed to validate the
// definition on block transforms (the 8-point DCT: 8.83 dB at rho = 0.95).
double finite_coding_gain_db(const Eigen::MatrixXd& T, const Eigen::MatrixXd& S, double rho);

// What a bank is good for, from its figures (rule and calibration in docs/pups.md).
struct CodingVerdict {
  bool coding = false;
  std::string reason;  // why not (or, for coding banks, what to watch); one line
};
CodingVerdict coding_verdict(const Merit& m);

// Thresholds of the verdict: below kMinCodingGainDb every bank measured more than 3 dB
// (BD-PSNR) below OpenJPEG on the test photographs; above it, within 2.1 dB.
inline constexpr double kMinCodingGainDb = 8.0;
inline constexpr double kMaxDcLeak = 0.005;         // details carry more than 0.5% of the mean
inline constexpr double kMaxCoarseGain = 2.0;       // worst-case coarse gain after `levels` levels
inline constexpr double kMaxConditionNumber = 100;  // multi-level 2-norm condition number
inline constexpr double kMaxNormProduct = 1.2;      // CDF 9/7: 1.04, the best PUPs banks 1.03-1.10

}  // namespace pupwave::merit

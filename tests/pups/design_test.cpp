// PUPs filter design: refinement (framework paper Tables 1-3), Algorithm 5.1 (multiresolution
// paper Section 5), presets, specs and serialization.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <vector>

#include "transforms/pups/design.h"
#include "transforms/pups/refinement.h"

namespace pupwave::pups {
namespace {

// Agreement to the printed precision: `printed` has `digits` significant digits.
void expect_printed(double value, double printed, int digits = 6) {
  const double scale = std::pow(10.0, std::floor(std::log10(std::abs(printed))) - digits + 1);
  EXPECT_NEAR(value, printed, 0.5 * scale + 1e-15) << "printed " << printed;
}

void expect_taps(const std::vector<double>& got, const std::vector<double>& printed) {
  ASSERT_EQ(got.size(), printed.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (printed[i] == 0)
      EXPECT_NEAR(got[i], 0.0, 1e-12) << "tap " << i;
    else
      expect_printed(got[i], printed[i]);
  }
}

DesignParams cinpact(WeightKind kind, double c, double sigma) {
  DesignParams p;
  p.weight = kind;
  p.c = c;
  p.sigma = sigma;
  return p;
}

DesignParams polynomial(std::vector<double> coeffs, double lo, double hi) {
  DesignParams p;
  p.weight = WeightKind::polynomial;
  p.coeffs = std::move(coeffs);
  p.domain_lo = lo;
  p.domain_hi = hi;
  return p;
}

TEST(Refinement, BsplinesAreExact) {
  DesignParams p;
  p.degree = 2;
  Refinement r = refine(p);
  expect_taps(r.coeffs, {0.25, 0.75, 0.75, 0.25});
  p.degree = 3;
  r = refine(p);
  ASSERT_EQ(r.coeffs.size(), 5u);
  const double cubic[] = {1, 4, 6, 4, 1};
  for (std::size_t i = 0; i < 5; ++i) EXPECT_NEAR(r.coeffs[i], cubic[i] / 8, 1e-12);
  EXPECT_LT(r.error, 1e-9);
}

TEST(Refinement, PolynomialTable1) {
  Refinement r = refine(polynomial({64, 0, -48, 0, 12, 0, -1}, -2, 2));
  expect_printed(r.error, 0.00784382);
  expect_taps(r.coeffs, {0.218601, 0.487201, 0.593167, 0.487201, 0.218601});
  r = refine(polynomial({0, 0, -125, 75, -15, 1}, 0, 5));
  expect_printed(r.error, 0.00799114);
  expect_taps(r.coeffs, {0.353395, 0.397012, 0.436764, 0.418329, 0.226328, 0.170216});
  r = refine(polynomial({65536, 0, -16384, 0, 1536, 0, -64, 0, 1}, -4, 4));
  expect_printed(r.error, 0.000986008);
  expect_taps(r.coeffs,
              {0.0989794, 0.163489, 0.251154, 0.314675, 0.343853, 0.314675, 0.251154, 0.163489, 0.0989794});
}

TEST(Refinement, InterpolatingCinpactTable2) {
  Refinement r = refine(cinpact(WeightKind::cinpact_interp, 5, 4.79));
  expect_printed(r.error, 0.00353701);
  expect_taps(r.coeffs,
              {0.0240126, 0, -0.129882, 0, 0.606154, 0.99909, 0.606154, 0, -0.129882, 0, 0.0240126});
  r = refine(cinpact(WeightKind::cinpact_interp, 7, 7.77));
  expect_printed(r.error, 0.00119872);
  expect_taps(r.coeffs, {-0.00654163, 0, 0.0402722, 0, -0.145579, 0, 0.611639, 0.999841, 0.611639, 0,
                         -0.145579, 0, 0.0402722, 0, -0.00654163});
}

TEST(Refinement, CinpactTable3) {
  // Support placement: c = 2.5 has width 5 and 6 coefficients, c = 3.684 is extended to 8.
  Refinement r = refine(cinpact(WeightKind::cinpact, 2.5, 6.28));
  expect_printed(r.error, 0.00717758);
  expect_taps(r.coeffs, {0.0232679, 0.339142, 0.638865, 0.638865, 0.339142, 0.0232679});
  r = refine(cinpact(WeightKind::cinpact, 3, 7.27));
  expect_printed(r.error, 0.001974, 4);
  expect_taps(r.coeffs, {0.00561628, 0.206365, 0.482727, 0.610716, 0.482727, 0.206365, 0.00561628});
  r = refine(cinpact(WeightKind::cinpact, 4.5, 14.78));
  expect_printed(r.error, 0.000121679);
  EXPECT_EQ(r.coeffs.size(), 10u);
  r = refine(cinpact(WeightKind::cinpact, 3.684, 17.27));
  expect_printed(r.error, 0.00234953);
  expect_taps(r.coeffs, {0.000624709, 0.0012315, 0.12346, 0.501413, 0.746809, 0.501413, 0.12346, 0.0012315,
                         0.000624709});
}

TEST(Refinement, SigmaSearchFindsTheTableOptimum) {
  // Table 3 lists sigma = 6.28 as the E-minimizing value for c = 2.5 (to two decimals).
  const DesignParams p = cinpact(WeightKind::cinpact, 2.5, 0);
  DesignParams fast = p;
  fast.samples = 20000;
  const double sigma = optimize_sigma(fast, 1, 40);
  EXPECT_NEAR(sigma, 6.28, 0.06);
  DesignParams at = p;
  at.sigma = sigma;
  EXPECT_LE(refine(at).error, 0.00717758 + 1e-6);
}

TEST(Multiresolution, ChaikinMinimalMasks) {
  const std::vector<double> p{0.25, 0.75, 0.75, 0.25};
  const auto all = design_q_all_shifts(p, 0);
  ASSERT_EQ(all.size(), 3u);
  expect_printed(all[0].error, 1.02588);  // E_{-1}, Eq. 55
  expect_taps(all[0].q, {-1.30932, 0.0720339, 0.572034, 0.190678});
  expect_printed(all[2].error, 1.02588);  // E_1, Eq. 56
  expect_taps(all[2].q, {-0.190678, -0.572034, -0.0720339, 1.30932});
  const FilterBank bank = design_bank(p, -1, ExtensionRule{0});
  EXPECT_EQ(bank.shift, 0);
  expect_printed(bank.orthogonality_error, 0.53033, 5);
  expect_taps(bank.Q.taps, {0.25, 0.75, -0.75, -0.25});
  expect_taps(bank.A.taps, {-0.25, 0.75, 0.75, -0.25});
  expect_taps(bank.B.taps, {-0.25, 0.75, -0.75, 0.25});
}

TEST(Multiresolution, ChaikinExtendedByTwo) {
  const FilterBank bank = design_bank({0.25, 0.75, 0.75, 0.25}, -1, ExtensionRule{2});
  expect_printed(bank.orthogonality_error, 0.34716, 5);
  // Eq. 61 prints one of the two mirror-image optima (q reversed and negated).
  const std::vector<double> eq61{-0.0857226, -0.257168, 0.03642, 0.795041, -0.619237, -0.206412};
  ASSERT_EQ(bank.Q.taps.size(), 6u);
  std::vector<double> mirror(6);
  for (std::size_t i = 0; i < 6; ++i) mirror[i] = -eq61[5 - i];
  const bool direct = std::abs(bank.Q.taps[0] - eq61[0]) < 1e-5;
  expect_taps(bank.Q.taps, direct ? eq61 : mirror);
}

TEST(Multiresolution, InterpolatingCinpactMinimalQ) {
  const FilterBank bank = design_preset("cinpact-interp-c5");
  EXPECT_EQ(bank.shift, -1);  // "the result of a shift using E_{-1}"
  // Section 5.4 prints the 11 leading taps (its "-0.779710.36458" is -0.77971, 0.36458);
  // the 12th tap (P was padded to even length) is zero to rounding.
  ASSERT_EQ(bank.Q.taps.size(), 12u);
  EXPECT_NEAR(bank.Q.taps[11], 0.0, 1e-12);
  expect_taps({bank.Q.taps.begin(), bank.Q.taps.end() - 1},
              {0.00876249, 0, -0.0473956, 0, -0.779718, 0.36458, 0.221193, 0, -0.0473956, 0, 0.00876249});
  expect_printed(bank.refinement_error, 0.00353701);
}

TEST(Multiresolution, CirculantIdentitiesForAllPresets) {
  for (const auto& preset : presets()) {
    const FilterBank bank = design_preset(preset.name);
    const int n0 = min_circulant_size(bank);
    for (int n : {n0, n0 + 1, n0 + 7, 2 * n0 + 3})
      EXPECT_LT(circulant_identity_error(bank, n), 1e-12) << preset.name << " n=" << n;
  }
}

TEST(Multiresolution, ThresholdStopsAtTheFirstGoodExtension) {
  const FilterBank a = design_preset("cinpact-interp-c5");
  ExtensionRule rule;
  rule.threshold = 0.1;
  const FilterBank b = design_bank(a.P.taps, a.P.offset, rule);
  EXPECT_LE(b.orthogonality_error, 0.1);
  const FilterBank before = design_bank(a.P.taps, a.P.offset, ExtensionRule{b.design.extension - 2});
  EXPECT_GT(before.orthogonality_error, 0.1);
  EXPECT_LT(b.orthogonality_error, a.orthogonality_error);
}

TEST(Multiresolution, ExtendedInterpolatingDesignIsFast) {
  const auto t0 = std::chrono::steady_clock::now();
  const FilterBank bank = design_preset("cinpact-interp-c5-ext");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(bank.design.extension, 32);
  EXPECT_LT(bank.orthogonality_error, 0.01);
  EXPECT_LT(seconds, 1.0);
  RecordProperty("design_seconds", std::to_string(seconds));
}

TEST(FilterBankData, BytesRoundTripBitExactly) {
  for (const auto& preset : presets()) {
    const FilterBank bank = design_preset(preset.name);
    EXPECT_EQ(filter_bank_from_bytes(to_bytes(bank)), bank);
  }
}

TEST(FilterBankData, MalformedBytesThrow) {
  const std::vector<std::uint8_t> good = to_bytes(design_preset("chaikin"));
  for (std::size_t cut = 0; cut < good.size(); ++cut) {
    std::vector<std::uint8_t> bad(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut));
    EXPECT_THROW(filter_bank_from_bytes(bad), std::invalid_argument) << "cut " << cut;
  }
  std::vector<std::uint8_t> extra = good;
  extra.push_back(0);
  EXPECT_THROW(filter_bank_from_bytes(extra), std::invalid_argument);
  std::vector<std::uint8_t> huge = good;
  huge[8] = 0x7f;  // top byte of the name length (bytes 5..8): claims a 2 GB name
  EXPECT_THROW(filter_bank_from_bytes(huge), std::invalid_argument);
}

TEST(Specs, ParseAndCanonicalFormRoundTrip) {
  const FilterBank a = design(parse_design_spec("cinpact-interp(c=5,sigma=4.79,l=4)"));
  EXPECT_EQ(canonical_spec_body(a), "cinpact-interp(c=5,sigma=4.79,l=4)");
  EXPECT_EQ(design(parse_design_spec(canonical_spec_body(a))), a);
  const FilterBank b = design(parse_design_spec("polynomial(coeffs=64:0:-48:0:12:0:-1,domain=-2:2,t=0.5)"));
  EXPECT_LE(b.orthogonality_error, 0.5);
  EXPECT_EQ(design(parse_design_spec(canonical_spec_body(b))), b);
  EXPECT_EQ(canonical_spec_body(design(parse_design_spec("chaikin"))), "chaikin");
  EXPECT_EQ(design(parse_design_spec("bspline(degree=2)")).Q.taps, design_preset("chaikin").Q.taps);
}

TEST(Specs, BadSpecsThrowInvalidArgument) {
  for (const char* bad : {"", "nonsense", "bspline", "bspline(", "bspline(degree=x)", "bspline(degree=3,l=3)",
                          "bspline(degree=3,l=2,t=1)", "cinpact(c=3)", "cinpact(c=3,sigma=7,foo=1)",
                          "bspline(degree=3,degree=2)", "polynomial(coeffs=1:2,domain=1)", "given(p=1)",
                          "cinpact(c=-1,sigma=2)"})
    EXPECT_THROW(design(parse_design_spec(bad)), std::invalid_argument) << bad;
}

}  // namespace
}  // namespace pupwave::pups

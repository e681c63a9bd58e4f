// Design search pieces: vanishing-moment masks, polynomial weights refining to them, sigmas
// without DC leak, interpolating designs whose support ends on an even index, candidates.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "transforms/analysis/merit.h"
#include "transforms/pups/design.h"
#include "transforms/pups/mask_weight.h"
#include "transforms/pups/pups_transform.h"
#include "transforms/pups/refinement.h"
#include "transforms/pups/search.h"

namespace pupwave::pups {
namespace {

// sum_t (-1)^t p_t t^k: zero for k < m when B = alternating flip of P has m vanishing moments.
double alternating_moment(const std::vector<double>& p, int first, int k) {
  double m = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int t = first + static_cast<int>(i);
    m += (t % 2 == 0 ? 1.0 : -1.0) * p[i] * std::pow(t, k);
  }
  return m;
}

TEST(Masks, VanishingMomentMaskHasItsMoments) {
  const std::vector<double> p = vanishing_moment_mask(4, 2.75);
  ASSERT_EQ(p.size(), 7u);
  double sum = 0;
  for (double v : p) sum += v;
  EXPECT_NEAR(sum, 2, 1e-15);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(alternating_moment(p, -3, k), 0, 1e-14) << k;
  EXPECT_GT(std::abs(alternating_moment(p, -3, 4)), 0.1);
  EXPECT_THROW(vanishing_moment_mask(3, 1), std::invalid_argument);
}

TEST(Masks, PolynomialWeightRefinesToTheMask) {
  const std::vector<double> mask = vanishing_moment_mask(4, 2.75);
  const MaskWeight w = polynomial_weight_for_mask(mask, 16, 20000);
  EXPECT_LE(w.max_tap_error, 1e-11);
  const Refinement r = refine(w.params);
  double sum = 0;
  for (double v : r.coeffs) sum += v;
  ASSERT_EQ(r.coeffs.size(), mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) EXPECT_NEAR(2 * r.coeffs[i] / sum, mask[i], 1e-11);
  EXPECT_THROW(polynomial_weight_for_mask({1, 2, 1, 3}, 16), std::invalid_argument);
}

TEST(Masks, PresetPoly16RefinesToTheMaximalCodingGainMask) {
  const FilterBank bank = design_preset("poly16-vm4-cg");
  const std::vector<double> mask = vanishing_moment_mask(4, 2.75);
  double sum = 0;
  for (double v : bank.P.taps) sum += v;
  ASSERT_EQ(bank.P.taps.size(), mask.size());
  for (std::size_t i = 0; i < mask.size(); ++i) EXPECT_NEAR(2 * bank.P.taps[i] / sum, mask[i], 1e-10);
  const merit::Merit m = merit::figures_of_merit(*make_pups_transform_from_spec("poly16-vm4-cg"));
  EXPECT_EQ(m.analysis_moments, 4);
  EXPECT_GT(m.coding_gain_db, 9.8);
}

TEST(Search, LeakFreeSigmaZeroesTheDetailOfAConstant) {
  DesignParams p;
  p.weight = WeightKind::cinpact_interp;
  p.c = 5;
  p.samples = 20000;
  const std::vector<double> sigmas = leak_free_sigmas(p, 1.0, 20.0);
  ASSERT_FALSE(sigmas.empty());
  for (double s : sigmas) {
    p.sigma = s;
    const Refinement r = refine(p);
    EXPECT_NEAR(alternating_moment(r.coeffs, r.first, 0), 0, 1e-10) << s;
  }
}

TEST(Search, InterpolatingSupportEndingOnAnEvenIndexDesigns) {
  // c = 5.5: support [-6, 6], whose even end taps are hard zeros; trimmed, the bank designs.
  const FilterBank bank = design(parse_design_spec("cinpact-interp(c=5.5,sigma=6,l=8)"));
  EXPECT_EQ(bank.P.taps.size(), 11u);
  EXPECT_NE(bank.P.taps.front(), 0.0);
}

TEST(Search, CandidatesAreCanonicalSpecBodies) {
  SearchSpace s;
  s.weight = WeightKind::bspline;
  s.degrees = {1, 2};
  s.extensions = {0, 8};
  s.boundaries = {BoundaryRule::wire_hss, BoundaryRule::line_wss};
  s.samples = 2000;
  const std::vector<std::string> c = search_candidates(s);
  ASSERT_EQ(c.size(), 8u);
  EXPECT_EQ(c[0], "bspline(degree=1,samples=2000,l=0)");
  EXPECT_EQ(c[1], "bspline(degree=1,samples=2000,l=0,boundary=wss)");
  for (const auto& body : c) EXPECT_EQ(make_pups_transform_from_spec(body)->spec(), "pups:" + body);
  s.extensions = {3};
  EXPECT_THROW(search_candidates(s), std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::pups

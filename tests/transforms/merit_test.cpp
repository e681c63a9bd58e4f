// Figures of merit (transforms/analysis/merit.h) checked against values known independently:
// the 2-point and 8-point DCT coding gains of an AR(1) source, CDF 9/7 and 5/3 computed from
// the ISO 15444-1 filter taps by a separate program, vanishing moments of the CDF banks, and
// the invariance of the coding gain under rescaling a band (why renormalising does not help).
#include "transforms/analysis/merit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>

#include "transforms/spec.h"

namespace pupwave::merit {
namespace {

// Block-diagonal orthonormal DCT-II of block size b on n samples.
Eigen::MatrixXd block_dct(int n, int b) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  for (int blk = 0; blk < n; blk += b)
    for (int k = 0; k < b; ++k)
      for (int i = 0; i < b; ++i)
        T(blk + k, blk + i) = (k == 0 ? std::sqrt(1.0 / b) : std::sqrt(2.0 / b)) *
                              std::cos(std::numbers::pi * (2 * i + 1) * k / (2.0 * b));
  return T;
}

TEST(CodingGain, BlockDctMatchesTheTextbookValues) {
  // 2-point (the Haar/KLT pair): 10 log10(1 / sqrt(1 - rho^2)) = 5.05 dB at rho = 0.95.
  const Eigen::MatrixXd T2 = block_dct(256, 2);
  EXPECT_NEAR(finite_coding_gain_db(T2, T2.transpose(), 0.95),
              10 * std::log10(1 / std::sqrt(1 - 0.95 * 0.95)), 1e-9);
  // 8-point DCT at rho = 0.95: 8.83 dB (Jayant & Noll, Digital Coding of Waveforms, 1984).
  const Eigen::MatrixXd T8 = block_dct(256, 8);
  EXPECT_NEAR(finite_coding_gain_db(T8, T8.transpose(), 0.95), 8.83, 0.005);
}

TEST(CodingGain, CdfBanksMatchAnIndependentComputationFromTheStandardTaps) {
  // Katto-Yasuda gain of the 5-level tree of the ISO 15444-1 Table F.4 / F.5 filters, computed
  // separately (numpy, docs/pups.md): 9/7 9.870 dB, 5/3 9.587 dB; one level 5.916 / 6.277 dB.
  const InteriorFilters f97 = interior_filters(*make_transform("cdf97"));
  const InteriorFilters f53 = interior_filters(*make_transform("cdf53"));
  EXPECT_NEAR(interior_coding_gain_db(f97, 5, 0.95), 9.870, 0.001);
  EXPECT_NEAR(interior_coding_gain_db(f53, 5, 0.95), 9.587, 0.001);
  EXPECT_NEAR(interior_coding_gain_db(f97, 1, 0.95), 5.916, 0.001);
  EXPECT_NEAR(interior_coding_gain_db(f53, 1, 0.95), 6.277, 0.001);
  // The finite operator loses a little at the boundaries (N = 512, 5 levels).
  const Merit m = figures_of_merit(*make_transform("cdf97"));
  EXPECT_LT(m.coding_gain_db, m.interior_coding_gain_db);
  EXPECT_GT(m.coding_gain_db, m.interior_coding_gain_db - 0.05);
}

TEST(Merit, CdfVanishingMomentsAndOrthogonality) {
  const Merit m97 = figures_of_merit(*make_transform("cdf97"));
  EXPECT_EQ(m97.analysis_moments, 4);
  EXPECT_EQ(m97.synthesis_moments, 4);
  EXPECT_LT(m97.dc_leak, 1e-12);
  EXPECT_NEAR(m97.norm_product, 1.04, 0.01);  // nearly orthogonal
  EXPECT_LT(m97.condition, 20);
  ASSERT_EQ(m97.coarse_gain.size(), 5u);
  const Merit m53 = figures_of_merit(*make_transform("cdf53"));
  EXPECT_EQ(m53.analysis_moments, 2);
  EXPECT_EQ(m53.synthesis_moments, 2);
  EXPECT_TRUE(coding_verdict(m97).coding);
}

// A transform with its coarse band multiplied by `k` after every analysis level.
class ScaledCoarse final : public Transform1D {
 public:
  ScaledCoarse(Transform1DPtr t, double k) : t_(std::move(t)), k_(k) {}
  std::string spec() const override { return t_->spec() + "*"; }
  void analyze(std::span<double> x) const override {
    t_->analyze(x);
    for (std::size_t i = 0; i < (x.size() + 1) / 2 && x.size() > 1; ++i) x[i] *= k_;
  }
  void synthesize(std::span<double> x) const override {
    for (std::size_t i = 0; i < (x.size() + 1) / 2 && x.size() > 1; ++i) x[i] /= k_;
    t_->synthesize(x);
  }
  void analyze(std::span<float>) const override {}
  void synthesize(std::span<float>) const override {}

 private:
  Transform1DPtr t_;
  double k_;
};

TEST(CodingGain, RenormalisingTheCoarseBandPerLevelChangesNothing) {
  const Transform1DPtr t = make_transform("pups:cinpact-c3");
  MeritOptions o;
  o.condition = false;
  EXPECT_NEAR(coding_gain_db(ScaledCoarse(t, 0.2), o), coding_gain_db(*t, o), 1e-9);
}

}  // namespace
}  // namespace pupwave::merit

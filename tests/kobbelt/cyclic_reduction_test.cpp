// Cyclic reduction as lifting against a direct banded solve (Eigen SparseLU).
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <cmath>
#include <random>
#include <vector>

#include "transforms/kobbelt/cyclic_reduction.h"
#include "transforms/kobbelt/variational.h"

namespace pupwave::kobbelt {
namespace {

Eigen::VectorXd direct_solve(const Tridiagonal& a, const Eigen::VectorXd& b) {
  const auto m = static_cast<Eigen::Index>(a.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index j = 0; j < m; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    entries.emplace_back(j, j, a.diag[uj]);
    if (j > 0) entries.emplace_back(j, j - 1, a.sub[uj]);
    if (j + 1 < m) entries.emplace_back(j, j + 1, a.super[uj]);
  }
  Eigen::SparseMatrix<double> mat(m, m);
  mat.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(mat);
  EXPECT_EQ(lu.info(), Eigen::Success);
  return lu.solve(b);
}

double max_abs(const Eigen::VectorXd& v) { return v.size() == 0 ? 0.0 : v.cwiseAbs().maxCoeff(); }

// Every scheme, every number of unknowns 1..1000, both fine-line parities (odd lines have
// coarse samples at both ends, even lines end on an extrapolated odd sample).
TEST(CyclicReduction, MatchesDirectBandedSolveForAllSizes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl, Scheme::k4pt}) {
    for (std::size_t m = 1; m <= 1000; ++m) {
      for (std::size_t n : {2 * m, 2 * m + 1}) {
        const EulerLagrangeSystem el = euler_lagrange_system(s, n);
        ASSERT_EQ(el.a.size(), m);
        Eigen::VectorXd b(static_cast<Eigen::Index>(m));
        for (auto& v : b) v = uni(rng);
        const Eigen::VectorXd expected = direct_solve(el.a, b);
        std::vector<double> x(b.begin(), b.end());
        const CyclicReduction cr(el.a);
        cr.solve(std::span<double>(x));
        const Eigen::VectorXd got = Eigen::Map<const Eigen::VectorXd>(x.data(), b.size());
        ASSERT_LE(max_abs(got - expected), 1e-12 * std::max(1.0, max_abs(expected)))
            << scheme_name(s) << " n=" << n;
      }
    }
  }
}

// The inverted network multiplies by A (to the truncation of CR at machine precision).
TEST(CyclicReduction, InvertedNetworkMultipliesByA) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl}) {
    for (std::size_t n : {3u, 10u, 101u, 512u, 2049u}) {
      const EulerLagrangeSystem el = euler_lagrange_system(s, n);
      const std::size_t m = el.a.size();
      std::vector<double> x(m), ax(m);
      for (auto& v : x) v = uni(rng);
      for (std::size_t j = 0; j < m; ++j) {
        ax[j] = el.a.diag[j] * x[j] + (j > 0 ? el.a.sub[j] * x[j - 1] : 0.0) +
                (j + 1 < m ? el.a.super[j] * x[j + 1] : 0.0);
      }
      const CyclicReduction cr(el.a);
      cr.multiply(std::span<double>(x));
      for (std::size_t j = 0; j < m; ++j) ASSERT_NEAR(x[j], ax[j], 1e-13) << n << " " << j;
    }
  }
}

// The recursion stops when the reduced matrix is diagonal to machine precision; for K2 the
// paper's argument (digits double per level) bounds it by ceil(log2 53) = 6 levels.
TEST(CyclicReduction, StopsAfterLogarithmicallyManyLevels) {
  for (Scheme s : {Scheme::k2, Scheme::k3, Scheme::kspl}) {
    const CyclicReduction cr(euler_lagrange_system(s, 1u << 20).a);
    EXPECT_LE(cr.levels(), 6u) << scheme_name(s);
    EXPECT_GE(cr.levels(), 3u) << scheme_name(s);
  }
  // K4pt is stationary (A = I inside); only the boundary rows need reduction.
  const CyclicReduction cr4(euler_lagrange_system(Scheme::k4pt, 1u << 20).a);
  EXPECT_LE(cr4.levels(), 6u);
}

TEST(CyclicReduction, RejectsSingularSystems) {
  Tridiagonal a{{0, 1}, {1, 1}, {1, 0}};  // [[1, 1], [1, 1]]
  EXPECT_THROW(CyclicReduction{a}, std::domain_error);
  Tridiagonal bad{{0}, {1, 1}, {0, 0}};
  EXPECT_THROW(CyclicReduction{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace pupwave::kobbelt

// Section 8 boundary curves: the filters built by local least squares reproduce the published
// B (Eq. 8.1) and Q (Eq. 8.2) values, every loop length reconstructs exactly, and the boundary
// of a subdivided real mesh follows Kobbelt's every-other-step rule, checked against an
// implementation written here from the rule alone.
#include <gtest/gtest.h>

#include <map>

#include "tests/sqrt3/fixtures.h"
#include "tests/sqrt3/real_meshes.h"
#include "transforms/sqrt3/boundary_curve.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::sqrt3 {
namespace {

constexpr double kDen1 = 6124761750733245.0, kDen2 = 680529083414805.0;
// b_1 .. b_12 of Eq. 8.1.
const double kPaperB[12] = {
    -360908824401952.0 / kDen1,     821150352767744.0 / kDen1,        324486832948544.0 / kDen1,
    -227763072235964.0 / kDen2,     276752921024.0 / 1311231374595.0, 34302231721304.0 / kDen2,
    -149920452798584.0 / kDen1,     -412135978326626.0 / kDen1,       276003571289944.0 / kDen1,
    -1740361028.0 / 513090537885.0, -4404178928.0 / 513090537885.0,   1935707674.0 / 513090537885.0};
// q_1 .. q_5 of Eq. 8.2.
const double kPaperQ[5] = {11710197.0 / 17758786.0, 13321692.0 / 8879393.0, 1.0, 11774114.0 / 8879393.0,
                           -39839315.0 / 17758786.0};

TEST(Sqrt3Boundary, LocalLeastSquaresReproducesEq81And82) {
  const CurveStencils& s = curve_stencils();
  // d_{k-1} = sum_{l=-7}^{4} b_{5-l} f_{k+l};  d_{k+1} = sum_{l=-4}^{7} b_{5+l} f_{k+l}.
  for (int l = -7; l <= 4; ++l) EXPECT_NEAR(s.b_before[std::size_t(l + 7)], kPaperB[5 - l - 1], 1e-14) << l;
  for (int l = -4; l <= 7; ++l) EXPECT_NEAR(s.b_after[std::size_t(l + 4)], kPaperB[5 + l - 1], 1e-14) << l;
  // e_{k-1} = q2 d_{k-2} + q3 d_{k-1} + q5 d_{k+1}; e_{k+1} = q5 d_{k-1} + q3 d_{k+1} + q2 d_{k+2};
  // e_k = q1 d_{k-2} + q4 d_{k-1} + q4 d_{k+1} + q1 d_{k+2}: the Q columns read off these rows.
  const double q_after[5] = {kPaperQ[4], kPaperQ[3], kPaperQ[2], kPaperQ[1], kPaperQ[0]};
  const double q_before[5] = {kPaperQ[0], kPaperQ[1], kPaperQ[2], kPaperQ[3], kPaperQ[4]};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(s.q_after[std::size_t(i)], q_after[i], 1e-13) << i;
    EXPECT_NEAR(s.q_before[std::size_t(i)], q_before[i], 1e-13) << i;
  }
  // The A row (Fig. 18, whose values the text does not print): minimum norm, exact rationals.
  const double a477[9] = {109, -248, -98, 244, 463, 244, -98, -248, 109};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(s.a[std::size_t(i)], a477[i] / 477.0, 1e-14) << i;
  EXPECT_EQ(build_curve_filters(12).t_width, 3);  // T of width 0..2 is inconsistent (Sec. 7 rule)
}

TEST(Sqrt3Boundary, EveryLoopLengthReconstructsExactly) {
  for (std::size_t m = 3; m <= 24; ++m) {
    std::vector<Vec3> fine(3 * m), coarse(m), details(2 * m), back(3 * m);
    test::perturb(fine, 1.0, unsigned(m));
    const CurveFilters f(m);
    f.analyse(fine, coarse, details);
    f.synthesise(coarse, details, back);
    EXPECT_LT(test::max_distance(fine, back), 1e-13) << m;
    // A P = I: the reversal of a subdivided loop is the loop itself, with zero details.
    std::vector<Vec3> again(m);
    f.analyse(curve_subdivide(coarse), again, details);
    EXPECT_LT(test::max_distance(coarse, again), 1e-13) << m;
    for (const Vec3& d : details) EXPECT_LT(d.norm(), 1e-13) << m;
  }
  EXPECT_FALSE(build_curve_filters(3).local);  // 3 points: the local Q is not unique
  for (std::size_t m = 4; m <= 12; ++m) EXPECT_TRUE(build_curve_filters(m).local) << m;
}

// Kobbelt's rule written out independently: boundary loops from the directed edges, then the
// ternary cubic B-spline masks 4 19 4, 1 16 10 and 10 16 1 (over 27).
std::vector<std::vector<std::uint32_t>> boundary_loops(const TriMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Face& f : m.faces)
    for (int j = 0; j < 3; ++j) directed[{f[std::size_t(j)], f[std::size_t((j + 1) % 3)]}] = 1;
  std::map<std::uint32_t, std::uint32_t> next;
  for (const auto& [e, one] : directed)
    if (!directed.count({e.second, e.first})) next[e.first] = e.second;
  std::vector<std::vector<std::uint32_t>> loops;
  std::map<std::uint32_t, bool> seen;
  for (const auto& [start, unused] : next) {
    if (seen[start]) continue;
    std::vector<std::uint32_t> loop;
    for (std::uint32_t v = start; !seen[v]; v = next[v]) {
      seen[v] = true;
      loop.push_back(v);
    }
    loops.push_back(loop);
  }
  return loops;
}

TEST(Sqrt3Boundary, SubdividedRealMeshFollowsKobbeltsBoundaryRule) {
  for (const char* name : test::kOpenMeshes) {
    const TriMesh base = test::real_mesh(name);
    const TriMesh one = subdivide(base, 1), two = subdivide(base, 2);
    std::map<std::uint32_t, std::uint32_t> next_fine;
    for (const auto& loop : boundary_loops(two))
      for (std::size_t i = 0; i < loop.size(); ++i) next_fine[loop[i]] = loop[(i + 1) % loop.size()];
    std::size_t checked = 0;
    for (const auto& loop : boundary_loops(base)) {
      const std::size_t m = loop.size();
      for (std::size_t i = 0; i < m; ++i) {
        const Vec3& a = base.points[loop[(i + m - 1) % m]];
        const Vec3& b = base.points[loop[i]];
        const Vec3& c = base.points[loop[(i + 1) % m]];
        const Vec3& d = base.points[loop[(i + 2) % m]];
        EXPECT_LT((one.points[loop[i]] - b).norm(), 1e-15) << name;  // first (plain) step keeps it
        const std::uint32_t pl = next_fine[loop[i]], pr = next_fine[pl];
        ASSERT_EQ(next_fine[pr], loop[(i + 1) % m]) << name;  // every edge trisected
        EXPECT_LT((two.points[loop[i]] - (4 * a + 19 * b + 4 * c) / 27).norm(), 1e-13) << name;
        EXPECT_LT((two.points[pl] - (a + 16 * b + 10 * c) / 27).norm(), 1e-13) << name;
        EXPECT_LT((two.points[pr] - (10 * b + 16 * c + d) / 27).norm(), 1e-13) << name;
        ++checked;
      }
    }
    EXPECT_GT(checked, 30u) << name;
  }
}

}  // namespace
}  // namespace pupwave::sqrt3

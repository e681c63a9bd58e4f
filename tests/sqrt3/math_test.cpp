// sqrt(3) math on synthetic meshes: the closed-form filters, exact reconstruction for every
// valence 3..12 and on boundaries, structure recovery.
#include <gtest/gtest.h>

#include "tests/sqrt3/fixtures.h"
#include "transforms/sqrt3/hierarchy.h"
#include "transforms/sqrt3/reversal.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::sqrt3 {
namespace {

using test::bipyramid;
using test::disk;
using test::grid;
using test::max_distance;
using test::perturb;
using test::torus;

TEST(Sqrt3Alpha, KobbeltValues) {
  EXPECT_NEAR(alpha(6), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(alpha(3), 5.0 / 9.0, 1e-15);
  EXPECT_NEAR(alpha(4), 4.0 / 9.0, 1e-15);
}

// Eq. 5.4/5.5 solve the row system (5.3): column k gives 1, each neighbour column 0, and
// the local least-squares solver finds the same row for every valence.
TEST(Sqrt3Reversal, ClosedFormIsTheMinimumNormLocalRow) {
  for (std::uint32_t n = 3; n <= 12; ++n) {
    const TriMesh m = bipyramid(n);
    const Topology t(m.points.size(), m.faces);
    const Refinement r = refine(t, StepKind::plain);
    const std::size_t apex = n;
    ASSERT_EQ(t.valence(apex), n);
    const double a = reversal_a(n), h = reversal_h(n), al = alpha(n);
    EXPECT_NEAR((1 - al) * a + n * h / 3.0, 1.0, 1e-14) << n;
    EXPECT_NEAR(al / n * a + 2.0 * h / 3.0, 0.0, 1e-14) << n;
    const ReversalRow row = local_reversal_row(t, r, apex);
    EXPECT_TRUE(row.closed_form);
    EXPECT_NEAR(row.home, a, 1e-12) << n;
    for (double w : row.weights) EXPECT_NEAR(w, h, 1e-12) << n;
  }
}

void expect_exact_two_levels(const TriMesh& base, const char* what) {
  TriMesh fine = subdivide(base, 2);
  perturb(fine.points, 0.05, 7);
  const Multiresolution mr = decompose(fine, 2);
  const TriMesh back = reconstruct(mr, 0);
  ASSERT_EQ(back.points.size(), fine.points.size()) << what;
  EXPECT_LT(max_distance(back.points, fine.points), 1e-12 * mesh_scale(fine.points)) << what;
}

TEST(Sqrt3Multiresolution, ExactForValences3To12) {
  for (std::uint32_t n = 3; n <= 12; ++n) expect_exact_two_levels(bipyramid(n), "bipyramid");
}

TEST(Sqrt3Multiresolution, ExactWithBoundaries) {
  for (std::uint32_t n = 3; n <= 12; ++n) expect_exact_two_levels(disk(n), "disk");
  expect_exact_two_levels(grid(4, 3), "grid");
  expect_exact_two_levels(grid(1, 1), "grid 1x1");
}

TEST(Sqrt3Multiresolution, SubdividedMeshDecomposesToItsBase) {
  for (const TriMesh& base : {torus(3, 1, 8, 6), disk(7), grid(3, 3), bipyramid(5)}) {
    const TriMesh fine = subdivide(base, 3);
    const Multiresolution mr = decompose(fine, 3);
    EXPECT_LT(max_distance(mr.coarsest.points, base.points), 1e-12 * mesh_scale(base.points));
    for (const Sqrt3Level& l : mr.levels)
      for (const Vec3& d : l.details) EXPECT_LT(d.norm(), 1e-12 * mesh_scale(base.points));
  }
}

}  // namespace
}  // namespace pupwave::sqrt3

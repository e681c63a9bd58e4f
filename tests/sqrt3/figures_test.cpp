// The seed's results (Section 9) on real meshes, made numbers:
//   Fig. 21: subdivided twice, decomposed twice: the original coarse mesh, details zero.
//   Fig. 22: the same with every vertex randomly perturbed: reconstruction is exact, and the
//            coarse mesh stays close to the unperturbed one (RMS and max deviation against the
//            perturbation size).
//   Fig. 23: a torus sampled from its parametric equation, four decompositions: distance of
//            every coarse level's vertices to the true torus, relative to the minor radius.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "tests/sqrt3/fixtures.h"
#include "tests/sqrt3/real_meshes.h"
#include "transforms/sqrt3/hierarchy.h"
#include "transforms/sqrt3/subdivide.h"

namespace pupwave::sqrt3 {
namespace {

std::vector<const char*> all_meshes() {
  std::vector<const char*> v(std::begin(test::kClosedMeshes), std::end(test::kClosedMeshes));
  v.insert(v.end(), std::begin(test::kOpenMeshes), std::end(test::kOpenMeshes));
  return v;
}

double diagonal(const std::vector<Vec3>& p) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& x : p) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

TEST(Sqrt3Figures, Fig21SubdividedTwiceDecomposesToTheOriginal) {
  for (const char* name : all_meshes()) {
    const TriMesh base = test::real_mesh(name);
    const double size = mesh_scale(base.points);
    const Multiresolution mr = decompose(subdivide(base, 2), 2);
    const double coarse_error = test::max_distance(mr.coarsest.points, base.points);
    double detail = 0;
    for (const Sqrt3Level& l : mr.levels)
      for (const Vec3& d : l.details) detail = std::max(detail, d.norm());
    std::printf("Fig. 21 %-14s max |c - original| / size = %.2e, max |detail| / size = %.2e\n", name,
                coarse_error / size, detail / size);
    EXPECT_LT(coarse_error, 1e-12 * size) << name;
    EXPECT_LT(detail, 1e-12 * size) << name;
  }
}

TEST(Sqrt3Figures, Fig22PerturbedMeshIsExactAndItsCoarseMeshStaysClose) {
  for (const char* name : all_meshes()) {
    const TriMesh base = test::real_mesh(name);
    TriMesh fine = subdivide(base, 2);
    const std::vector<Vec3> clean = fine.points;
    const double delta = 0.01 * diagonal(base.points);  // each coordinate moved by up to delta
    test::perturb(fine.points, delta, 2024);
    double rms_in = 0, max_in = 0;
    for (std::size_t i = 0; i < clean.size(); ++i) {
      rms_in += (fine.points[i] - clean[i]).squaredNorm();
      max_in = std::max(max_in, (fine.points[i] - clean[i]).norm());
    }
    rms_in = std::sqrt(rms_in / double(clean.size()));
    const Multiresolution mr = decompose(fine, 2);
    const double exact = test::max_distance(reconstruct(mr, 0).points, fine.points);
    double rms = 0, worst = 0;
    for (std::size_t i = 0; i < base.points.size(); ++i) {
      rms += (mr.coarsest.points[i] - base.points[i]).squaredNorm();
      worst = std::max(worst, (mr.coarsest.points[i] - base.points[i]).norm());
    }
    rms = std::sqrt(rms / double(base.points.size()));
    std::printf(
        "Fig. 22 %-14s |rec - f| / size = %.1e; perturbation rms %.3g max %.3g; coarse deviation rms %.3g "
        "(%.2f x) max %.3g (%.2f x)\n",
        name, exact / mesh_scale(fine.points), rms_in, max_in, rms, rms / rms_in, worst, worst / max_in);
    EXPECT_LT(exact, 1e-12 * mesh_scale(fine.points)) << name;
    // Stability as numbers. The reversal (5.4-5.6) amplifies independent noise by its row norm
    // sqrt(a^2 + n h^2) per level: 2.04 at valence 6, 3.16 at 4, 6.67 at 3, so two levels give
    // about 4.2 on regular meshes, more where valence-3 vertices sit (u.off). Measured ratios
    // (seed 2024) are in docs/sqrt3.md; the bounds are 1.25 x those, so a less stable
    // reversal fails.
    const bool has_valence_3 = std::string(name) == "u.off";
    EXPECT_LT(rms / rms_in, has_valence_3 ? 13.3 : 5.9) << name;
    EXPECT_LT(worst / max_in, has_valence_3 ? 43.5 : 12.3) << name;
  }
}

// Torus connectivity refined four times by sqrt(3); every vertex keeps its (u, v) parameters
// (a face point takes the centroid of its corners' parameters, unwrapped), and all positions are
// sampled from the parametric equation (Section 9), so the fine mesh lies exactly on the torus.
TriMesh sampled_torus(double R, double r, int levels) {
  const std::uint32_t nu = 12, nv = 8;
  TriMesh m = test::torus(R, r, nu, nv);
  std::vector<Eigen::Vector2d> uv;
  for (std::uint32_t i = 0; i < nu; ++i)
    for (std::uint32_t j = 0; j < nv; ++j)
      uv.push_back({2 * std::numbers::pi * i / nu, 2 * std::numbers::pi * j / nv});
  auto unwrap = [](double a, double ref) {
    return a + 2 * std::numbers::pi * std::round((ref - a) / (2 * std::numbers::pi));
  };
  for (int l = 0; l < levels; ++l) {
    const Topology t(m.points.size(), m.faces);
    const Refinement ref = refine(t, StepKind::plain);
    uv.resize(ref.fine_vertices());
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      const Eigen::Vector2d& a = uv[m.faces[f][0]];
      Eigen::Vector2d sum = a;
      for (int k = 1; k < 3; ++k) {
        const Eigen::Vector2d& b = uv[m.faces[f][std::size_t(k)]];
        sum += Eigen::Vector2d(unwrap(b.x(), a.x()), unwrap(b.y(), a.y()));
      }
      uv[ref.face_point[f]] = sum / 3;
    }
    m.faces = ref.faces;
    m.points.resize(uv.size());
  }
  for (std::size_t i = 0; i < uv.size(); ++i) m.points[i] = test::torus_point(R, r, uv[i].x(), uv[i].y());
  return m;
}

double torus_distance(const Vec3& p, double R, double r) {
  return std::abs(std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r);
}

TEST(Sqrt3Figures, Fig23TorusStaysOnTheTorusThroughFourDecompositions) {
  const double R = 1.0, r = 0.4;
  const TriMesh fine = sampled_torus(R, r, 4);
  const Multiresolution mr = decompose(fine, 4);
  EXPECT_LT(test::max_distance(reconstruct(mr, 0).points, fine.points), 1e-12);
  // Measured: max distance / r = 0.0065, 0.0260, 0.0846, 0.2630 at levels 1-4 (docs/sqrt3.md);
  // the bounds are 1.25 x those, so a less stable reversal fails.
  const double bound[5] = {1e-12, 0.0081, 0.0325, 0.106, 0.329};
  for (int j = 0; j <= 4; ++j) {
    const TriMesh c = reconstruct(mr, j);
    double worst = 0, rms = 0;
    for (const Vec3& p : c.points) {
      const double d = torus_distance(p, R, r) / r;
      worst = std::max(worst, d);
      rms += d * d;
    }
    rms = std::sqrt(rms / double(c.points.size()));
    std::printf(
        "Fig. 23 level %d (%5zu vertices): distance to the torus / r: max %.4f rms %.4f (/ R: max %.4f)\n", j,
        c.points.size(), worst, rms, worst * r / R);
    EXPECT_LT(worst, bound[j]) << "level " << j;
  }
}

}  // namespace
}  // namespace pupwave::sqrt3

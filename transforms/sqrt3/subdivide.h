#pragma once
// Kobbelt's sqrt(3) subdivision P (seed Section 4, Eq. 4.1; boundary rule of Section 8).
//   face point      (c_a + c_b + c_c) / 3
//   interior vertex (1 - alpha_n) c + alpha_n / n * sum of its n neighbours,
//                   alpha_n = (4 - 2 cos(2 pi / n)) / 9
//   boundary vertex plain step: unchanged; boundary-trisect step: the ternary cubic B-spline
//                   rule along its boundary loop (curve_subdivide in boundary_curve.h)

#include <span>
#include <vector>

#include "transforms/sqrt3/mesh.h"
#include "transforms/sqrt3/refine.h"

namespace pupwave::sqrt3 {

// Kobbelt's alpha_n (Eq. 4.1).
double alpha(std::size_t n);

// Fine points of one step: P applied to the coarse points (canonical fine order, refine.h).
std::vector<Vec3> subdivide_points(const Topology& coarse, const Refinement& r, std::span<const Vec3> points);

// `levels` sqrt(3) steps of a mesh, the i-th of kind kobbelt_step_kind(first_step + i). The
// result carries its hierarchy in its vertex order (refine.h). Throws std::invalid_argument for
// a mesh that is not a manifold triangle mesh.
TriMesh subdivide(const TriMesh& mesh, int levels, int first_step = 0);

}  // namespace pupwave::sqrt3

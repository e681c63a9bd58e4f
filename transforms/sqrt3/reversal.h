#pragma once
// The sqrt(3) reversal A and correction Q of one level (seed Sections 5-7), prepared from the
// coarse connectivity alone.
//
// Interior coarse vertex k with n neighbours, none on the boundary (Eq. 5.4-5.6, 6.4-6.5):
//   c_k = a_k g_k + h_k * sum of its n face points,  a_k = -2 / (3 alpha_n - 2),
//   h_k = (3 / n) alpha_n / (3 alpha_n - 2);  details d_i = e_i on face points;
//   e_k = -(h_k / a_k) * sum of the details of its face points.
// Interior vertex next to the boundary: the boundary coarse points are known first (the curve
// filters of boundary_curve.h), so its row is the minimum-norm solution of the same local
// least-squares system over its home node and face points with the columns of its interior
// coarse neighbours only (docs/sqrt3.md); c_k applies that row to g minus the known boundary
// part of P c, and e_k = -(1 / home) * sum of the row's face-point weights times their details.

#include <cstdint>
#include <span>
#include <vector>

#include "transforms/sqrt3/boundary_curve.h"
#include "transforms/sqrt3/mesh.h"
#include "transforms/sqrt3/refine.h"

namespace pupwave::sqrt3 {

// (5.4) and (5.5) for valence n.
double reversal_a(std::size_t n);
double reversal_h(std::size_t n);

// The A row of one coarse vertex: weight on its displaced point and on its face points.
struct ReversalRow {
  double home = 1.0;
  std::vector<std::uint32_t> face_points;  // fine indices
  std::vector<double> weights;
  bool closed_form = true;  // Eq. 5.4-5.5 (no boundary neighbour)
};

// Local least-squares A row of interior vertex v (the general construction; equal to the
// closed form when v has no boundary neighbour). Throws std::logic_error if inconsistent.
ReversalRow local_reversal_row(const Topology& coarse, const Refinement& r, std::size_t v);

// Everything a level's analysis and synthesis needs, computed once from the connectivity.
struct LevelFilters {
  std::vector<ReversalRow> rows;                        // per coarse vertex (boundary vertices: unused)
  std::vector<std::vector<std::uint32_t>> loop_coarse;  // per boundary loop: coarse vertices
  std::vector<std::vector<std::uint32_t>> loop_fine;    // per loop: 3m fine indices (trisect)
  std::vector<CurveFilters> curves;                     // per loop (trisect steps)
};
LevelFilters prepare_filters(const Topology& coarse, const Refinement& r);

// Decomposition of fine points g (canonical order) into coarse points c = A g and details
// d = B g, one per introduced point (index fine - coarse_vertices).
void analyse(const Topology& coarse, const Refinement& r, const LevelFilters& filters,
             std::span<const Vec3> fine, std::vector<Vec3>& coarse_points, std::vector<Vec3>& details);

// Reconstruction g = P c + Q d.
std::vector<Vec3> synthesise(const Topology& coarse, const Refinement& r, const LevelFilters& filters,
                             std::span<const Vec3> coarse_points, std::span<const Vec3> details);

}  // namespace pupwave::sqrt3

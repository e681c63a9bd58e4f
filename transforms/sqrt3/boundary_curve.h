#pragma once
// Boundary curves of the sqrt(3) multiresolution (seed Section 8): a closed boundary loop is a
// uniform cubic B-spline whose knot intervals are trisected every other sqrt(3) step, so
//   fine[3i]     = (4 c[i-1] + 19 c[i] + 4 c[i+1]) / 27          (displaced point)
//   fine[3i + 1] = (c[i-1] + 16 c[i] + 10 c[i+1]) / 27           (introduced points)
//   fine[3i + 2] = (10 c[i] + 16 c[i+1] + c[i+2]) / 27
// (the P column diagram of Fig. 17: 1 4 10 16 19 16 10 4 1, over 27). Its reversal A, correction
// Q and details B are built by local least squares exactly as the seed builds the mesh filters:
//   A row: width 4 around the displaced point, minimum-norm solution of a P_S = u  (Fig. 18)
//   Q column: width 2 around the introduced point, the null space of the A rows it meets,
//             scaled to 1 on its home node                                       (Fig. 20, Eq. 8.2)
//   T row: the narrowest width whose system T Q_S = u is consistent (width 3), minimum norm
//   B = T (I - P A)                                                               (Fig. 19, Eq. 8.1)
// On loops of 10 or more coarse points the filters are the stencils of the infinite curve;
// shorter loops build them on the loop itself (indices wrap), and a loop of 3 points, where
// the local Q is not unique, uses the global pseudo-inverse construction (docs/sqrt3.md).

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "transforms/sqrt3/mesh.h"

namespace pupwave::sqrt3 {

// Ternary cubic B-spline refinement of a closed polygon of m >= 3 points: 3 m fine points.
std::vector<Vec3> curve_subdivide(std::span<const Vec3> coarse);

// Dense filters of a closed loop of m coarse points (3 m fine): fine index 3i is displaced,
// 3i + 1 and 3i + 2 introduced; detail j belongs to introduced fine point 3 (j / 2) + 1 + j % 2.
struct DenseCurveFilters {
  Eigen::MatrixXd P;  // 3m x m
  Eigen::MatrixXd A;  // m x 3m
  Eigen::MatrixXd Q;  // 3m x 2m
  Eigen::MatrixXd B;  // 2m x 3m
  bool local = true;  // false: the global construction was needed
  int t_width = 0;    // widest T diagram used (local construction)
};
DenseCurveFilters build_curve_filters(std::size_t m);

// The infinite curve's filters, taken from a loop long enough to have no wrap-around.
struct CurveStencils {
  std::array<double, 9> a;          // A row: fine offsets -4..4 from the displaced point 3i
  std::array<double, 12> b_before;  // B row of fine 3i - 1: offsets -7..4 from 3i
  std::array<double, 12> b_after;   // B row of fine 3i + 1: offsets -4..7 from 3i
  std::array<double, 5> q_before;   // Q column of fine 3i - 1: offsets -2..2 from 3i - 1
  std::array<double, 5> q_after;    // Q column of fine 3i + 1: offsets -2..2 from 3i + 1
};
const CurveStencils& curve_stencils();

// A, B and Q of one closed loop, ready to apply.
class CurveFilters {
 public:
  explicit CurveFilters(std::size_t m);
  std::size_t coarse_size() const { return m_; }
  // fine: 3m points -> coarse: m points, details: 2m.
  void analyse(std::span<const Vec3> fine, std::span<Vec3> coarse, std::span<Vec3> details) const;
  // coarse + details -> fine = P c + Q d.
  void synthesise(std::span<const Vec3> coarse, std::span<const Vec3> details, std::span<Vec3> fine) const;

 private:
  std::size_t m_;
  bool dense_;
  DenseCurveFilters filters_;  // loops shorter than kStencilLoop
};

}  // namespace pupwave::sqrt3

#pragma once
// The small dense solves of local least squares (seed Section 3): minimum-norm solutions of
// the row systems x M = u and null spaces of column systems, with rank decided at a
// relative tolerance.

#include <Eigen/Core>

namespace pupwave::sqrt3 {

inline constexpr double kRankTolerance = 1e-10;

// Minimum-norm x with x M = u (row vectors). `residual` receives |x M - u|_inf, so a caller
// can tell a consistent system (residual ~ 1e-15) from an inconsistent one.
Eigen::RowVectorXd min_norm_row(const Eigen::MatrixXd& M, const Eigen::RowVectorXd& u, double* residual);

// Orthonormal basis (columns) of the null space of M.
Eigen::MatrixXd null_space(const Eigen::MatrixXd& M);

// Moore-Penrose pseudo-inverse of M.
Eigen::MatrixXd pseudo_inverse(const Eigen::MatrixXd& M);

}  // namespace pupwave::sqrt3

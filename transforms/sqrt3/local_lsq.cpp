#include "transforms/sqrt3/local_lsq.h"

#include <algorithm>

#include <Eigen/SVD>

namespace pupwave::sqrt3 {
namespace {

int numerical_rank(const Eigen::VectorXd& singular) {
  if (singular.size() == 0) return 0;
  const double cut = kRankTolerance * std::max(1.0, singular(0));
  int r = 0;
  while (r < singular.size() && singular(r) > cut) ++r;
  return r;
}

}  // namespace

Eigen::MatrixXd pseudo_inverse(const Eigen::MatrixXd& M) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd s = svd.singularValues();
  const int r = numerical_rank(s);
  Eigen::MatrixXd pinv = Eigen::MatrixXd::Zero(M.cols(), M.rows());
  for (int i = 0; i < r; ++i) pinv += svd.matrixV().col(i) * (1.0 / s(i)) * svd.matrixU().col(i).transpose();
  return pinv;
}

Eigen::RowVectorXd min_norm_row(const Eigen::MatrixXd& M, const Eigen::RowVectorXd& u, double* residual) {
  const Eigen::RowVectorXd x = u * pseudo_inverse(M);
  if (residual) *residual = (x * M - u).cwiseAbs().maxCoeff();
  return x;
}

Eigen::MatrixXd null_space(const Eigen::MatrixXd& M) {
  if (M.rows() == 0) return Eigen::MatrixXd::Identity(M.cols(), M.cols());
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullV);
  const int r = numerical_rank(svd.singularValues());
  return svd.matrixV().rightCols(M.cols() - r);
}

}  // namespace pupwave::sqrt3

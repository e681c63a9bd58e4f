#include "transforms/kobbelt/cyclic_reduction.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pupwave::kobbelt {
namespace {

// Unit roundoff of double: off-diagonals below this fraction of the diagonal no longer
// change a solution component, so the reduced matrix is diagonal "to machine precision".
constexpr double kDiagonalTolerance = std::numeric_limits<double>::epsilon() / 2;

bool is_diagonal(const Tridiagonal& a) {
  const std::size_t m = a.size();
  for (std::size_t j = 0; j < m; ++j) {
    const double off = (j > 0 ? std::abs(a.sub[j]) : 0.0) + (j + 1 < m ? std::abs(a.super[j]) : 0.0);
    if (!(off <= kDiagonalTolerance * std::abs(a.diag[j]))) return false;
  }
  return true;
}

double checked_pivot(double v, std::size_t row) {
  if (!std::isfinite(v) || v == 0.0) {
    throw std::domain_error("cyclic reduction: zero or non-finite pivot at row " + std::to_string(row) +
                            " (singular system)");
  }
  return v;
}

// Even row j = 2k is combined with its odd neighbours using the weights of Eq. (12), scaled
// so the even row keeps weight 1: row_j - (sub_j / diag_{j-1}) row_{j-1}
// - (super_j / diag_{j+1}) row_{j+1}. Fills the R b update and returns R A U_e.
Tridiagonal reduce(const Tridiagonal& a, BandedStep& update) {
  const std::size_t m = a.size(), ne = (m + 1) / 2;
  Tridiagonal r{std::vector<double>(ne, 0.0), std::vector<double>(ne, 0.0), std::vector<double>(ne, 0.0)};
  update = make_banded_step(ne, 2, -1);  // sources: odd wire k-1 and k
  for (std::size_t k = 0; k < ne; ++k) {
    const std::size_t j = 2 * k;
    double diag = a.diag[j];
    if (j > 0) {
      const double l = -a.sub[j] / checked_pivot(a.diag[j - 1], j - 1);
      update.at(k, 0) = l;
      r.sub[k] = l * a.sub[j - 1];
      diag += l * a.super[j - 1];
    }
    if (j + 1 < m) {
      const double rr = -a.super[j] / checked_pivot(a.diag[j + 1], j + 1);
      update.at(k, 1) = rr;
      r.super[k] = rr * a.super[j + 1];
      diag += rr * a.sub[j + 1];
    }
    r.diag[k] = diag;
  }
  return r;
}

// Back-substitution of Eq. (16) for the odd rows: x_odd = (b_odd - off-diagonals x_even) / diag.
void back_substitution(const Tridiagonal& a, BandedStep& predict, std::vector<double>& inv_diag) {
  const std::size_t m = a.size(), no = m / 2;
  predict = make_banded_step(no, 2, 0);  // sources: even wire k and k+1
  inv_diag.assign(no, 0.0);
  for (std::size_t k = 0; k < no; ++k) {
    const std::size_t j = 2 * k + 1;
    predict.at(k, 0) = -a.sub[j];
    if (j + 1 < m) predict.at(k, 1) = -a.super[j];
    inv_diag[k] = 1.0 / checked_pivot(a.diag[j], j);
  }
}

}  // namespace

CyclicReduction::CyclicReduction(const Tridiagonal& a) : size_(a.size()) {
  if (a.sub.size() != size_ || a.super.size() != size_) {
    throw std::invalid_argument("CyclicReduction: sub, diag and super must have equal sizes");
  }
  Tridiagonal current = a;
  while (current.size() > 1 && !is_diagonal(current)) {
    Level level;
    level.m = current.size();
    back_substitution(current, level.predict, level.inv_diag);
    current = reduce(current, level.update);
    levels_.push_back(std::move(level));
  }
  final_inv_diag_.resize(current.size());
  for (std::size_t j = 0; j < current.size(); ++j) {
    final_inv_diag_[j] = 1.0 / checked_pivot(current.diag[j], j);
  }
}

}  // namespace pupwave::kobbelt

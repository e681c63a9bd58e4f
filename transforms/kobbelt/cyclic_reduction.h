#pragma once
// Cyclic reduction (CR) of a tridiagonal system written as lifting steps (Kobbelt-Schroder,
// Section 2.4, Eq. 11-16, Fig. 11). One CR level splits the unknowns into even and odd
// wires, updates the even right-hand sides from the odd ones (R b, Eq. 14), recurses on the
// reduced even system R A U_e, then predicts the odd unknowns from the even solution and
// scales them by the inverse diagonal (Eq. 16). The recursion stops as soon as the reduced
// matrix is diagonal to machine precision (the paper's ceil(log2 r) argument), so the
// network is finite and is inverted or transposed step by step, never by a general solver.

#include <cstddef>
#include <span>
#include <vector>

#include "transforms/kobbelt/banded_lifting.h"
#include "transforms/lifting.h"
#include "transforms/scratch.h"

namespace pupwave::kobbelt {

// Tridiagonal matrix: row j is sub[j] x[j-1] + diag[j] x[j] + super[j] x[j+1]
// (sub[0] and super[m-1] are ignored).
struct Tridiagonal {
  std::vector<double> sub, diag, super;
  std::size_t size() const { return diag.size(); }
};

// The lifting network that solves A x = b for one tridiagonal A.
class CyclicReduction {
 public:
  // Builds the network. Throws std::invalid_argument if the sizes disagree and
  // std::domain_error if a pivot vanishes (A singular or not reducible without pivoting).
  explicit CyclicReduction(const Tridiagonal& a);

  std::size_t size() const { return size_; }
  // Number of CR levels before the reduced matrix became diagonal.
  std::size_t levels() const { return levels_.size(); }

  // b <- A^{-1} b in place (the synthesis direction).
  template <class T>
  void solve(std::span<T> b) const;
  // x <- A x in place through the inverted network (every box undone in reverse order).
  template <class T>
  void multiply(std::span<T> x) const;

 private:
  struct Level {
    std::size_t m = 0;             // unknowns at this level
    BandedStep update;             // even[k] += R weights * odd[k-1], odd[k]      (R b)
    BandedStep predict;            // odd[k]  -= off-diagonals * even[k], even[k+1] (Eq. 16)
    std::vector<double> inv_diag;  // odd[k] *= 1 / diagonal                    (Eq. 16)
  };
  std::size_t size_ = 0;
  std::vector<Level> levels_;
  std::vector<double> final_inv_diag_;  // the diagonal system left at the bottom
};

template <class T>
void CyclicReduction::solve(std::span<T> b) const {
  if (b.size() != size_) throw std::invalid_argument("CyclicReduction::solve: size mismatch");
  std::span<T> scratch = thread_scratch<T>(size_ / 2 + 1, 1);
  std::span<T> wire = b;
  for (const Level& l : levels_) {  // down: split, reduce the right-hand side
    lifting::split<T>(wire, scratch);
    const std::size_t ne = (l.m + 1) / 2;
    lift<T>(l.update, wire.subspan(ne), wire.first(ne));
    wire = wire.first(ne);
  }
  scale<T>(final_inv_diag_, wire);
  for (auto it = levels_.rbegin(); it != levels_.rend(); ++it) {  // up: back-substitute
    wire = b.first(it->m);
    const std::size_t ne = (it->m + 1) / 2;
    lift<T>(it->predict, wire.first(ne), wire.subspan(ne));
    scale<T>(it->inv_diag, wire.subspan(ne));
    lifting::merge<T>(wire, scratch);
  }
}

template <class T>
void CyclicReduction::multiply(std::span<T> x) const {
  if (x.size() != size_) throw std::invalid_argument("CyclicReduction::multiply: size mismatch");
  std::span<T> scratch = thread_scratch<T>(size_ / 2 + 1, 1);
  std::span<T> wire = x;
  for (const Level& l : levels_) {  // undo the up sweep: split, unscale, unpredict
    lifting::split<T>(wire, scratch);
    const std::size_t ne = (l.m + 1) / 2;
    unscale<T>(l.inv_diag, wire.subspan(ne));
    unlift<T>(l.predict, wire.first(ne), wire.subspan(ne));
    wire = wire.first(ne);
  }
  unscale<T>(final_inv_diag_, wire);
  for (auto it = levels_.rbegin(); it != levels_.rend(); ++it) {  // undo the down sweep
    wire = x.first(it->m);
    const std::size_t ne = (it->m + 1) / 2;
    unlift<T>(it->update, wire.subspan(ne), wire.first(ne));
    lifting::merge<T>(wire, scratch);
  }
}

}  // namespace pupwave::kobbelt

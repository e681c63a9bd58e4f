#pragma once
// Lifting steps whose filter changes from sample to sample (Kobbelt-Schroder's non-Toeplitz
// wiring-diagram boxes). transforms/lifting.h applies one filter to a whole wire with
// symmetric extension; cyclic reduction, natural boundary rows and non-uniform parameters
// need a different filter per target sample and no extension, hence this small variant.

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

namespace pupwave::kobbelt {

// A banded matrix acting between two wires: target[i] += sum_k coeff[i][k] source[i+offset+k].
// Source indices outside the wire must carry zero coefficients (they are skipped).
struct BandedStep {
  std::size_t width = 0;      // taps per target sample
  std::ptrdiff_t offset = 0;  // source index of tap 0 relative to the target index
  std::vector<double> coeff;  // rows() * width coefficients, row-major
  std::size_t rows() const { return width == 0 ? 0 : coeff.size() / width; }
  double& at(std::size_t row, std::size_t k) { return coeff[row * width + k]; }
  double at(std::size_t row, std::size_t k) const { return coeff[row * width + k]; }
};

// Returns an all-zero step of `rows` target samples.
inline BandedStep make_banded_step(std::size_t rows, std::size_t width, std::ptrdiff_t offset) {
  return BandedStep{width, offset, std::vector<double>(rows * width, 0.0)};
}

namespace detail {

// Filtered source at target row i (only taps that fall inside the source wire).
template <class T>
T banded_sum(const BandedStep& s, std::span<const T> source, std::size_t i) {
  const auto first = static_cast<std::ptrdiff_t>(i) + s.offset;
  const auto k0 = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, -first));
  const auto avail = static_cast<std::ptrdiff_t>(source.size()) - first;
  const auto k1 =
      static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(avail, 0, static_cast<std::ptrdiff_t>(s.width)));
  if (k0 >= k1) return T(0);
  const T* src = source.data() + first;  // first + k >= 0 for k >= k0
  T sum = T(s.at(i, k0)) * src[k0];      // w taps cost w multiplications, w - 1 additions
  for (std::size_t k = k0 + 1; k < k1; ++k) sum += T(s.at(i, k)) * src[k];
  return sum;
}

}  // namespace detail

// Lifting step: target += step * source. The source wire is left unchanged, so unlift()
// with the same arguments subtracts the identical sums and restores target to rounding.
template <class T>
void lift(const BandedStep& s, std::span<const T> source, std::span<T> target) {
  const std::size_t m = std::min(target.size(), s.rows());
  for (std::size_t i = 0; i < m; ++i) target[i] += detail::banded_sum(s, source, i);
}

// Mirror of lift(): target -= step * source.
template <class T>
void unlift(const BandedStep& s, std::span<const T> source, std::span<T> target) {
  const std::size_t m = std::min(target.size(), s.rows());
  for (std::size_t i = 0; i < m; ++i) target[i] -= detail::banded_sum(s, source, i);
}

// Scale box: wire[i] *= factor[i].
template <class T>
void scale(std::span<const double> factor, std::span<T> wire) {
  const std::size_t m = std::min(wire.size(), factor.size());
  for (std::size_t i = 0; i < m; ++i) wire[i] *= T(factor[i]);
}

// Mirror of scale(): wire[i] /= factor[i].
template <class T>
void unscale(std::span<const double> factor, std::span<T> wire) {
  const std::size_t m = std::min(wire.size(), factor.size());
  for (std::size_t i = 0; i < m; ++i) wire[i] /= T(factor[i]);
}

}  // namespace pupwave::kobbelt

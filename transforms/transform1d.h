#pragma once
// The one interface every 1-D two-channel wavelet transform implements (CDF, PUPs, Kobbelt).

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace pupwave {

// A 1-D two-channel transform on a line of any length n >= 1.
//
// Layout contract (all overloads): analysis works in place on a contiguous line; on return
// line[0, ceil(n/2)) holds the coarse (low) band and line[ceil(n/2), n) the detail (high)
// band. synthesize() takes that layout and restores the original line, perfectly
// reconstructing to rounding (bit-exactly for the integer overloads of reversible
// transforms). n == 1 is the identity (one coarse sample, no detail).
// Implementations are immutable after construction and safe to call from many threads.
class Transform1D {
 public:
  virtual ~Transform1D() = default;

  // Canonical transform spec string (e.g. "cdf97", "pups:chaikin", "kobbelt:k2").
  virtual std::string spec() const = 0;

  virtual void analyze(std::span<double> line) const = 0;
  virtual void synthesize(std::span<double> line) const = 0;
  virtual void analyze(std::span<float> line) const = 0;
  virtual void synthesize(std::span<float> line) const = 0;

  // Reversible integer-to-integer transforms (cdf53) override these and return true from
  // is_reversible(); the defaults throw std::logic_error.
  virtual bool is_reversible() const { return false; }
  virtual void analyze(std::span<int32_t> line) const;
  virtual void synthesize(std::span<int32_t> line) const;

  // The same on every column of a block of rows: block holds block.size() / width rows of
  // `width` samples, row i at block[i * width], and each column is transformed as one line.
  // The separable engine's column passes use these; the defaults copy each column to a line,
  // and transforms override them with row-wise lifting that vectorizes over the columns
  // (results bit-identical to the line form).
  virtual void analyze_columns(std::span<float> block, std::size_t width) const;
  virtual void synthesize_columns(std::span<float> block, std::size_t width) const;
  virtual void analyze_columns(std::span<double> block, std::size_t width) const;
  virtual void synthesize_columns(std::span<double> block, std::size_t width) const;
  virtual void analyze_columns(std::span<int32_t> block, std::size_t width) const;
  virtual void synthesize_columns(std::span<int32_t> block, std::size_t width) const;
};

using Transform1DPtr = std::shared_ptr<const Transform1D>;

// Number of coarse samples of a line of n samples.
constexpr std::size_t coarse_size(std::size_t n) { return (n + 1) / 2; }
// Number of detail samples of a line of n samples.
constexpr std::size_t detail_size(std::size_t n) { return n / 2; }

}  // namespace pupwave

#pragma once
// Lifting primitives (split/merge, predict, update, scale) shared by every transform family.
//
// A line of n samples x[0..n) is split into two wires: the even wire e[j] = x[2j]
// (ceil(n/2) samples, becomes the coarse band) and the odd wire o[j] = x[2j+1] (floor(n/2)
// samples, becomes the detail band), stored as [e | o] in the layout of transform1d.h.
// A lifting step adds to every sample of a target wire a filtered copy of the other
// (source) wire; it is undone exactly by its mirror step, which subtracts the identical
// sum, because the source wire is not changed by the step. Neighbours beyond the ends of
// the source wire come from a symmetric extension chosen per end (Boundary), so every step
// is invertible for every wire length, whatever rule is chosen.
//
//   predict: odd  += taps * even   (Kobbelt-Schroder "predict odd")
//   update:  even += taps * odd    ("predict even")
//   scale:   wire *= k
//
// All functions are stateless and thread safe; T is float or double (integer steps for the
// reversible 5/3 are at the end).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace pupwave::lifting {

// Symmetric extension at one end of a wire of m samples.
enum class Extension {
  whole_sample,  // mirror about the end sample: w[-k] = w[k], w[m-1+k] = w[m-1-k]
  half_sample,   // mirror about the half-way point: w[-1-k] = w[k], w[m+k] = w[m-1-k]
};

// Extension rule of a wire at its left (index 0) and right (index m-1) ends.
struct Boundary {
  Extension left = Extension::whole_sample;
  Extension right = Extension::whole_sample;
};

// Wire boundaries that reproduce whole-sample symmetric extension of the interleaved line
// (JPEG 2000): for symmetric lifting filters, lifting the wires with these rules equals
// lifting the symmetrically extended line.
struct WireBoundaries {
  Boundary even;  // rule for reading the even wire (in predict steps)
  Boundary odd;   // rule for reading the odd wire (in update steps)
};

// n = length of the interleaved line. Derivation: x[-k] = x[k] maps even to even indices
// about 0 (whole) and odd to odd indices about -1/2 (half); at the right end x[n-1+k] =
// x[n-1-k] is whole-sample for the wire holding x[n-1] and half-sample for the other.
constexpr WireBoundaries whole_sample_symmetric_wires(std::size_t n) {
  const bool last_is_even = (n % 2) == 1;
  const Extension even_right = last_is_even ? Extension::whole_sample : Extension::half_sample;
  const Extension odd_right = last_is_even ? Extension::half_sample : Extension::whole_sample;
  return {{Extension::whole_sample, even_right}, {Extension::half_sample, odd_right}};
}

// Index into a wire of m >= 1 samples for any integer position i, by repeated symmetric
// reflection (handles filters longer than the wire). A wire of one sample is constant.
constexpr std::size_t reflect_index(std::ptrdiff_t i, std::size_t m, Boundary b) {
  if (m <= 1) return 0;
  const auto last = static_cast<std::ptrdiff_t>(m) - 1;
  while (i < 0 || i > last) {
    if (i < 0) {
      i = b.left == Extension::whole_sample ? -i : -1 - i;
    } else {
      i = b.right == Extension::whole_sample ? 2 * last - i : 2 * last + 1 - i;
    }
  }
  return static_cast<std::size_t>(i);
}

// Filter of a lifting step: target[i] += sum_k taps[k] * source[i + offset + k].
// Example, CDF 9/7 first predict: odd[i] += alpha (even[i] + even[i+1]) is
// taps {alpha, alpha}, offset 0; its first update even[i] += beta (odd[i-1] + odd[i]) is
// taps {beta, beta}, offset -1.
struct Taps {
  std::span<const double> taps;  // filter coefficients, in source index order
  std::ptrdiff_t offset = 0;     // source index of taps[0] relative to the target index
};

namespace detail {

// Sum of one lifting filter at target index i, reading the source through the boundary
// rule; used near the ends where the filter overhangs the source wire.
template <class T>
T boundary_sum(std::span<const T> source, Boundary b, const Taps& f, std::ptrdiff_t i) {
  T s = 0;
  for (std::size_t k = 0; k < f.taps.size(); ++k) {
    const std::ptrdiff_t j = i + f.offset + static_cast<std::ptrdiff_t>(k);
    s += static_cast<T>(f.taps[k]) * source[reflect_index(j, source.size(), b)];
  }
  return s;
}

// Longest filter the fast paths below hold on the stack; longer ones (no design makes them)
// take boundary_sum at every sample.
inline constexpr std::ptrdiff_t kMaxFastTaps = 64;
// Samples filtered per accumulator block: one cache line, few enough for the accumulators to
// stay in vector registers. A fixed count lets the compiler unroll and vectorize the block.
template <class T>
inline constexpr std::ptrdiff_t kLiftLanes = std::ptrdiff_t(64 / sizeof(T));

// t[c] += sign * sum_k taps[k] * rows(k)[c] for c in [0, m), m <= kLiftLanes<T>: each sum formed
// from 0 in tap order, exactly as boundary_sum forms it, with the taps outermost so the columns
// are independent lanes (rows(k) is the source run tap k reads).
template <class T, class Rows>
[[gnu::always_inline]] inline void filter_lanes(Rows rows, const T* taps, std::ptrdiff_t nk, T* t,
                                                std::ptrdiff_t m, T sign) {
  constexpr std::ptrdiff_t L = kLiftLanes<T>;
  T acc[L] = {};
  if (m == L) {
    for (std::ptrdiff_t k = 0; k < nk; ++k) {
      const T tk = taps[k];
      const T* r = rows(k);
      for (std::ptrdiff_t c = 0; c < L; ++c) acc[c] += tk * r[c];
    }
    for (std::ptrdiff_t c = 0; c < L; ++c) t[c] += sign * acc[c];
    return;
  }
  for (std::ptrdiff_t k = 0; k < nk; ++k) {
    const T tk = taps[k];
    const T* r = rows(k);
    for (std::ptrdiff_t c = 0; c < m; ++c) acc[c] += tk * r[c];
  }
  for (std::ptrdiff_t c = 0; c < m; ++c) t[c] += sign * acc[c];
}

// target[i] += sign * sum_k taps[k] * src[i + k] for i in [0, count), src holding every sample
// the filter reaches (no index checks), a block of lanes at a time.
template <class T>
[[gnu::always_inline]] inline void filter_run(const T* src, T* target, std::ptrdiff_t count, const T* taps,
                                              std::ptrdiff_t nk, T sign) {
  constexpr std::ptrdiff_t L = kLiftLanes<T>;
  for (std::ptrdiff_t i0 = 0; i0 < count; i0 += L)
    filter_lanes([&](std::ptrdiff_t k) { return src + i0 + k; }, taps, nk, target + i0,
                 std::min(L, count - i0), sign);
}

// filter_run and columns::filter_rows for float and double, compiled in lifting_kernels.cpp
// once per instruction set where the compiler can pick one at load time (x86-64: AVX2 and the
// baseline); every version performs the same IEEE operations in the same order (no FMA), so
// results do not depend on the machine.
void run_filter(const float* src, float* target, std::ptrdiff_t count, const float* taps, std::ptrdiff_t nk,
                float sign);
void run_filter(const double* src, double* target, std::ptrdiff_t count, const double* taps,
                std::ptrdiff_t nk, double sign);
void run_filter_rows(const float* const* rows, const float* taps, std::ptrdiff_t nk, float* t,
                     std::size_t width, float sign);
void run_filter_rows(const double* const* rows, const double* taps, std::ptrdiff_t nk, double* t,
                     std::size_t width, double sign);

// A per-thread buffer of at least n samples for the extended source wire of apply_general.
template <class T>
T* extension_buffer(std::size_t n) {
  thread_local std::vector<T> buffer;
  if (buffer.size() < n) buffer.resize(n);
  return buffer.data();
}

// apply for filters of other than two taps: the source samples the targets read, reflected
// ones included, are copied once into an extended wire (reflect_index per sample near the
// ends, not per tap), and every target is filtered from it by filter_run without index
// checks. Each sum gets boundary_sum's operations in its order. Not inlined, so that apply
// (two-tap steps, the CDF hot path) stays small enough to inline into its callers.
template <class T>
[[gnu::noinline]] void apply_general(std::span<const T> source, Boundary b, std::span<T> target,
                                     const Taps& f, T sign) {
  const auto ms = static_cast<std::ptrdiff_t>(source.size());
  const auto mt = static_cast<std::ptrdiff_t>(target.size());
  const auto nk = static_cast<std::ptrdiff_t>(f.taps.size());
  if (nk > kMaxFastTaps) {
    for (std::ptrdiff_t i = 0; i < mt; ++i) target[i] += sign * boundary_sum(source, b, f, i);
    return;
  }
  T taps[kMaxFastTaps];
  for (std::ptrdiff_t k = 0; k < nk; ++k) taps[k] = static_cast<T>(f.taps[std::size_t(k)]);
  const std::ptrdiff_t len = mt + nk - 1;  // ext[q] = the source sample at index q + offset
  T* ext = extension_buffer<T>(std::size_t(len));
  const std::ptrdiff_t in0 = std::clamp<std::ptrdiff_t>(-f.offset, 0, len);  // first q inside the wire
  const std::ptrdiff_t in1 = std::clamp<std::ptrdiff_t>(ms - f.offset, in0, len);
  for (std::ptrdiff_t q = 0; q < in0; ++q) ext[q] = source[reflect_index(q + f.offset, source.size(), b)];
  std::copy(source.data() + (in0 + f.offset), source.data() + (in1 + f.offset), ext + in0);
  for (std::ptrdiff_t q = in1; q < len; ++q) ext[q] = source[reflect_index(q + f.offset, source.size(), b)];
  run_filter(ext, target.data(), mt, taps, nk, sign);
}

// target[i] += sign * (filtered source)[i]; sign = +1 lifts, -1 undoes the lift. The sum is
// formed identically in both directions so the mirror step cancels to rounding. The interior
// (filter inside the source wire) runs without index checks; the samples within reach of an
// end read the reflected source. Every sample gets boundary_sum's operations in its order,
// except the interior of a two-tap step: a0 * x + a1 * y with a = sign * tap (the same sum,
// negation being exact).
template <class T>
void apply(std::span<const T> source, Boundary b, std::span<T> target, const Taps& f, T sign) {
  if (source.empty() || target.empty() || f.taps.empty()) return;
  const auto ms = static_cast<std::ptrdiff_t>(source.size());
  const auto mt = static_cast<std::ptrdiff_t>(target.size());
  const auto nk = static_cast<std::ptrdiff_t>(f.taps.size());
  if (nk != 2) return apply_general(source, b, target, f, sign);
  // Interior: i + offset >= 0 and i + offset + nk - 1 <= ms - 1.
  const std::ptrdiff_t lo = std::min(mt, std::max<std::ptrdiff_t>(0, -f.offset));
  const std::ptrdiff_t hi = std::max(lo, std::min(mt, ms - nk - f.offset + 1));
  for (std::ptrdiff_t i = 0; i < lo; ++i) target[i] += sign * boundary_sum(source, b, f, i);
  const T* src = source.data() + f.offset;
  const T a0 = sign * static_cast<T>(f.taps[0]), a1 = sign * static_cast<T>(f.taps[1]);
  for (std::ptrdiff_t i = lo; i < hi; ++i) target[i] += a0 * src[i] + a1 * src[i + 1];
  for (std::ptrdiff_t i = hi; i < mt; ++i) target[i] += sign * boundary_sum(source, b, f, i);
}

}  // namespace detail

namespace detail {

// split and merge through a scratch copy of the whole line: reading (or writing) the two wires
// interleaved from a separate buffer has no overlap, so the compiler vectorizes both loops.
template <class T>
void split_copy(T* __restrict line, T* __restrict copy, std::size_t n) {
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  std::copy_n(line, n, copy);
  for (std::size_t j = 0; j < no; ++j) {
    line[j] = copy[2 * j];
    line[ne + j] = copy[2 * j + 1];
  }
  if (ne > no) line[no] = copy[n - 1];
}

template <class T>
void merge_copy(T* __restrict line, T* __restrict copy, std::size_t n) {
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  std::copy_n(line, n, copy);
  for (std::size_t j = 0; j < no; ++j) {
    line[2 * j] = copy[j];
    line[2 * j + 1] = copy[ne + j];
  }
  if (ne > no) line[n - 1] = copy[no];
}

}  // namespace detail

// Reorders an interleaved line x[0..n) into [even wire | odd wire] in place.
// scratch: at least floor(n/2) samples, used to hold the odd wire while compacting; with at
// least n samples (not overlapping the line) the faster whole-line copy is used.
template <class T>
void split(std::span<T> line, std::span<T> scratch) {
  const std::size_t n = line.size(), ne = (n + 1) / 2, no = n / 2;
  if (scratch.size() < no) throw std::invalid_argument("lifting::split: scratch too small");
  if (scratch.size() >= n) return detail::split_copy(line.data(), scratch.data(), n);
  for (std::size_t j = 0; j < no; ++j) scratch[j] = line[2 * j + 1];
  for (std::size_t j = 1; j < ne; ++j) line[j] = line[2 * j];
  for (std::size_t j = 0; j < no; ++j) line[ne + j] = scratch[j];
}

// Inverse of split: [even wire | odd wire] back to the interleaved line, in place.
// scratch: at least floor(n/2) samples (at least n: the faster whole-line copy).
template <class T>
void merge(std::span<T> line, std::span<T> scratch) {
  const std::size_t n = line.size(), ne = (n + 1) / 2, no = n / 2;
  if (scratch.size() < no) throw std::invalid_argument("lifting::merge: scratch too small");
  if (scratch.size() >= n) return detail::merge_copy(line.data(), scratch.data(), n);
  for (std::size_t j = 0; j < no; ++j) scratch[j] = line[ne + j];
  for (std::size_t j = ne; j-- > 1;) line[2 * j] = line[j];
  for (std::size_t j = 0; j < no; ++j) line[2 * j + 1] = scratch[j];
}

// Predict step: odd[i] += sum_k f.taps[k] * even[i + f.offset + k].
// even: the source wire (unchanged), read beyond its ends through even_boundary.
// odd: the target wire, modified in place. Does nothing if either wire is empty.
template <class T>
void predict(std::span<const T> even, Boundary even_boundary, std::span<T> odd, const Taps& f) {
  detail::apply<T>(even, even_boundary, odd, f, T(1));
}

// Exact mirror of predict (same arguments): odd[i] -= the same sum.
template <class T>
void undo_predict(std::span<const T> even, Boundary even_boundary, std::span<T> odd, const Taps& f) {
  detail::apply<T>(even, even_boundary, odd, f, T(-1));
}

// Update step: even[i] += sum_k f.taps[k] * odd[i + f.offset + k].
// odd: the source wire (unchanged), read beyond its ends through odd_boundary; an empty odd
// wire (n = 1) leaves even unchanged. even: the target wire, modified in place.
template <class T>
void update(std::span<const T> odd, Boundary odd_boundary, std::span<T> even, const Taps& f) {
  detail::apply<T>(odd, odd_boundary, even, f, T(1));
}

// Exact mirror of update (same arguments): even[i] -= the same sum.
template <class T>
void undo_update(std::span<const T> odd, Boundary odd_boundary, std::span<T> even, const Taps& f) {
  detail::apply<T>(odd, odd_boundary, even, f, T(-1));
}

// Scale step: wire[i] *= k. k must be non-zero (else std::invalid_argument).
template <class T>
void scale(std::span<T> wire, double k) {
  if (k == 0) throw std::invalid_argument("lifting::scale: factor must be non-zero");
  const T kt = static_cast<T>(k);
  for (T& v : wire) v *= kt;
}

// Mirror of scale: wire[i] /= k (division, not multiplication by 1/k, to stay closest).
template <class T>
void undo_scale(std::span<T> wire, double k) {
  if (k == 0) throw std::invalid_argument("lifting::undo_scale: factor must be non-zero");
  const T kt = static_cast<T>(k);
  for (T& v : wire) v /= kt;
}

// ---- Integer (reversible) lifting, as in JPEG 2000's 5/3 -------------------------------
//
// An integer step adds or subtracts floor((sum_k w[k] * source[i + offset + k] + bias) /
// 2^shift); the floor makes it map integers to integers, and the mirror step (opposite
// direction, same arguments) restores the target bit-exactly. Sums are formed in 64 bits.
// JPEG 2000 reversible 5/3 forward:
//   predict: odd[i]  -= floor((even[i] + even[i+1]) / 2)      {1,1}, offset 0,  bias 0, shift 1
//   update:  even[i] += floor((odd[i-1] + odd[i] + 2) / 4)    {1,1}, offset -1, bias 2, shift 2
struct IntegerTaps {
  std::span<const int32_t> weights;  // integer filter coefficients in source index order
  std::ptrdiff_t offset = 0;         // source index of weights[0] relative to the target index
  int64_t bias = 0;                  // added before the shift (rounding offset)
  int shift = 0;                     // divide by 2^shift with floor rounding, 0..30
};

// Direction of an integer step: the mirror of `add` is `subtract` and vice versa.
enum class Direction { add, subtract };

namespace detail {

inline int32_t integer_term(std::span<const int32_t> source, Boundary b, const IntegerTaps& f,
                            std::ptrdiff_t i, bool interior) {
  int64_t s = f.bias;
  for (std::size_t k = 0; k < f.weights.size(); ++k) {
    const std::ptrdiff_t j = i + f.offset + static_cast<std::ptrdiff_t>(k);
    const std::size_t jj = interior ? static_cast<std::size_t>(j) : reflect_index(j, source.size(), b);
    s += int64_t{f.weights[k]} * source[jj];
  }
  return static_cast<int32_t>(s >> f.shift);  // arithmetic shift = floor division (C++20)
}

}  // namespace detail

// Integer lifting step: target[i] (+= or -=) floor((sum w * source + bias) / 2^shift).
// source: the unchanged wire, read beyond its ends through source_boundary; empty source or
// target does nothing. The mirror step is the same call with the other Direction.
inline void lift_integer(std::span<const int32_t> source, Boundary source_boundary, std::span<int32_t> target,
                         const IntegerTaps& f, Direction dir) {
  if (f.shift < 0 || f.shift > 30) throw std::invalid_argument("lifting: shift out of 0..30");
  if (source.empty() || target.empty() || f.weights.empty()) return;
  const auto ms = static_cast<std::ptrdiff_t>(source.size());
  const auto nk = static_cast<std::ptrdiff_t>(f.weights.size());
  const int32_t sign = dir == Direction::add ? 1 : -1;
  const auto mt = static_cast<std::ptrdiff_t>(target.size());
  const std::ptrdiff_t lo = std::min(mt, std::max<std::ptrdiff_t>(0, -f.offset));
  const std::ptrdiff_t hi = std::max(lo, std::min(mt, ms - nk - f.offset + 1));
  auto edge = [&](std::ptrdiff_t i) {
    target[static_cast<std::size_t>(i)] += sign * detail::integer_term(source, source_boundary, f, i, false);
  };
  for (std::ptrdiff_t i = 0; i < lo; ++i) edge(i);
  if (nk == 2) {  // the 5/3 steps: a branch-free loop the compiler can vectorize
    const int32_t* src = source.data() + f.offset;
    const int64_t w0 = f.weights[0], w1 = f.weights[1];
    for (std::ptrdiff_t i = lo; i < hi; ++i)
      target[static_cast<std::size_t>(i)] +=
          sign * static_cast<int32_t>((w0 * src[i] + w1 * src[i + 1] + f.bias) >> f.shift);
  } else {
    for (std::ptrdiff_t i = lo; i < hi; ++i)
      target[static_cast<std::size_t>(i)] += sign * detail::integer_term(source, source_boundary, f, i, true);
  }
  for (std::ptrdiff_t i = hi; i < mt; ++i) edge(i);
}

}  // namespace pupwave::lifting

#pragma once
// The lifting primitives of lifting.h applied to many lines at once: a column block holds n
// rows of `width` samples (row i at block + i * width), and every column is one line. Each
// step walks whole rows, so the inner loop runs over adjacent columns with unit stride and
// vectorizes, and the separable engine's column passes need no transposes. Every sample is
// computed by exactly the expression the 1-D primitive uses, so the results are bit-identical
// to transforming each column as a line (tests/transforms checks it).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "transforms/lifting.h"

namespace pupwave::lifting::columns {

// Copies one row of a block. Rows of the separable engine's usual 32 columns are copied with a
// constant size, which compiles to a few vector moves instead of a memcpy call per row.
template <class T>
inline void copy_row(T* dst, const T* src, std::size_t width) {
  if (width == 32)
    std::memcpy(dst, src, 32 * sizeof(T));
  else
    std::memcpy(dst, src, width * sizeof(T));
}

// Reorders the rows of a block of n rows into [even rows | odd rows] (lifting::split per
// column). scratch: at least floor(n/2) * width samples.
template <class T>
void split(T* block, std::size_t n, std::size_t width, T* scratch) {
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  for (std::size_t j = 0; j < no; ++j) copy_row(scratch + j * width, block + (2 * j + 1) * width, width);
  for (std::size_t j = 1; j < ne; ++j) copy_row(block + j * width, block + 2 * j * width, width);
  std::memcpy(block + ne * width, scratch, no * width * sizeof(T));
}

// Inverse of split (lifting::merge per column). scratch: at least floor(n/2) * width samples.
template <class T>
void merge(T* block, std::size_t n, std::size_t width, T* scratch) {
  const std::size_t ne = (n + 1) / 2, no = n / 2;
  std::memcpy(scratch, block + ne * width, no * width * sizeof(T));
  for (std::size_t j = ne; j-- > 1;) copy_row(block + 2 * j * width, block + j * width, width);
  for (std::size_t j = 0; j < no; ++j) copy_row(block + (2 * j + 1) * width, scratch + j * width, width);
}

// t[c] += sign * sum_k taps[k] * rows[k][c] for c in [0, width): each column's sum formed from 0
// in tap order (boundary_sum's operations), a block of columns at a time with the taps
// outermost (detail::filter_lanes), so the columns are vector lanes.
template <class T>
[[gnu::always_inline]] inline void filter_rows(const T* const* rows, const T* taps, std::ptrdiff_t nk, T* t,
                                               std::size_t width, T sign) {
  constexpr auto L = detail::kLiftLanes<T>;
  const auto w = static_cast<std::ptrdiff_t>(width);
  for (std::ptrdiff_t c0 = 0; c0 < w; c0 += L)
    detail::filter_lanes([&](std::ptrdiff_t k) { return rows[k] + c0; }, taps, nk, t + c0,
                         std::min(L, w - c0), sign);
}

// apply_row for every filter but the interior of a two-tap one: the source rows each tap reads
// (reflected near the ends), then filter_rows. Kept out of apply_row so that stays inlinable.
template <class T>
[[gnu::noinline]] void apply_row_general(const T* source, std::size_t ms, Boundary b, T* t, std::ptrdiff_t i,
                                         bool interior, const Taps& f, T sign, std::size_t width) {
  const auto nk = static_cast<std::ptrdiff_t>(f.taps.size());
  if (nk > detail::kMaxFastTaps) {  // longer than any design: one column at a time
    for (std::size_t c = 0; c < width; ++c) {
      T s = 0;
      for (std::ptrdiff_t k = 0; k < nk; ++k) {
        const std::ptrdiff_t j = i + f.offset + k;
        const std::size_t jj = interior ? std::size_t(j) : reflect_index(j, ms, b);
        s += static_cast<T>(f.taps[std::size_t(k)]) * source[jj * width + c];
      }
      t[c] += sign * s;
    }
    return;
  }
  const T* rows[detail::kMaxFastTaps];
  T taps[detail::kMaxFastTaps];
  for (std::ptrdiff_t k = 0; k < nk; ++k) {
    const std::ptrdiff_t j = i + f.offset + k;
    rows[k] = source + (interior ? std::size_t(j) : reflect_index(j, ms, b)) * width;
    taps[k] = static_cast<T>(f.taps[std::size_t(k)]);
  }
  detail::run_filter_rows(rows, taps, nk, t, width, sign);
}

// Row i of lifting::detail::apply per column: target row i += sign * filtered source rows
// [0, ms) (mt: rows of the target wire). One row at a time lets a transform run its steps
// pipelined down the block (each row lifted while the rows it reads are still in cache).
template <class T>
[[gnu::always_inline]] inline void apply_row(const T* source, std::size_t ms, Boundary b, T* target,
                                             std::size_t mt, std::ptrdiff_t i, const Taps& f, T sign,
                                             std::size_t width) {
  const auto nk = static_cast<std::ptrdiff_t>(f.taps.size());
  const auto sm = static_cast<std::ptrdiff_t>(ms), tm = static_cast<std::ptrdiff_t>(mt);
  const std::ptrdiff_t lo = std::min(tm, std::max<std::ptrdiff_t>(0, -f.offset));
  const std::ptrdiff_t hi = std::max(lo, std::min(tm, sm - nk - f.offset + 1));
  T* t = target + std::size_t(i) * width;
  const bool interior = i >= lo && i < hi;
  if (nk == 2 && interior) {  // the two-tap interior form of detail::apply
    const T a0 = sign * static_cast<T>(f.taps[0]), a1 = sign * static_cast<T>(f.taps[1]);
    const T* s0 = source + std::size_t(i + f.offset) * width;
    const T* s1 = s0 + width;
    for (std::size_t c = 0; c < width; ++c) t[c] += a0 * s0[c] + a1 * s1[c];
    return;
  }
  // The general form (interior of longer filters, and boundary_sum near the ends).
  apply_row_general(source, ms, b, t, i, interior, f, sign, width);
}

// lifting::detail::apply per column: target rows [0, mt) += sign * filtered source rows [0, ms).
// Filters of other than two taps find the source row of every position they reach once (the
// rows table, reflected near the ends), so each target row is filter_rows over a window of it.
template <class T>
void apply(const T* source, std::size_t ms, Boundary b, T* target, std::size_t mt, const Taps& f, T sign,
           std::size_t width) {
  if (ms == 0 || mt == 0 || f.taps.empty()) return;
  const auto nk = static_cast<std::ptrdiff_t>(f.taps.size());
  if (nk == 2 || nk > detail::kMaxFastTaps) {
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(mt); ++i)
      apply_row(source, ms, b, target, mt, i, f, sign, width);
    return;
  }
  T taps[detail::kMaxFastTaps];
  for (std::ptrdiff_t k = 0; k < nk; ++k) taps[k] = static_cast<T>(f.taps[std::size_t(k)]);
  const std::size_t len = mt + std::size_t(nk) - 1;  // rows[q]: source row at index q + offset
  const T** rows = detail::extension_buffer<const T*>(len);
  for (std::size_t q = 0; q < len; ++q)
    rows[q] = source + reflect_index(std::ptrdiff_t(q) + f.offset, ms, b) * width;
  for (std::size_t i = 0; i < mt; ++i)
    detail::run_filter_rows(rows + i, taps, nk, target + i * width, width, sign);
}

template <class T>
void scale(T* rows, std::size_t count, double k) {
  const T kt = static_cast<T>(k);
  for (std::size_t i = 0; i < count; ++i) rows[i] *= kt;
}

template <class T>
void undo_scale(T* rows, std::size_t count, double k) {
  const T kt = static_cast<T>(k);
  for (std::size_t i = 0; i < count; ++i) rows[i] /= kt;
}

// lifting::lift_integer per column (two-tap filters; longer ones are not used in columns).
inline void lift_integer(const int32_t* source, std::size_t ms, Boundary b, int32_t* target, std::size_t mt,
                         const IntegerTaps& f, Direction dir, std::size_t width) {
  if (ms == 0 || mt == 0 || f.weights.size() != 2) return;
  const int32_t sign = dir == Direction::add ? 1 : -1;
  const int64_t w0 = f.weights[0], w1 = f.weights[1];
  for (std::size_t i = 0; i < mt; ++i) {
    const auto j = static_cast<std::ptrdiff_t>(i) + f.offset;
    const int32_t* s0 = source + reflect_index(j, ms, b) * width;
    const int32_t* s1 = source + reflect_index(j + 1, ms, b) * width;
    int32_t* t = target + i * width;
    // Sums in 64 bits, floor by arithmetic shift: detail::integer_term's value exactly.
    for (std::size_t c = 0; c < width; ++c)
      t[c] += sign * static_cast<int32_t>((w0 * s0[c] + w1 * s1[c] + f.bias) >> f.shift);
  }
}

}  // namespace pupwave::lifting::columns

// The inner loops of the generic lifting (lifting.h filter_run, lifting_columns.h filter_rows),
// compiled for the baseline instruction set and, on x86-64 with GCC or Clang, also for AVX2 (the
// loader picks the version the CPU runs: target_clones). AVX2 carries no FMA, and the sums are
// formed in the same order in every version, so the results are the same to the bit.
#include "transforms/lifting.h"
#include "transforms/lifting_columns.h"

#if defined(__x86_64__) && defined(__GNUC__) && defined(__ELF__) && \
    (!defined(__clang__) || __clang_major__ >= 14)
#define PUPWAVE_LIFTING_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define PUPWAVE_LIFTING_CLONES
#endif

namespace pupwave::lifting::detail {

PUPWAVE_LIFTING_CLONES void run_filter(const float* src, float* target, std::ptrdiff_t count,
                                       const float* taps, std::ptrdiff_t nk, float sign) {
  filter_run(src, target, count, taps, nk, sign);
}

PUPWAVE_LIFTING_CLONES void run_filter(const double* src, double* target, std::ptrdiff_t count,
                                       const double* taps, std::ptrdiff_t nk, double sign) {
  filter_run(src, target, count, taps, nk, sign);
}

PUPWAVE_LIFTING_CLONES void run_filter_rows(const float* const* rows, const float* taps, std::ptrdiff_t nk,
                                            float* t, std::size_t width, float sign) {
  columns::filter_rows(rows, taps, nk, t, width, sign);
}

PUPWAVE_LIFTING_CLONES void run_filter_rows(const double* const* rows, const double* taps, std::ptrdiff_t nk,
                                            double* t, std::size_t width, double sign) {
  columns::filter_rows(rows, taps, nk, t, width, sign);
}

}  // namespace pupwave::lifting::detail

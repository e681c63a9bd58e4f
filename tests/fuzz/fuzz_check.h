#pragma once
// Shared by the fuzz targets (docs/fuzzing.md): the decode limit they run under and the
// invariant check whose failure is a finding (abort, which libFuzzer and the corpus runner
// both report with the input).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>

#include "codec/format/decode_limits.h"

namespace pupwave::fuzz {

// Small enough that one input decodes in milliseconds; large enough for every seed.
inline constexpr DecodeLimits kFuzzLimits{std::size_t(1) << 20};

[[noreturn]] inline void invariant_failed(const char* what, const char* file, int line) {
  std::fprintf(stderr, "fuzz invariant violated at %s:%d: %s\n", file, line, what);
  std::abort();
}

inline std::span<const std::uint8_t> as_span(const std::uint8_t* data, std::size_t size) {
  return {data, size};
}

}  // namespace pupwave::fuzz

#define FUZZ_CHECK(cond) ((cond) ? void(0) : ::pupwave::fuzz::invariant_failed(#cond, __FILE__, __LINE__))

#pragma once
// The lossless context coder (`--entropy lc`, entropy coder 3 in docs/bitstream.md): one pass
// over a code-block's integer coefficients in raster order, each magnitude binarised as
// zero / bit length (unary) / two modelled mantissa bits / raw bits, every decision coded by the
// range coder with a two-rate adaptive probability in a context made from the magnitudes of the
// causal neighbours (W, N, NW, NE, WW, NN) and of the parent in the next coarser band of the
// same orientation (ECECOW-style context modelling). The coarse band (the whole image at 0
// levels, the lc default) is predicted by a self-correcting weighted predictor (after JPEG XL's
// modular mode) or the median edge detector of LOCO-I, and its residuals are coded the same way,
// with the residuals of earlier colour components at the same sample in the context. No
// truncation points: reversible (lossless) streams only.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "codec/entropy/bit_model.h"

namespace pupwave {

// Adaptive probability of a 0: the mean of a fast (settling at 1/64) and a slow (1/1024)
// estimate, both starting count-based (whole bands are one block, so the statistics are
// nearly stationary: on the test photographs these rates beat 1/16 and 1/128 by 1.1%).
struct LcModel {
  std::uint16_t fast = 16384, slow = 16384;
  std::uint16_t count = 0;

  std::uint32_t p0() const { return (std::uint32_t(fast) + slow + 1) >> 1; }
  void update(int bit) {
    const int warm = int(std::bit_width(unsigned(count) + 1u));
    step(fast, std::min(warm, 6), bit);
    step(slow, std::min(warm, 10), bit);
    if (count < 1023) ++count;
  }
  // p stays inside [1, 32767]: p >> s is 0 at p = 1 and (32768 - p) >> s is 0 at 32767.
  static void step(std::uint16_t& p, int shift, int bit) {
    p = std::uint16_t(bit ? p - (p >> shift) : p + ((kProbabilityOne - p) >> shift));
  }
};

// Activity contexts: 0 for all-zero neighbours, then two per octave of the weighted sum.
inline constexpr int kLcActivityContexts = 32;

// Context of a weighted neighbour-magnitude sum: 0, then two per octave, capped.
inline int lc_activity_context(std::uint32_t s) {
  if (s == 0) return 0;
  const int n = int(std::bit_width(s));
  const int q = n < 2 ? 1 : 2 * n - 2 + int((s >> (n - 2)) & 1u);
  return std::min(q, kLcActivityContexts - 1);
}

// The parent band of a detail block: the coefficients of the next coarser band of the same
// orientation, already decoded (coefficient (x, y) of the block's band has the parent
// (x / 2, y / 2), clamped to the parent band). Null `origin`: no parent.
struct LcParent {
  const std::int32_t* origin = nullptr;  // parent band sample (0, 0)
  std::size_t stride = 0;                // samples between parent rows
  std::size_t width = 0, height = 0;     // parent band extent
  std::size_t x0 = 0, y0 = 0;            // the block's position inside its own band
  // Coarse-band blocks of components after the first: the first component's block at the same
  // place (already decoded), whose MED residuals join the context. Null: none.
  const std::int32_t* guide = nullptr;
  std::size_t guide_stride = 0;
  // Components after the second: the previous component's block, a second guide. Null: none.
  const std::int32_t* guide2 = nullptr;
};

struct LcCodeword {
  int planes = 0;  // bit length of the largest coded magnitude (0: all zero, no bytes)
  std::vector<std::uint8_t> bytes;
};

// Codes `width` x `height` coefficients (x fastest). `low_pass`: the coarse band (MED
// prediction). Throws IndexRangeError for a coded magnitude of 2^kMaxBitPlanes or more.
LcCodeword lc_encode_block(std::span<const std::int32_t> values, std::size_t width, std::size_t height,
                           bool low_pass, const LcParent& parent);

// Decodes a codeword into `width` x `height` coefficients at `out` (row y at out + y * stride).
// Throws DecodeError unless the largest decoded magnitude has bit length `planes` and every
// value stays within 2^30.
void lc_decode_block(std::span<const std::uint8_t> codeword, std::size_t width, std::size_t height,
                     bool low_pass, const LcParent& parent, int planes, std::int32_t* out,
                     std::size_t stride);

}  // namespace pupwave

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

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pupwave {

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

#pragma once
// Decoding of entropy coder 4 (the parent-context coefficient coder, codec/entropy/pc_blocks.h):
// its blocks read the decoded integer indices of their parent band, so they are decoded one
// resolution at a time into index planes and dequantized afterwards (docs/bitstream.md).

#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/entropy/pc_blocks.h"
#include "codec/image/image_stream.h"
#include "transforms/executor.h"

namespace pupwave {

// sign(q) x (|q| + delta) x step for q != 0, 0 for q = 0: the pc coder's dequantisation, shared
// by the decoder and the encoder's PSNR so both give the same floats.
inline float pc_dequantize(std::int32_t q, float step, float delta) {
  if (q == 0) return 0.0f;
  const float r = (float(q < 0 ? -std::int64_t(q) : q) + delta) * step;
  return q < 0 ? -r : r;
}

// Block b of the index plane `index` dequantized into `plane` (both `stride` samples a row, b at
// its offset in each): the encoder's PSNR; the decoder dequantizes in place with the same
// pc_dequantize, so both give the same floats.
void pc_dequantize_block(const CodeBlock& b, const std::int32_t* index, float* plane, std::size_t stride,
                         float step, float delta);

// Adds block b's chroma-from-luma prediction (pc_cfl.h) to its dequantized residual in `plane`,
// from the decoded luma `first` and Cb `second` planes (all `stride` samples a row): the decoder's
// and the encoder's PSNR's, one expression for both.
void pc_add_prediction(const CodeBlock& b, const PcCfl& k, const float* first, const float* second,
                       float* plane, std::size_t stride);

// Decodes every block of the read resolutions of a pc stream (planes[c]: `region`-sized and
// zeroed, the low corner of the Mallat layout) and dequantizes them into the planes: the
// planes hold the indices until their children are decoded, so no other planes are needed.
void decode_pc_into(const ParsedStream& s, const Extent& region, const Executor& ex,
                    const std::vector<float*>& planes);

}  // namespace pupwave

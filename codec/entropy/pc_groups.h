#pragma once
// The pc coder's decode groups (docs/bitstream.md, "Parent-context coefficient coder"): a block
// reads its parent band (one resolution coarser) and, for the second and third of three or more
// components, the co-located indices of the first component (luma after the ICT), so the blocks
// of one resolution are coded in two groups, the first component's (and any fourth's) before
// the other two. Encoder and decoder both order by pc_group, so their contexts agree.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/entropy/codeblocks.h"
#include "codec/entropy/pc_blocks.h"

namespace pupwave {

// Whether block b (of an image with `components` components) takes the first component as a
// second parent.
inline bool pc_has_luma(const CodeBlock& b, std::size_t components) {
  return components >= 3 && (b.component == 1 || b.component == 2);
}

// The group of block b: 2 x resolution, + 1 for a block with a luma parent.
inline int pc_group(const CodeBlock& b, std::size_t components) {
  return 2 * b.resolution + (pc_has_luma(b, components) ? 1 : 0);
}

// Block b's luma parent in the index planes (rows of `stride` samples), or none.
inline PcLuma pc_luma(const CodeBlock& b, const std::vector<std::vector<std::int32_t>>& planes,
                      std::size_t stride) {
  if (!pc_has_luma(b, planes.size())) return {};
  return {planes[0].data() + b.offset[0] + stride * b.offset[1], stride};
}

}  // namespace pupwave

#pragma once
// The pc coder's decode groups (docs/bitstream.md, "Parent-context coefficient coder"): a block
// reads its parent band (one resolution coarser) and, for the second and third of three or more
// components, the co-located indices of the first component (luma after the ICT) and, for the
// third, those of the second (Cb for Cr), so the blocks of one resolution are coded in three
// groups: the first component's (and any from the fourth on), the second's, the third's.
// Encoder and decoder both order by pc_group, so their contexts agree.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/entropy/codeblocks.h"
#include "codec/entropy/pc_blocks.h"

namespace pupwave {

// Number of groups a resolution has.
inline constexpr int kPcGroupsPerResolution = 3;

// Whether block b (of an image with `components` components) takes the first component (and,
// for the third, the second) as further parents.
inline bool pc_has_luma(std::size_t component, std::size_t components) {
  return components >= 3 && (component == 1 || component == 2);
}
inline bool pc_has_luma(const CodeBlock& b, std::size_t components) {
  return pc_has_luma(b.component, components);
}

// The group of block b: 3 x resolution, + its component for a block with a luma parent.
inline int pc_group(const CodeBlock& b, std::size_t components) {
  return kPcGroupsPerResolution * b.resolution + (pc_has_luma(b, components) ? int(b.component) : 0);
}

// Block b's luma (and Cb) parents, the first and second components' index planes being `first`
// and `second` (rows of `stride` samples), or none.
inline PcLuma pc_luma(const CodeBlock& b, std::size_t components, const std::int32_t* first,
                      const std::int32_t* second, std::size_t stride) {
  if (!pc_has_luma(b, components)) return {};
  const std::size_t at = b.offset[0] + stride * b.offset[1];
  return {first + at, stride, b.component == 2 ? second + at : nullptr};
}

inline PcLuma pc_luma(const CodeBlock& b, const std::vector<std::vector<std::int32_t>>& planes,
                      std::size_t stride) {
  if (!pc_has_luma(b, planes.size())) return {};
  return pc_luma(b, planes.size(), planes[0].data(), planes[1].data(), stride);
}

}  // namespace pupwave

#pragma once
// Where the lc coder (codec/entropy/lc_blocks.h) finds a block's parent band: the band one
// level coarser with the same orientation, in the component's in-place (Mallat) array. The
// encoder and the decoder both use it, so their contexts agree.

#include <cstdint>
#include <vector>

#include "codec/entropy/codeblocks.h"
#include "codec/entropy/lc_blocks.h"
#include "transforms/subband.h"

namespace pupwave {

// The parent of block `b` in `plane` (rows of `stride` samples), or none (the coarse band, the
// coarsest detail bands, an empty parent band); for a coarse-band block of a component after
// the first, the guides: the same block in `first_plane` (the first component's plane) and,
// after the second, in `previous_plane` (the previous component's).
inline LcParent lc_parent(const std::vector<Subband>& bands, const CodeBlock& b, const std::int32_t* plane,
                          std::size_t stride, const std::int32_t* first_plane,
                          const std::int32_t* previous_plane = nullptr) {
  const Subband& own = bands[b.band];
  if (own.orientation == 0) {
    LcParent g;
    if (b.component > 0 && first_plane) {
      g.guide = first_plane + b.offset[0] + stride * b.offset[1];
      g.guide_stride = stride;
    }
    if (b.component > 1 && previous_plane) g.guide2 = previous_plane + b.offset[0] + stride * b.offset[1];
    return g;
  }
  for (const Subband& p : bands) {
    if (p.level != own.level + 1 || p.orientation != own.orientation || p.count() == 0) continue;
    return {plane + p.offset[0] + stride * p.offset[1],
            stride,
            p.size[0],
            p.size[1],
            b.offset[0] - own.offset[0],
            b.offset[1] - own.offset[1]};
  }
  return {};
}

}  // namespace pupwave

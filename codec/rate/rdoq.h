#pragma once
// Rate-distortion optimised quantisation for the bit-plane coder, encoder only: once PCRD has
// chosen where each block is cut, a coefficient that would become significant alone in the
// last coded bit-plane (no neighbour significant there) costs a significance decision in a
// low-probability context and a sign for little distortion removed. Where that distortion
// is below lambda times its estimated rate, it is pulled just under the plane, so the block
// codes it one plane later (or never) and the bytes go where the slope is steeper.

#include <cstddef>
#include <span>

#include "transforms/subband.h"

namespace pupwave {

// Bit-plane of the last cleanup pass among the first `passes` of a block with `planes`
// planes (the top plane has a cleanup pass only, every other plane significance, refinement
// and cleanup); -1 when no cleanup pass is coded.
int last_cleanup_plane(int planes, int passes);

// Pulls below 2^plane every magnitude (index units) in [2^plane, 2^(plane+1)) whose 8
// neighbours in its slice are all below 2^plane and whose distortion removal, reconstructed
// at offset delta, is under `max_gain` (index units squared). Returns how many it changed.
std::size_t pull_isolated(std::span<float> magnitude, const Extent& size, int plane, double delta,
                          double max_gain);

}  // namespace pupwave

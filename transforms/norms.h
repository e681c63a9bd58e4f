#pragma once
// L2 norms of the synthesis basis functions of every subband, for any transform, so the
// quantizer can weight subbands (step_b = base / norm_b) even for non-orthogonal banks.

#include <vector>

#include "transforms/subband.h"
#include "transforms/transform1d.h"

namespace pupwave {

// Norms aligned with subbands(dims, levels): entry b is the L2 norm of the inverse transform
// (double precision) of a unit impulse in the middle of subband b.
//
// Computed as a product of 1-D norms, one per transformed axis. This is exact, not an
// approximation: the impulse is a tensor product of 1-D impulses, every engine pass applies
// the same 1-D synthesis to all lines of a box that contains the current support, so the
// response is the tensor product of the 1-D responses and its L2 norm the product of theirs.
//
// Results are cached per (t.spec(), dims, levels) in a thread-safe cache, so t.spec() must
// identify the transform uniquely. Throws std::invalid_argument like subbands().
std::vector<double> synthesis_norms(const Transform1D& t, const Extent& dims, int levels);

// 1-D building block: norms of a line of n samples, in the order of
// subbands({n, 1, 1}, levels) (coarse band first, then details from level `levels` to 1).
std::vector<double> synthesis_norms_1d(const Transform1D& t, std::size_t n, int levels);

}  // namespace pupwave

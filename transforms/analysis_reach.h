#pragma once
// How far the analysis of a 1-D transform reads around a sample, for strip-wise (line-based)
// forward transforms: windowed analysis gives the whole line's coefficients, bit for bit,
// wherever the window holds every sample a coefficient depends on.

#include <cstddef>

#include "transforms/transform1d.h"

namespace pupwave {

// Largest distance (in samples of the line, coefficients at their interleaved positions:
// coarse j at 2j, detail j at 2j + 1) between a sample and a coefficient that depends on it.
// Found by analysing lines holding one NaN (NaN reaches every coefficient computed from it),
// on two line lengths; 0 when analysis is not local (the reach grows with the line, as for a
// solve along the whole line) or reaches beyond 32 samples (windows would mostly overlap).
std::size_t analysis_reach(const Transform1D& t);

}  // namespace pupwave

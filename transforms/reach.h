#pragma once
// How far a 1-D transform reads around a sample, for strip-wise (line-based) transforms: a
// windowed analysis or synthesis gives the whole line's values, bit for bit, wherever the window
// holds every sample a value depends on. Both are found by transforming lines holding one NaN
// (NaN reaches every value computed from it), on two line lengths; 0 when the transform is not
// local (the reach grows with the line, as for a solve along the whole line) or reaches beyond 32
// samples (windows would mostly overlap), in which case callers transform whole lines.

#include <cstddef>

#include "transforms/transform1d.h"

namespace pupwave {

// Largest distance (in samples of the line, coefficients at their interleaved positions:
// coarse j at 2j, detail j at 2j + 1) between a sample and a coefficient that depends on it.
std::size_t analysis_reach(const Transform1D& t);

// Largest distance between a coefficient (at its interleaved position) and an output sample
// that depends on it.
std::size_t synthesis_reach(const Transform1D& t);

}  // namespace pupwave

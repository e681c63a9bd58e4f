#pragma once
// The wavelet low pass that makes each level of `pupwave lod` (tools/lod_pyramid.h), measured in
// the CLI; kept apart from the OpenVDB code, which lives in the module loaded for .vdb files.

#include <vector>

#include "transforms/transform1d.h"

namespace pupwave::cli {

// What lies beyond a grid's data (--edge): background for sparse grids (their outside is
// background), whole-sample symmetric reflection at the active box for dense grids; automatic
// judges by the faces of the active box (kDenseFaceFill in tools/vdb/lod_pyramid.cpp).
enum class LodEdge { automatic, symmetric, background };

// The analysis low pass of a linear, shift-invariant 1-D transform: in the interior of a line x,
// coarse sample c is sum over d in [-radius, radius] of taps[d + radius] * x[2c + d]. gain is its
// response to a constant (the sum of the taps), by which levels are normalised.
struct LowPass {
  int radius = 0;
  std::vector<double> taps;
  double gain = 1.0;
};

// Measures the low pass of t from impulse responses and checks it against a random line; throws
// std::runtime_error for transforms that are not a linear filter bank with a usable gain.
LowPass low_pass_of(const Transform1D& t);

}  // namespace pupwave::cli

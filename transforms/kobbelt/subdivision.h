#pragma once
// Variational subdivision of 2-D polylines on its own (the wavelet synthesis with zero
// details): each level keeps the old points and inserts one new point per edge, placed so
// the scheme's fairness energy is minimal (Kobbelt-Schroder, Section 1.1).

#include <cstddef>
#include <span>
#include <vector>

#include "transforms/kobbelt/variational.h"

namespace pupwave::kobbelt {

struct Point2 {
  double x = 0.0;
  double y = 0.0;
};

enum class Parameterization {
  uniform,      // t_{i+1} - t_i = 1
  centripetal,  // t_{i+1} - t_i = sqrt(|p_{i+1} - p_i|) (Lee 1989); K2 and K3 only
};

struct SubdivisionOptions {
  Scheme scheme = Scheme::k2;
  int levels = 1;       // 0 .. kMaxSubdivisionLevels
  bool closed = false;  // closed polygon: the last point connects back to the first
  Parameterization parameterization = Parameterization::uniform;
};

inline constexpr int kMaxSubdivisionLevels = 12;

// Refines `points` `levels` times. An open polyline of n points becomes 2^L (n - 1) + 1
// points, a closed one 2^L n. New parameter values are edge midpoints at every level
// (Section 1.1). Throws std::invalid_argument for fewer than 2 points, levels outside
// 0 .. 12, non-finite coordinates, centripetal parameters with coincident consecutive
// points, or centripetal parameters for a scheme other than K2 and K3.
std::vector<Point2> subdivide(std::span<const Point2> points, const SubdivisionOptions& options);

// One uniform refinement step of scalar samples on an open line: returns 2 n - 1 samples
// whose even ones are `coarse` (for tests and 1-D use).
std::vector<double> refine_open(Scheme scheme, std::span<const double> coarse);

}  // namespace pupwave::kobbelt

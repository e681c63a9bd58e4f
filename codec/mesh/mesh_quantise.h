#pragma once
// The quantised form of a multiresolution (internal to codec/mesh): integer grid indices of
// the coarsest points and of every level's details, and the dequantised multiresolution the
// encoder verifies and the decoder reconstructs from, computed by the same code.

#include <cstdint>
#include <vector>

#include "transforms/sqrt3/hierarchy.h"

namespace pupwave::mesh {

struct QuantisedLevels {
  std::vector<std::int64_t> coarsest;             // 3 per point, round(c / coarse_step)
  std::vector<std::vector<std::int64_t>> levels;  // 3 per detail, round(d / steps[level])
};

// Throws std::invalid_argument if a value does not fit kMaxQuantised.
QuantisedLevels quantise(const sqrt3::Multiresolution& mr, const std::vector<double>& steps,
                         double coarse_step);

// Multiresolution with points q * coarse_step and details q * steps[level], faces and kinds
// as given.
sqrt3::Multiresolution dequantise(const QuantisedLevels& q, const std::vector<sqrt3::Face>& coarsest_faces,
                                  const std::vector<sqrt3::StepKind>& kinds, const std::vector<double>& steps,
                                  double coarse_step);

// Coarsest points are coded as differences to the previous point (per axis).
std::vector<std::int64_t> delta_encode(const std::vector<std::int64_t>& v);
std::vector<std::int64_t> delta_decode(const std::vector<std::int64_t>& v);

}  // namespace pupwave::mesh

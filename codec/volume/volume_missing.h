#pragma once
// Internal to the volume encoder: missing values of dense grids (NaN, infinities and a caller's
// fill value, as ocean and climate fields mark land). A grid with any is coded as a sparse box
// whose inactive voxels are the missing ones (kept exactly in its MASK chunk); before the
// transform they are filled smoothly from the valid voxels of their brick, so they cost little
// and never pull the valid voxels' coefficients.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "codec/volume/volume_view.h"

namespace pupwave {

// Whether a value is missing: NaN, an infinity, or equal to the fill value.
inline bool is_missing(double v, const std::optional<double>& fill) {
  return !std::isfinite(v) || (fill.has_value() && v == *fill);
}

// The valid-voxel mask of a dense view (1 valid, 0 missing), laid out as VolumeView::active
// needs it (one byte per element at the view's element offsets) in `bytes`; returns the pointer
// to give as the view's `active`.
const std::uint8_t* missing_value_mask(const VolumeView& view, const std::optional<double>& fill,
                                       std::vector<std::uint8_t>& bytes);

// Replaces the missing voxels (active[i] == 0) of a brick of extent `size`, x fastest, with a
// smooth fill from its valid ones: pull-push averages over a pyramid of 2x2x2 cells, then a few
// sweeps of the 6-neighbour mean, so the fill meets the valid voxels without a step. A brick
// with no valid voxel is set to 0. S: std::uint8_t, std::uint16_t, float or double.
template <class S>
void fill_missing(std::vector<S>& samples, const std::vector<std::uint8_t>& active, const Extent& size);

}  // namespace pupwave

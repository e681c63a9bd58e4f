#pragma once
// Internal to the library, the CLI and the chunk codecs (not installed): the one place where the
// public volume options (api::VolumeOptions) become the encoder's, so every front door (C++ and
// C APIs, Python, the CLI, the HDF5 filter and numcodecs) codes the same grids and options to the
// same bytes.

#include <span>
#include <vector>

#include "codec/volume/volume_codec.h"
#include "pupwave/pupwave.hpp"

namespace pupwave::api {

// The fraction of the value range that bounds every voxel's error when no target is given for
// float data (VolumeRate::automatic).
inline constexpr double kDefaultRelativeError = 1e-3;

struct ResolvedVolumeOptions {
  VolumeEncodeOptions encode;
  // The value range a relative bound was scaled by (1 for every other target): a max_error
  // stream's error in the caller's unit is its max_error / error_unit.
  double error_unit = 1.0;
};

// The encoder's options for `options` on the grids `grids` (with `views` as encode_volumes takes
// them): rate mode and target (automatic: lossless when every grid holds integers, else a bound
// of kDefaultRelativeError of the range; max_error_rel: the target times the range, the largest
// over the grids, 1 when the data is constant), transform (kMaxErrorVolumeTransform for error
// bounds, cdf53 for lossless, else cdf97), levels and brick. The range is read only for a
// relative bound. Callers add the executor. Throws Error for a target or levels out of range.
ResolvedVolumeOptions resolve_volume_options(const VolumeOptions& options,
                                             const std::vector<VolumeGrid>& grids,
                                             std::span<const pupwave::VolumeView> views);

}  // namespace pupwave::api

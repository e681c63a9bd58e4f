// The public volume options resolved into the encoder's (api_volume_options.h).
#include "codec/api/api_volume_options.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "codec/api/api_errors.h"

namespace pupwave::api {
namespace {

// Widens [lo, hi] by the active voxels of a box that are not missing (one typed pass, summarize_values).
void widen(const pupwave::VolumeView& v, double& lo, double& hi, const std::optional<double>& fill = {}) {
  const ValueSummary s = summarize_values(v, v.is_sparse() ? std::nullopt : fill);
  lo = std::min(lo, s.lo), hi = std::max(hi, s.hi);
}

bool all_integer(const std::vector<VolumeGrid>& grids) {
  return std::all_of(grids.begin(), grids.end(),
                     [](const VolumeGrid& g) { return is_integer(g.volume.type); });
}

// The rate the rule codes: automatic made explicit for the data at hand.
VolumeRate effective_rate(VolumeRate rate, const std::vector<VolumeGrid>& grids) {
  if (rate != VolumeRate::automatic) return rate;
  return all_integer(grids) ? VolumeRate::lossless : VolumeRate::max_error_rel;
}

VolumeRateMode encoder_mode(VolumeRate rate) {
  switch (rate) {
    case VolumeRate::max_error:
    case VolumeRate::max_error_rel: return VolumeRateMode::max_error;
    case VolumeRate::bpv: return VolumeRateMode::bpv;
    case VolumeRate::psnr: return VolumeRateMode::psnr;
    case VolumeRate::step: return VolumeRateMode::step;
    case VolumeRate::lossless: return VolumeRateMode::lossless;
    case VolumeRate::automatic: break;
  }
  detail::fail("unknown volume rate mode " + std::to_string(int(rate)));
}

const char* default_transform(VolumeRateMode mode) {
  switch (mode) {
    case VolumeRateMode::lossless: return "cdf53";
    case VolumeRateMode::max_error: return kMaxErrorVolumeTransform;
    default: return "cdf97";
  }
}

// The largest value range (max - min of the active voxels not missing, active tiles included) over the grids;
// 0 when every grid is constant or has no active voxel.
double largest_range(const std::vector<VolumeGrid>& grids, std::span<const pupwave::VolumeView> views,
                     const std::optional<double>& fill) {
  double range = 0.0;
  for (std::size_t i = 0; i < grids.size(); ++i) {
    const VolumeGrid& g = grids[i];
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    if (i < views.size() && views[i].data != nullptr)
      widen(views[i], lo, hi, fill);
    else if (!g.is_blocked() && !g.is_opaque())
      widen(view_of(g.volume), lo, hi, fill);
    for (const VolumeBlock& b : g.blocks) widen(view_of(b.volume), lo, hi);
    for (const VolumeTile& t : g.tiles)
      if (t.active) lo = std::min(lo, t.value), hi = std::max(hi, t.value);
    if (hi > lo) range = std::max(range, hi - lo);
  }
  return range;
}

}  // namespace

ResolvedVolumeOptions resolve_volume_options(const VolumeOptions& options,
                                             const std::vector<VolumeGrid>& grids,
                                             std::span<const pupwave::VolumeView> views) {
  const bool given = options.rate != VolumeRate::automatic && options.rate != VolumeRate::lossless;
  if (given && !(options.target > 0.0 && std::isfinite(options.target)))
    detail::fail("rate target must be a positive finite number, got " + std::to_string(options.target));
  if (options.levels < -1 || options.levels > 32)
    detail::fail("levels must be -1 (default) or 0..32, got " + std::to_string(options.levels));
  const VolumeRate rate = effective_rate(options.rate, grids);
  ResolvedVolumeOptions out;
  VolumeEncodeOptions& enc = out.encode;
  enc.mode = encoder_mode(rate);
  if (rate == VolumeRate::max_error_rel) {
    const double range = largest_range(grids, views, options.fill_value);
    out.error_unit = range > 0.0 ? range : 1.0;
    const double fraction = options.rate == VolumeRate::automatic ? kDefaultRelativeError : options.target;
    enc.target = fraction * out.error_unit;
  } else if (rate != VolumeRate::lossless) {
    enc.target = options.target;
  }
  enc.transform = !options.transform.empty() ? options.transform : default_transform(enc.mode);
  enc.levels = options.levels;
  enc.brick = options.brick;
  enc.fill_value = options.fill_value;
  return out;
}

}  // namespace pupwave::api

#pragma once
// A rate-distortion proxy measured on an image plane, for design searches: the plane is
// transformed (separable, all levels), every subband is quantized by a dead-zone uniform
// quantizer with step base / (synthesis norm of the band), as the codec does, the rate is the
// zeroth-order entropy of the indices of each band, and the distortion is measured on the
// reconstructed plane (rounded and clamped to 8 bits). It ignores the codec's context
// modelling and rate control, and ranks filter banks as `pupwave bench rd` does (docs/pups.md).

#include <vector>

#include "transforms/subband.h"
#include "transforms/transform1d.h"

namespace pupwave::merit {

struct RdProxyPoint {
  double bits_per_sample = 0;
  double psnr_db = 0;  // peak 255
};

// One point per base step (in 8-bit sample units); `plane` holds dims[0] x dims[1] samples
// in [0, 255], levels >= 0 (0 = no transform). delta: reconstruction offset of non-zero
// indices in steps (the codec's default is 0.4375). Throws std::invalid_argument for an
// empty or mismatched plane or a non-positive step.
std::vector<RdProxyPoint> rd_proxy_curve(const Transform1D& t, const std::vector<float>& plane, const Extent& dims,
                                         int levels, const std::vector<double>& base_steps, double delta = 0.4375);

// The base steps used by `pupwave filters search --objective images`: 0.5 to 32, about
// 0.1 to 3 bits per sample on photographs.
std::vector<double> default_proxy_steps();

}  // namespace pupwave::merit

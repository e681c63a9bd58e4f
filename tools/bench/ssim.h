#pragma once
// Structural similarity of a decoded image against its original, on luma (Rec. 601,
// Y = 0.299 R + 0.587 G + 0.114 B, unrounded, as psnr_luma; the grey channel of grey images):
//
// - SSIM: Z. Wang, A. C. Bovik, H. R. Sheikh, E. P. Simoncelli, "Image quality assessment: from
//   error visibility to structural similarity", IEEE Trans. Image Processing 13(4), 2004.
//   11x11 Gaussian window (sigma 1.5, normalised to sum 1), K1 = 0.01, K2 = 0.03, L = 255; the
//   mean of the SSIM map over the window positions that lie wholly inside the image.
// - MS-SSIM: Z. Wang, E. P. Simoncelli, A. C. Bovik, "Multi-scale structural similarity for
//   image quality assessment", 37th Asilomar Conference, 2003. Five scales with weights 0.0448,
//   0.2856, 0.3001, 0.2363, 0.1333, 2x2 average downsampling between scales (an odd last row or
//   column is dropped); the mean contrast-structure term at every scale but the coarsest, and
//   the mean SSIM (luminance times contrast-structure) at the coarsest. A negative mean
//   contrast-structure term counts as 0 (its fractional power would be undefined).
//   An image whose smaller side is under 176 pixels (5 scales of an 11-pixel window) gets the
//   scales that fit, with their weights renormalised to sum 1 (with all five, the published
//   weights are used as they are).
//
// Both are NaN when the image is smaller than one 11x11 window.

#include "codec/image/image.h"

namespace pupwave::bench {

// SSIM of `test` against `reference` (same width, height and channel count, 1 or 3 channels,
// samples on a 0..255 scale; std::invalid_argument otherwise).
double ssim(const Image& reference, const Image& test);

// MS-SSIM of `test` against `reference`, same requirements as ssim().
double ms_ssim(const Image& reference, const Image& test);

}  // namespace pupwave::bench

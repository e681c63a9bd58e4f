#pragma once
// Bjontegaard delta metrics (VCEG-M33): the average PSNR gap and the average rate gap between
// two rate-distortion curves over the range where both are measured.

#include <vector>

namespace pupwave::bench {

// One measured point of a rate-distortion curve.
struct RdPoint {
  double bpp = 0.0;   // achieved bits per pixel (> 0)
  double psnr = 0.0;  // quality in dB (finite): PSNR, or MS-SSIM as -10 log10(1 - MS-SSIM)
};

// Average PSNR difference in dB of `test` over `anchor` (positive = test is better), over the
// overlap of their log10(bpp) ranges. Each curve is fitted by a least-squares polynomial in
// log10(bpp) of degree min(3, points - 1), as in VCEG-M33. Points with non-finite or
// non-positive values are ignored. NaN when a curve has fewer than two distinct rates or the
// ranges do not overlap.
double bd_psnr(const std::vector<RdPoint>& anchor, const std::vector<RdPoint>& test);

// Average rate difference in percent of `test` against `anchor` at equal PSNR (negative =
// test needs fewer bits), over the overlap of their PSNR ranges: log10(bpp) fitted as a
// polynomial in PSNR (same degree rule), mean log difference d, result (10^d - 1) * 100.
// NaN under the same conditions as bd_psnr.
double bd_rate(const std::vector<RdPoint>& anchor, const std::vector<RdPoint>& test);

}  // namespace pupwave::bench
